// Small POSIX socket helpers with deadlines: connect, send, bounded line reads, datagrams.
// Every descriptor passed in must be non-blocking, or a deadline cannot be kept.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

namespace gc::headctl::net {

using Clock = std::chrono::steady_clock;

// A connection that failed or broke (as opposed to a head refusing a command).
class NetError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// While a CancelScope lives on a thread, every wait of that thread here looks at `flag`
// at least every 20 ms and throws NetError("cancelled") once it is set: a client being
// destroyed does not sit out a silent head's timeouts.
class CancelScope {
public:
    explicit CancelScope(const std::atomic<bool>& flag);
    ~CancelScope();
    CancelScope(const CancelScope&) = delete;
    CancelScope& operator=(const CancelScope&) = delete;

private:
    const std::atomic<bool>* previous_;
};

// Whether the CancelScope of this thread, if any, has been told to stop: for waits done
// elsewhere (a GLib main loop) that must end as promptly as these.
bool cancel_requested();

// Owns a file descriptor.
class Fd {
public:
    Fd() = default;
    explicit Fd(int fd) : fd_(fd) {}
    Fd(Fd&& o) noexcept : fd_(o.release()) {}
    Fd& operator=(Fd&& o) noexcept;
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    ~Fd() { reset(); }
    int get() const { return fd_; }
    explicit operator bool() const { return fd_ >= 0; }
    int release();
    void reset();

private:
    int fd_ = -1;
};

void set_nonblocking(int fd);

enum class Transport { Tcp, Udp };

// Resolves host and connects within the deadline; the socket is non-blocking.
Fd connect_to(const std::string& host, std::uint16_t port, Transport transport, Clock::time_point deadline);

// Writes everything before the deadline or throws NetError.
void send_all(int fd, std::span<const char> data, Clock::time_point deadline);
void send_all(int fd, std::span<const std::uint8_t> data, Clock::time_point deadline);

// Receives one datagram (or whatever a stream has) before the deadline; nullopt on timeout.
std::optional<std::size_t> receive_some(int fd, std::span<std::uint8_t> buffer, Clock::time_point deadline);

// Splits a byte stream into lines of at most max_length bytes, not counting the '\n' and a
// '\r' before it.
class LineReader {
public:
    explicit LineReader(std::size_t max_length) : max_length_(max_length) {}
    // The next line without its '\r\n' or '\n', or nullopt on timeout. Throws NetError on
    // close, error or an over-long line.
    std::optional<std::string> read_line(int fd, Clock::time_point deadline);
    void clear() { buffer_.clear(); }

private:
    std::size_t max_length_;
    std::string buffer_;
};

}  // namespace gc::headctl::net
