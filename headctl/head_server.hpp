// The simulated head's network side: a single-threaded poll() loop serving GCHP/1 to many
// clients over a HeadModel. Each client has bounded buffers, so a misbehaving one (garbage,
// half lines, never reading, vanishing) costs only its own slot.
#pragma once

#include "headctl/head_model.hpp"
#include "headctl/net.hpp"
#include "headctl/protocol.hpp"

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

struct pollfd;

namespace gc::headctl {

struct HeadServerConfig {
    std::string host = "127.0.0.1";  // numeric IPv4 or IPv6 address to bind
    std::uint16_t port = 5050;       // 0 = any free port
    std::string token;               // empty = no authentication
    std::size_t max_clients = 16;
    std::size_t max_pending_output = 64 * 1024;  // per client; beyond it the client is not read
    int max_auth_failures = 3;                   // then the connection is closed
    bool verbose = false;                        // one stderr line per connection event
    HeadModelConfig model;
};

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

private:
    struct Client;
    using Clock = std::chrono::steady_clock;

    void accept_clients();
    void read_from(Client& c);
    void handle_line(Client& c, std::string_view line);
    void reply(Client& c, const Reply& r);
    void flush(Client& c);
    double now_s() const;

    HeadServerConfig config_;
    HeadModel model_;
    net::Fd listener_;
    net::Fd wake_read_;
    net::Fd wake_write_;
    std::uint16_t port_ = 0;
    Clock::time_point start_;
    std::vector<std::unique_ptr<Client>> clients_;
    std::vector<pollfd> poll_set_;
    std::string reply_line_;  // reused formatting buffer
};

}  // namespace gc::headctl
