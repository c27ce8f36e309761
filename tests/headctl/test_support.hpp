// Loopback helpers of the head tests: an in-process simulated head and a raw line client.
#pragma once

#include "headctl/head_server.hpp"
#include "headctl/net.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <thread>

namespace gc::headctl::testing {

using namespace std::chrono_literals;

// A HeadServer on 127.0.0.1 serving on its own thread for the lifetime of the object.
class RunningServer {
public:
    explicit RunningServer(HeadServerConfig config = {}) {
        if (config.port == 5050) config.port = 0;
        server_ = std::make_unique<HeadServer>(config);
        thread_ = std::thread([this] { server_->run(); });
    }
    ~RunningServer() { stop(); }
    void stop() {
        if (!thread_.joinable()) return;
        server_->request_stop();
        thread_.join();
    }
    std::uint16_t port() const { return server_->port(); }
    std::string uri() const { return "tcp://127.0.0.1:" + std::to_string(port()); }

private:
    std::unique_ptr<HeadServer> server_;
    std::thread thread_;
};

// A blocking line client with deadlines, to talk to the server byte by byte.
class LineClient {
public:
    explicit LineClient(std::uint16_t port)
        : fd_(net::connect_to("127.0.0.1", port, net::Transport::Tcp, net::Clock::now() + 2s)) {}
    void send(std::string_view text) {
        net::send_all(fd_.get(), std::span<const char>(text.data(), text.size()), net::Clock::now() + 2s);
    }
    std::optional<std::string> line(std::chrono::milliseconds timeout = 2000ms) {
        return reader_.read_line(fd_.get(), net::Clock::now() + timeout);
    }
    std::string request(std::string_view text) {
        send(std::string(text) + "\n");
        auto l = line();
        return l ? *l : std::string("<timeout>");
    }
    int fd() const { return fd_.get(); }
    void close() { fd_.reset(); }

private:
    net::Fd fd_;
    net::LineReader reader_{8192};
};

}  // namespace gc::headctl::testing
