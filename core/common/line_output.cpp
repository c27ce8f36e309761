#include "common/line_output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

namespace gc {

namespace {

bool is_regular(int fd)
{
    struct stat st {};
    return ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
}

}  // namespace

LineOutput::LineOutput(int fd, std::string name, bool owned, bool regular)
    : fd_(fd), name_(std::move(name)), owned_(owned), regular_(regular)
{
}

LineOutput LineOutput::create(const std::string& path)
{
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOCTTY, 0666);
    if (fd < 0) throw OutputError("cannot open '" + path + "' for writing: " + std::strerror(errno));
    return LineOutput(fd, "'" + path + "'", true, is_regular(fd));
}

LineOutput LineOutput::standard_output()
{
    return LineOutput(STDOUT_FILENO, "standard output", false, is_regular(STDOUT_FILENO));
}

LineOutput::LineOutput(LineOutput&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), name_(std::move(other.name_)), owned_(other.owned_), regular_(other.regular_),
      committed_(other.committed_)
{
}

LineOutput& LineOutput::operator=(LineOutput&& other) noexcept
{
    if (this != &other) {
        if (owned_ && fd_ >= 0) ::close(fd_);
        fd_ = std::exchange(other.fd_, -1);
        name_ = std::move(other.name_);
        owned_ = other.owned_;
        regular_ = other.regular_;
        committed_ = other.committed_;
    }
    return *this;
}

LineOutput::~LineOutput()
{
    if (owned_ && fd_ >= 0) ::close(fd_);
}

void LineOutput::fail(const char* action, int error) const
{
    throw OutputError("cannot " + std::string(action) + " " + name_ + ": " + std::strerror(error));
}

void LineOutput::write_line(std::string_view line)
{
    if (fd_ < 0) throw OutputError("cannot write to " + name_ + ": already closed");
    std::size_t done = 0;
    // One call writes the whole line; the loop only finishes a write a signal cut short.
    while (done < line.size()) {
        const ssize_t n = ::write(fd_, line.data() + done, line.size() - done);
        if (n > 0) {
            done += static_cast<std::size_t>(n);
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        const int error = n < 0 ? errno : ENOSPC;
        const bool cut_back = regular_ && done > 0 && ::ftruncate(fd_, committed_) == 0;
        fail(cut_back ? "write a whole line to" : "write to", error);
    }
    committed_ += static_cast<long long>(line.size());
}

void LineOutput::close()
{
    const int fd = std::exchange(fd_, -1);
    if (!owned_ || fd < 0) return;
    if (::close(fd) != 0 && errno != EINTR) fail("close", errno);
}

}  // namespace gc
