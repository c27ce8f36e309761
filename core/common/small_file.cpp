#include "common/small_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace gc {

namespace {

std::string kind_of(mode_t mode)
{
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

std::string limit_text(std::size_t max_bytes) { return std::to_string(max_bytes) + " bytes"; }

// Closes the descriptor on every way out.
struct Descriptor {
    int fd;
    ~Descriptor() { ::close(fd); }
};

}  // namespace

std::string read_small_file(const std::string& path, std::size_t max_bytes)
{
    // O_NONBLOCK: opening a FIFO without a writer would otherwise wait for one forever.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) throw SmallFileError(std::string("cannot be opened for reading: ") + std::strerror(errno));
    const Descriptor guard{fd};
    struct stat st {};
    if (::fstat(fd, &st) != 0) throw SmallFileError(std::string("cannot be examined: ") + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) throw SmallFileError("is " + kind_of(st.st_mode) + ", not a regular file");
    if (static_cast<unsigned long long>(st.st_size) > max_bytes)
        throw SmallFileError("is " + std::to_string(st.st_size) + " bytes, more than the limit of " +
                             limit_text(max_bytes));
    std::string content(max_bytes + 1, '\0');
    std::size_t size = 0;
    while (size < content.size()) {
        const ssize_t n = ::read(fd, content.data() + size, content.size() - size);
        if (n == 0) break;
        if (n < 0) {
            if (errno == EINTR) continue;
            throw SmallFileError(std::string("read error: ") + std::strerror(errno));
        }
        size += static_cast<std::size_t>(n);
    }
    if (size > max_bytes)
        throw SmallFileError("grew beyond the limit of " + limit_text(max_bytes) + " while it was read");
    content.resize(size);
    return content;
}

}  // namespace gc
