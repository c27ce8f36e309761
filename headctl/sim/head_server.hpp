// The simulated head's network side: a single-threaded poll() loop serving GCHP/1 to many
// clients over a HeadModel. Each client has bounded buffers, so a misbehaving one (garbage,
// half lines, never reading, vanishing) costs only its own slot. With a token, connections
// that have not authenticated wait apart from the served clients, a few per address and for
// a few seconds at most, and wrong tokens cost their address a growing wait: clients without
// the token can neither take the served clients' places nor guess it quickly.
#pragma once

#include "headctl/sim/auth_throttle.hpp"
#include "headctl/sim/head_model.hpp"
#include "headctl/net.hpp"
#include "headctl/protocol.hpp"

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <sys/socket.h>

struct pollfd;

namespace gc::headctl {

struct HeadServerConfig {
    std::string host = "127.0.0.1";  // numeric IPv4 or IPv6 address to bind
    std::uint16_t port = 5050;       // 0 = any free port
    std::string token;               // empty = no authentication
    // Without a token anyone who reaches the port moves the head: a host beyond loopback
    // is refused unless this says that is meant.
    bool allow_remote_without_token = false;
    std::size_t max_clients = 16;                // authenticated clients served at once
    std::size_t max_pending_output = 64 * 1024;  // per client; beyond it the client is not read
    int max_auth_failures = 3;                   // then the connection is closed
    // Connections still to authenticate: at most this many in all (a new one pushes out the
    // oldest of the address that holds the most) and per address (a new one beyond it is
    // refused), each for at most auth_timeout.
    std::size_t max_unauthenticated = 128;
    std::size_t max_unauthenticated_per_address = 4;
    std::chrono::milliseconds auth_timeout{5000};
    // After a wrong token, the next token from that address is checked this much later,
    // doubling with each further failure up to the maximum.
    std::chrono::milliseconds auth_delay_initial{100};
    std::chrono::milliseconds auth_delay_max{5000};
    bool verbose = false;  // one stderr line per connection event
    HeadModelConfig model;
};

// Whether a numeric address reaches this host only (127.0.0.0/8, ::1, IPv4-mapped 127.x).
bool is_loopback_address(const std::string& host);
// The socket address of a numeric IPv4 or IPv6 host and a port, and its length; throws
// std::invalid_argument for anything else.
socklen_t numeric_address(const std::string& host, std::uint16_t port, sockaddr_storage& addr);
// The local port a socket is bound to.
std::uint16_t bound_port(int fd);

class HeadServer {
public:
    // Binds and listens; throws std::runtime_error or std::invalid_argument with the cause.
    explicit HeadServer(const HeadServerConfig& config);
    ~HeadServer();
    HeadServer(const HeadServer&) = delete;
    HeadServer& operator=(const HeadServer&) = delete;

    std::uint16_t port() const { return port_; }
    const std::string& host() const { return config_.host; }

    // Serves until request_stop(); closes every connection before returning.
    void run();
    // Safe from any thread and from a signal handler.
    void request_stop() noexcept;
    // Runs `f` on the head with the server's clock (seconds), under the lock the server's own
    // requests take: other front ends (the ONVIF responder) drive the same head from their threads.
    void with_model(const std::function<void(HeadModel&, double now_s)>& f);

private:
    struct Client;
    using Clock = std::chrono::steady_clock;

    int poll_timeout_ms(Clock::time_point now) const;
    void accept_clients();
    void admit(net::Fd& fd, const std::string& address, const std::string& peer);
    void drop_one_unauthenticated();
    void refuse(net::Fd& fd, const std::string& peer, const std::string& why);
    void expire_and_release(Clock::time_point now);
    void read_from(Client& c);
    void process_input(Client& c);
    void handle_line(Client& c, std::string_view line);
    void authenticate(Client& c, const Request& auth);
    void reply(Client& c, const Reply& r);
    void flush(Client& c);
    std::size_t count_clients(bool authenticated, const std::string* address = nullptr) const;
    void log(const std::string& peer, const std::string& what) const;
    double now_s() const;

    HeadServerConfig config_;
    std::mutex model_mutex_;
    HeadModel model_;
    AuthThrottle throttle_;
    net::Fd listener_;
    net::Fd wake_read_;
    net::Fd wake_write_;
    std::uint16_t port_ = 0;
    Clock::time_point start_;
    Clock::time_point accept_paused_until_;  // out of descriptors: the listener rests a moment
    std::vector<std::unique_ptr<Client>> clients_;
    std::vector<pollfd> poll_set_;
    std::string reply_line_;  // reused formatting buffer
};

}  // namespace gc::headctl
