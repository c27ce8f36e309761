#include "headctl/sim/auth_throttle.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <algorithm>
#include <cstring>

namespace gc::headctl {

AuthThrottle::AuthThrottle(Clock::duration initial, Clock::duration max, std::size_t capacity,
                           Clock::duration forget_after)
    : initial_(initial), max_(std::max(max, initial)), forget_after_(forget_after),
      capacity_(std::max<std::size_t>(capacity, 1))
{
}

AuthThrottle::Clock::time_point AuthThrottle::next_check(const std::string& address) const
{
    const auto it = records_.find(address);
    return it == records_.end() ? Clock::time_point{} : it->second.next_check;
}

void AuthThrottle::failed(const std::string& address, Clock::time_point now)
{
    if (!records_.count(address)) make_room(now);
    Record& r = records_[address];
    if (r.failures > 0 && now - r.next_check > forget_after_) r.failures = 0;
    ++r.failures;
    Clock::duration wait = initial_;
    for (int i = 1; i < r.failures && wait < max_; ++i) wait *= 2;
    r.next_check = now + std::min(wait, max_);
}

void AuthThrottle::succeeded(const std::string& address) { records_.erase(address); }

// Forgets addresses quiet for long; if none is, the one whose wait ended first.
void AuthThrottle::make_room(Clock::time_point now)
{
    if (records_.size() < capacity_) return;
    std::erase_if(records_, [&](const auto& entry) { return now - entry.second.next_check > forget_after_; });
    if (records_.size() < capacity_) return;
    const auto oldest = std::min_element(records_.begin(), records_.end(), [](const auto& a, const auto& b) {
        return a.second.next_check < b.second.next_check;
    });
    records_.erase(oldest);
}

std::string address_key(const sockaddr_storage& peer)
{
    char text[INET6_ADDRSTRLEN] = "?";
    if (peer.ss_family == AF_INET) {
        ::inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in&>(peer).sin_addr, text, sizeof text);
        return text;
    }
    if (peer.ss_family != AF_INET6) return text;
    in6_addr a = reinterpret_cast<const sockaddr_in6&>(peer).sin6_addr;
    if (IN6_IS_ADDR_V4MAPPED(&a)) {
        ::inet_ntop(AF_INET, &a.s6_addr[12], text, sizeof text);
        return text;
    }
    std::memset(&a.s6_addr[8], 0, 8);
    ::inet_ntop(AF_INET6, &a, text, sizeof text);
    return std::string(text) + "/64";
}

}  // namespace gc::headctl
