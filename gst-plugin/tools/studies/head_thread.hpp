// headsim's server on a free loopback port, with 20 ms of command latency, on its own thread:
// the simulated head the studies' real-time loops steer.
#pragma once

#include "headctl/sim/head_server.hpp"

#include <memory>
#include <string>
#include <thread>

namespace gc::study {

class HeadThread {
public:
    HeadThread()
    {
        headctl::HeadServerConfig c;
        c.host = "127.0.0.1";
        c.port = 0;
        c.model.latency_s = 0.02;
        server_ = std::make_unique<headctl::HeadServer>(c);
        thread_ = std::thread([this] { server_->run(); });
    }
    ~HeadThread()
    {
        server_->request_stop();
        thread_.join();
    }
    HeadThread(const HeadThread&) = delete;
    HeadThread& operator=(const HeadThread&) = delete;
    std::string uri() const { return "tcp://127.0.0.1:" + std::to_string(server_->port()); }

private:
    std::unique_ptr<headctl::HeadServer> server_;
    std::thread thread_;
};

}  // namespace gc::study
