// The simulated head as a VISCA camera: VISCA over IP (UDP, Sony's 8-byte header) and raw
// VISCA over TCP on the same port number. A thread of its own answers pan-tilt, lens and
// memory messages by driving the same HeadModel as a HeadServer. VISCA has no
// authentication, so only loopback is served unless the configuration says otherwise.
#pragma once

#include "headctl/sim/head_server.hpp"
#include "headctl/visca.hpp"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <thread>
#include <vector>

namespace gc::headctl {

// How the camera's units map onto the head's degrees and magnification (the defaults are the
// VISCA backend's: a client with `zoom_max` set to the head's zoom maximum reads it right).
struct ViscaUnits {
    double units_per_deg = 16.0;   // pan and tilt
    int zoom_tele_units = 0x4000;  // the zoom position of the head's largest magnification
};

struct ViscaResponderConfig {
    std::string host = "127.0.0.1";  // numeric IPv4 or IPv6 address to bind
    std::uint16_t port = 52381;      // UDP and TCP; 0 = any free port (the same for both)
    // Anyone who reaches the port moves the head: beyond loopback only when this says so.
    bool allow_remote = false;
    ViscaUnits units;
};

// The replies of the camera to one VISCA message received at now_s: ACK and completion for
// a command it carried out, the position for an inquiry, a syntax error (02) for a message it
// does not know and "not executable" (41) for one the head refuses.
std::vector<visca::Bytes> answer_visca(HeadModel& model, double now_s, std::span<const std::uint8_t> message,
                                       const ViscaUnits& units);
// The same for one VISCA-over-IP datagram: the replies wrapped under its sequence number, a
// control reply to the sequence reset, nothing for a datagram that is not VISCA over IP.
std::vector<visca::Bytes> answer_visca_datagram(HeadModel& model, double now_s, std::span<const std::uint8_t> datagram,
                                                const ViscaUnits& units);

class ViscaResponder {
public:
    // Binds and starts serving; throws std::runtime_error or std::invalid_argument.
    ViscaResponder(const ViscaResponderConfig& config, HeadServer& head);
    ~ViscaResponder();
    ViscaResponder(const ViscaResponder&) = delete;
    ViscaResponder& operator=(const ViscaResponder&) = delete;

    std::uint16_t port() const { return port_; }
    const std::string& host() const { return config_.host; }

private:
    // One TCP connection: its unfinished message, or the rest of an over-long one to drop.
    struct Stream {
        net::Fd fd;
        visca::Bytes input;
        bool discarding = false;
        std::chrono::steady_clock::time_point last_active;
    };

    void bind_sockets();
    void serve();
    void serve_datagram();
    void accept_stream();
    bool serve_stream(Stream& stream);  // false: close it
    std::vector<visca::Bytes> answer(std::span<const std::uint8_t> message);

    ViscaResponderConfig config_;
    HeadServer& head_;
    net::Fd udp_;
    net::Fd listener_;
    std::vector<Stream> streams_;  // the serving thread's only
    std::uint16_t port_ = 0;
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

}  // namespace gc::headctl
