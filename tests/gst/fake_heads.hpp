// Heads that do not behave, for the element tests: one that accepts and never answers, one
// that answers garbage, and an address where nothing listens. Loopback only.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace gc::test {

// A listening socket on 127.0.0.1 and a free port.
inline int listen_loopback(std::uint16_t& port)
{
    const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) throw std::runtime_error("socket");
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof addr;
    if (bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 || listen(fd, 16) != 0 ||
        getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
        close(fd);
        throw std::runtime_error("bind/listen on 127.0.0.1");
    }
    port = ntohs(addr.sin_port);
    return fd;
}

// A port on 127.0.0.1 where nothing listens (bound once, then closed).
inline std::uint16_t closed_port()
{
    std::uint16_t port = 0;
    close(listen_loopback(port));
    return port;
}

// Accepts every connection; reads and drops what comes; answers nothing (silent) or a
// stream of garbage lines (garbage).
class MisbehavingHead {
public:
    enum class Kind { Silent, Garbage };
    explicit MisbehavingHead(Kind kind) : kind_(kind), listener_(listen_loopback(port_))
    {
        thread_ = std::thread([this] { run(); });
    }
    ~MisbehavingHead()
    {
        stop_ = true;
        thread_.join();
        for (int fd : clients_) close(fd);
        close(listener_);
    }
    MisbehavingHead(const MisbehavingHead&) = delete;
    MisbehavingHead& operator=(const MisbehavingHead&) = delete;

    std::string uri() const { return "tcp://127.0.0.1:" + std::to_string(port_); }
    int accepted() const { return accepted_; }

private:
    void run()
    {
        static const char junk[] = "GCHP/9 \x01\x02 not a greeting\r\nOK pan=banana\n\n\xff\xfe ERR\n";
        while (!stop_) {
            std::vector<pollfd> fds{{listener_, POLLIN, 0}};
            for (int fd : clients_) fds.push_back({fd, POLLIN, 0});
            if (poll(fds.data(), fds.size(), 20) < 0) continue;
            if (fds[0].revents & POLLIN) {
                const int fd = accept4(listener_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
                if (fd >= 0) clients_.push_back(fd), ++accepted_;
            }
            for (std::size_t i = 1; i < fds.size(); ++i) {
                char buffer[512];
                if ((fds[i].revents & POLLIN) && read(fds[i].fd, buffer, sizeof buffer) == 0) {
                    close(fds[i].fd);
                    std::erase(clients_, fds[i].fd);
                    continue;
                }
                if (kind_ == Kind::Garbage) (void)send(fds[i].fd, junk, sizeof junk - 1, MSG_NOSIGNAL);
            }
        }
    }

    Kind kind_;
    std::uint16_t port_ = 0;
    int listener_;
    std::vector<int> clients_;
    std::atomic<bool> stop_{false};
    std::atomic<int> accepted_{0};
    std::thread thread_;
};

}  // namespace gc::test
