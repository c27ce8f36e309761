// A head speaking GCHP/1 (docs/head-protocol.md) over TCP.
#pragma once

#include "headctl/head_backend.hpp"
#include "headctl/protocol.hpp"

namespace gc::headctl {

class GchpBackend final : public HeadBackend {
public:
    GchpBackend(std::string host, std::uint16_t port, std::string token);

    void open(Deadline deadline) override;
    void close() override;
    HeadState query_state(Deadline deadline) override;
    void send(const HeadCommand& command, Deadline deadline) override;
    std::optional<HeadLimits> query_limits(Deadline deadline) override;
    std::array<bool, kAxisCount> axes() const override { return greeting_.axes; }
    std::string name() const override;

private:
    // Sends the request with a fresh id and returns the reply carrying that id.
    Reply transact(Request request, Deadline deadline);

    std::string host_;
    std::uint16_t port_;
    std::string token_;
    net::Fd fd_;
    net::LineReader reader_{kMaxLineLength};
    Greeting greeting_;
    std::uint32_t next_id_ = 1;
};

}  // namespace gc::headctl
