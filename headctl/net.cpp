#include "headctl/net.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>

namespace gc::headctl::net {

namespace {

thread_local const std::atomic<bool>* t_cancel = nullptr;
constexpr long long kCancelCheckMs = 20;

int poll_timeout_ms(Clock::time_point deadline)
{
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now()).count();
    return static_cast<int>(std::clamp<long long>(left, 0, t_cancel ? kCancelCheckMs : 60'000));
}

// Waits for events on fd; false on timeout.
bool wait_for(int fd, short events, Clock::time_point deadline)
{
    for (;;) {
        if (t_cancel && t_cancel->load()) throw NetError("cancelled");
        pollfd p{fd, events, 0};
        const int n = ::poll(&p, 1, poll_timeout_ms(deadline));
        if (n > 0) return true;
        if (n == 0) {
            if (Clock::now() >= deadline) return false;
            continue;
        }
        if (errno != EINTR) throw NetError(std::string("poll: ") + std::strerror(errno));
    }
}

std::string errno_text(const char* what) { return std::string(what) + ": " + std::strerror(errno); }

}  // namespace

CancelScope::CancelScope(const std::atomic<bool>& flag) : previous_(t_cancel) { t_cancel = &flag; }
CancelScope::~CancelScope() { t_cancel = previous_; }

bool cancel_requested() { return t_cancel && t_cancel->load(); }

Fd& Fd::operator=(Fd&& o) noexcept
{
    if (this != &o) {
        reset();
        fd_ = o.release();
    }
    return *this;
}

int Fd::release()
{
    const int fd = fd_;
    fd_ = -1;
    return fd;
}

void Fd::reset()
{
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
}

void set_nonblocking(int fd)
{
    const int flags = ::fcntl(fd, F_GETFL, 0);
    if (flags < 0 || ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0) throw NetError(errno_text("fcntl"));
}

Fd connect_to(const std::string& host, std::uint16_t port, Transport transport, Clock::time_point deadline)
{
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = transport == Transport::Tcp ? SOCK_STREAM : SOCK_DGRAM;
    addrinfo* found = nullptr;
    const std::string service = std::to_string(port);
    if (const int rc = ::getaddrinfo(host.c_str(), service.c_str(), &hints, &found); rc != 0)
        throw NetError("cannot resolve " + host + ": " + ::gai_strerror(rc));
    std::string last_error = "no address";
    for (addrinfo* ai = found; ai; ai = ai->ai_next) {
        Fd fd(::socket(ai->ai_family, ai->ai_socktype | SOCK_CLOEXEC, ai->ai_protocol));
        if (!fd) {
            last_error = errno_text("socket");
            continue;
        }
        set_nonblocking(fd.get());
        if (::connect(fd.get(), ai->ai_addr, ai->ai_addrlen) != 0) {
            if (errno != EINPROGRESS) {
                last_error = errno_text("connect");
                continue;
            }
            if (!wait_for(fd.get(), POLLOUT, deadline)) {
                last_error = "connect: timed out";
                continue;
            }
            int err = 0;
            socklen_t len = sizeof err;
            ::getsockopt(fd.get(), SOL_SOCKET, SO_ERROR, &err, &len);
            if (err != 0) {
                last_error = std::string("connect: ") + std::strerror(err);
                continue;
            }
        }
        if (transport == Transport::Tcp) {
            const int one = 1;  // small command lines must not wait for Nagle
            ::setsockopt(fd.get(), IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
        }
        ::freeaddrinfo(found);
        return fd;
    }
    ::freeaddrinfo(found);
    throw NetError("cannot connect to " + host + ":" + service + " (" + last_error + ")");
}

void send_all(int fd, std::span<const char> data, Clock::time_point deadline)
{
    std::size_t sent = 0;
    while (sent < data.size()) {
        ssize_t n = ::send(fd, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
        if (n < 0 && errno == ENOTSOCK) n = ::write(fd, data.data() + sent, data.size() - sent);  // a serial line
        if (n > 0) {
            sent += static_cast<std::size_t>(n);
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            if (!wait_for(fd, POLLOUT, deadline)) throw NetError("send: timed out");
            continue;
        }
        throw NetError(errno_text("send"));
    }
}

void send_all(int fd, std::span<const std::uint8_t> data, Clock::time_point deadline)
{
    send_all(fd, std::span<const char>(reinterpret_cast<const char*>(data.data()), data.size()), deadline);
}

std::optional<std::size_t> receive_some(int fd, std::span<std::uint8_t> buffer, Clock::time_point deadline)
{
    for (;;) {
        const ssize_t n = ::read(fd, buffer.data(), buffer.size());
        if (n > 0) return static_cast<std::size_t>(n);
        if (n == 0) throw NetError("connection closed by the head");
        if (errno == EINTR) continue;
        if (errno != EAGAIN && errno != EWOULDBLOCK) throw NetError(errno_text("read"));
        if (!wait_for(fd, POLLIN, deadline)) return std::nullopt;
    }
}

std::optional<std::string> LineReader::read_line(int fd, Clock::time_point deadline)
{
    auto too_long = [this] {
        return NetError("the head sent a line longer than " + std::to_string(max_length_) + " bytes");
    };
    for (;;) {
        if (const auto nl = buffer_.find('\n'); nl != std::string::npos) {
            std::string line = buffer_.substr(0, nl);
            buffer_.erase(0, nl + 1);
            if (!line.empty() && line.back() == '\r') line.pop_back();
            if (line.size() > max_length_) throw too_long();
            return line;
        }
        if (buffer_.size() > max_length_ + 1) throw too_long();  // +1: a '\r' may still end it
        char chunk[1024];
        const ssize_t n = ::read(fd, chunk, sizeof chunk);  // read(): pipes work too
        if (n > 0) {
            buffer_.append(chunk, static_cast<std::size_t>(n));
            continue;
        }
        if (n == 0) throw NetError("connection closed by the head");
        if (errno == EINTR) continue;
        if (errno != EAGAIN && errno != EWOULDBLOCK) throw NetError(errno_text("read"));
        if (!wait_for(fd, POLLIN, deadline)) return std::nullopt;
    }
}

}  // namespace gc::headctl::net
