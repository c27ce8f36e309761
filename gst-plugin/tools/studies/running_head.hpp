// The simulated head served on 127.0.0.1 from its own thread, for the closed-loop tests and
// the studies that steer it in real time.
#pragma once

#include "headctl/sim/head_server.hpp"

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <thread>

namespace gc::loopback {

class RunningHead {
public:
    explicit RunningHead(headctl::HeadServerConfig config = {})
    {
        server_ = std::make_unique<headctl::HeadServer>(config);
        thread_ = std::thread([this] { server_->run(); });
    }
    ~RunningHead() { stop(); }
    RunningHead(const RunningHead&) = delete;
    RunningHead& operator=(const RunningHead&) = delete;

    void stop()
    {
        if (!thread_.joinable()) return;
        server_->request_stop();
        thread_.join();
    }
    std::uint16_t port() const { return server_->port(); }
    headctl::HeadServer& server() { return *server_; }
    // The head's own state now, read under the server's lock (no network in between).
    headctl::HeadState state()
    {
        headctl::HeadState s;
        server_->with_model([&](headctl::HeadModel& model, double now_s) { s = model.state(now_s); });
        return s;
    }
    std::string uri() const { return "tcp://127.0.0.1:" + std::to_string(port()); }

private:
    std::unique_ptr<headctl::HeadServer> server_;
    std::thread thread_;
};

// A server on any free port with the given command latency.
inline headctl::HeadServerConfig loopback_head(std::uint16_t port = 0, double latency_s = 0.02)
{
    headctl::HeadServerConfig c;
    c.host = "127.0.0.1";
    c.port = port;
    c.model.latency_s = latency_s;
    return c;
}

// Polls `condition` every 5 ms until it holds or `timeout` passes.
inline bool eventually(const std::function<bool()>& condition, std::chrono::milliseconds timeout)
{
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
        if (condition()) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return condition();
}

}  // namespace gc::loopback
