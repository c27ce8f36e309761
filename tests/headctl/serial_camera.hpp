// What the serial head tests share: the backend a URI names opened as a client would, and the
// text of the error a call throws; a camera keeps what it received in a SharedLog.
#pragma once

#include "headctl/head_backend.hpp"
#include "shared_log.hpp"

#include <chrono>
#include <memory>
#include <string>

namespace gc::headctl::testing {

// The deadline of one step of a test: ample for a pty round trip.
inline net::Clock::time_point step_deadline() { return net::Clock::now() + std::chrono::seconds(2); }

inline std::unique_ptr<HeadBackend> opened_backend(const std::string& uri)
{
    auto head = make_backend(parse_head_uri(uri));
    head->open(step_deadline());
    return head;
}

// What the net::NetError `call` throws says, or "no error".
template <class Call>
std::string net_error_of(Call&& call)
{
    try {
        call();
    } catch (const net::NetError& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace gc::headctl::testing
