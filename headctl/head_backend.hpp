// What a head client needs from a head, whatever protocol it speaks. Implementations are
// synchronous and used by one thread (the client's); they block up to the given deadline.
#pragma once

#include "headctl/axes.hpp"
#include "headctl/net.hpp"
#include "headctl/uri.hpp"

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

namespace gc::headctl {

// SavePreset stores where the head is under a number; RecallPreset moves it back there.
enum class CommandKind { Absolute, Relative, Velocity, Stop, Home, SavePreset, RecallPreset };

// Preset numbers every backend takes (VISCA's CAM_Memory holds 0..127).
inline constexpr int kMaxPreset = 127;

struct HeadCommand {
    CommandKind kind = CommandKind::Stop;
    AxisValues values;  // degrees, or degrees per second for Velocity
    int preset = 0;     // SavePreset, RecallPreset: 0..kMaxPreset
    bool operator==(const HeadCommand&) const = default;
};

inline HeadCommand preset_command(CommandKind kind, int number) { return HeadCommand{kind, {}, number}; }
inline bool is_preset(CommandKind kind) { return kind == CommandKind::SavePreset || kind == CommandKind::RecallPreset; }

std::string describe(const HeadCommand& command);

// The head refused a command; the connection is still good.
class HeadRejected : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class HeadBackend {
public:
    using Deadline = net::Clock::time_point;
    virtual ~HeadBackend() = default;

    // Connects (and authenticates). Throws net::NetError.
    virtual void open(Deadline deadline) = 0;
    virtual void close() = 0;
    // Throw net::NetError when the connection fails, HeadRejected when the head refuses.
    virtual HeadState query_state(Deadline deadline) = 0;
    virtual void send(const HeadCommand& command, Deadline deadline) = 0;
    // nullopt when the head cannot tell.
    virtual std::optional<HeadLimits> query_limits(Deadline deadline) = 0;
    // The limits the backend itself works within, without asking the head (its URI's
    // parameters: an ONVIF range, a lens's zoom_max): what a caller may use for a head that
    // does not report its own. Pan -180..180 and tilt -90..90 deg, no zoom, unless a backend
    // knows better.
    virtual HeadLimits assumed_limits() const;
    // The axes the head has; commands naming others are rejected before they are sent.
    virtual std::array<bool, kAxisCount> axes() const = 0;
    virtual std::string name() const = 0;
};

// HeadBackend::assumed_limits() with the zoom running from 1 to `zoom_max` at up to
// `zoom_speed` magnification per second.
HeadLimits limits_with_zoom(const HeadBackend& backend, double zoom_max, double zoom_speed);

// For heads that report positions without motion (VISCA, Pelco-D; ONVIF adds its own flags
// to these): marks the axes whose position
// changed since `last` as moving, then remembers this state's pose in `last`.
void flag_motion_since(HeadState& state, std::optional<HeadPose>& last);

// The backend for a URI's scheme (tcp: GCHP; visca-udp, visca-tcp, visca-serial: VISCA;
// pelco-d: Pelco-D; onvif: ONVIF PTZ, the token being the password). The token argument overrides a token in the URI. Throws std::invalid_argument for bad parameters.
std::unique_ptr<HeadBackend> make_backend(const HeadUri& uri, const std::string& token = {});

}  // namespace gc::headctl
