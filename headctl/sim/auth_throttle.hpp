// The growing wait a server imposes on an address that sent wrong tokens: after n failures
// in a row its next token is checked only initial * 2^(n-1) later (at most max), however
// many connections it opens, so guessing costs time rather than reconnections.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>
#include <unordered_map>

struct sockaddr_storage;

namespace gc::headctl {

class AuthThrottle {
public:
    using Clock = std::chrono::steady_clock;

    // Keeps at most `capacity` addresses; an address quiet for `forget_after` starts afresh.
    AuthThrottle(Clock::duration initial, Clock::duration max, std::size_t capacity = 4096,
                 Clock::duration forget_after = std::chrono::minutes(10));

    // When a token from this address may be checked next (in the past when it may now).
    Clock::time_point next_check(const std::string& address) const;
    void failed(const std::string& address, Clock::time_point now);
    void succeeded(const std::string& address);
    std::size_t size() const { return records_.size(); }

private:
    struct Record {
        int failures = 0;
        Clock::time_point next_check;
    };
    void make_room(Clock::time_point now);

    Clock::duration initial_, max_, forget_after_;
    std::size_t capacity_;
    std::unordered_map<std::string, Record> records_;
};

// The address connections are counted and throttled under: an IPv4 address, the /64
// network of an IPv6 address (one host usually holds a whole /64), an IPv4-mapped IPv6
// address as IPv4.
std::string address_key(const sockaddr_storage& peer);

}  // namespace gc::headctl
