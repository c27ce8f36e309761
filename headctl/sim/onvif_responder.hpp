// The simulated head's ONVIF PTZ service (SOAP 1.2 over HTTP, libsoup's server on a thread
// of its own) driving the same HeadModel as a HeadServer. With a password, every request
// carries a WS-Security UsernameToken digest, and wrong ones cost their address a growing
// wait. Requests are bounded in size and every connection in idle time, and each is served
// asynchronously: a silent or slow client cannot hold the others up.
#pragma once

#include "headctl/onvif_soap.hpp"
#include "headctl/sim/auth_throttle.hpp"
#include "headctl/sim/head_server.hpp"

#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

struct _GMainContext;
struct _GMainLoop;
struct _SoupServer;
struct _SoupServerMessage;

namespace gc::headctl {

struct OnvifResponderConfig {
    std::string host = "127.0.0.1";  // numeric IPv4 or IPv6 address to bind
    std::uint16_t port = 8080;       // 0 = any free port
    std::string user = "gesturecam";
    std::string password;  // empty = no authentication
    // As HeadServerConfig's: without a password only loopback is served unless this says otherwise.
    bool allow_remote_without_password = false;
    // A connection that sends or accepts nothing for this long is closed (whole seconds).
    std::chrono::seconds idle_timeout{5};
    std::chrono::milliseconds auth_delay_initial{100};
    std::chrono::milliseconds auth_delay_max{5000};
};

class OnvifResponder {
public:
    // Binds and starts serving; throws std::runtime_error or std::invalid_argument.
    OnvifResponder(const OnvifResponderConfig& config, HeadServer& head);
    ~OnvifResponder();
    OnvifResponder(const OnvifResponder&) = delete;
    OnvifResponder& operator=(const OnvifResponder&) = delete;

    std::uint16_t port() const { return port_; }
    const std::string& host() const { return config_.host; }

    // The reply to one request's body (HTTP status and SOAP envelope) from a peer address
    // key; what the HTTP side calls, public for tests.
    std::pair<unsigned, std::string> answer(std::string_view body, const std::string& address);

private:
    static void on_request(_SoupServer*, _SoupServerMessage* message, const char*, void*, void* self);
    static void on_request_started(_SoupServer*, _SoupServerMessage* message, void* self);
    static void on_got_headers(_SoupServerMessage* message, void* self);
    static void on_got_chunk(_SoupServerMessage* message, void* chunk, void* self);
    void listen();
    void release();
    std::string authentication_error(const onvif::Envelope& envelope, const std::string& address);
    std::string perform(const onvif::PtzRequest& request);

    OnvifResponderConfig config_;
    HeadServer& head_;
    std::mutex throttle_mutex_;
    AuthThrottle throttle_;
    _GMainContext* context_;
    _GMainLoop* loop_;
    _SoupServer* server_ = nullptr;
    std::uint16_t port_ = 0;
    std::thread thread_;
};

}  // namespace gc::headctl
