// Head addresses: "tcp://host:port" (GCHP), "visca-udp://host[:port]", "visca-tcp://host[:port]",
// "visca-serial:///dev/ttyUSB0", "pelco-d:///dev/ttyUSB0", "onvif://host[:port][/path]".
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gc::headctl {

enum class HeadScheme { Gchp, ViscaUdp, ViscaTcp, ViscaSerial, PelcoD, Onvif };

// Serial schemes name a device path instead of a host and port.
inline bool is_serial(HeadScheme scheme) { return scheme == HeadScheme::ViscaSerial || scheme == HeadScheme::PelcoD; }

inline constexpr std::size_t kMaxUriLength = 1024;

struct HeadUri {
    HeadScheme scheme = HeadScheme::Gchp;
    std::string host;  // a name or an address; IPv6 without its brackets
    std::uint16_t port = 0;
    std::string path;  // serial schemes: the device, e.g. /dev/ttyUSB0; onvif: the service path, e.g. /onvif/ptz
    std::vector<std::pair<std::string, std::string>> params;  // the query, in order

    std::optional<std::string> param(std::string_view key) const;
    // A numeric query parameter in [min, max], or fallback when absent.
    double number_param(std::string_view key, double fallback, double min, double max) const;
};

std::string_view scheme_name(HeadScheme scheme);

// Throws std::invalid_argument naming the offending part. Query keys are checked
// against those the scheme knows (tcp: token; visca-*: address, pan_units_per_deg,
// tilt_units_per_deg, pan_max_speed_dps, tilt_max_speed_dps, zoom_*, timeout_ms; and baud for
// visca-serial; pelco-d: address, baud, pan_max_speed_dps, tilt_max_speed_dps, zoom_max, timeout_ms;
// onvif: user, token (the password), profile, pan_min_deg, pan_max_deg, tilt_min_deg, tilt_max_deg,
// zoom_max, pan_max_speed_dps, tilt_max_speed_dps, zoom_max_speed, timeout_ms).
HeadUri parse_head_uri(std::string_view text);
// The full URI, token included: for connecting, never for showing.
std::string to_string(const HeadUri& uri);

// Where the value of each token= parameter lies in a head URI's text, in order; found in
// any text, even one that does not parse, and whatever the key's case.
struct TextSpan {
    std::size_t offset = 0;
    std::size_t length = 0;
};
std::vector<TextSpan> token_values(std::string_view text);

// The text of a head URI as it may be shown (logs, messages, errors, property values): the
// value of every token= query parameter replaced by "***". Works on any text, even one
// that does not parse.
std::string redact_uri(std::string_view text);

}  // namespace gc::headctl
