// The SOAP 1.2 messages of the ONVIF PTZ service that a head needs (GetStatus, AbsoluteMove,
// ContinuousMove, Stop, GetPresets, SetPreset, GotoPreset, GotoHomePosition), both sides:
// building requests and responses, and reading them with libxml2. Values are ONVIF's generic
// spaces (pan/tilt -1..1, zoom 0..1); mapping to degrees is the caller's.
#pragma once

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gc::headctl::onvif {

// A message that is not XML, not a SOAP envelope or lacks what its operation needs.
class SoapError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

inline constexpr std::size_t kMaxMessageBytes = 64 * 1024;

// An element of a parsed message: its local name (namespace prefix dropped), attributes,
// text and children.
struct XmlElement {
    std::string name;
    std::vector<std::pair<std::string, std::string>> attributes;
    std::string text;
    std::vector<XmlElement> children;

    const XmlElement* child(std::string_view local_name) const;
    std::optional<std::string> attribute(std::string_view local_name) const;
};

// The SOAP header (empty name when absent) and the one element inside the body.
struct Envelope {
    XmlElement header;
    XmlElement body;
};

// Throws SoapError for anything but a SOAP envelope of at most kMaxMessageBytes, at most
// 32 levels deep and 2048 elements, whose body holds one element. Entities and external
// resources are never loaded.
Envelope parse_envelope(std::string_view xml);

// WS-Security UsernameToken with a password digest: Base64(SHA-1(nonce + created + password)).
struct UsernameToken {
    std::string user;
    std::string digest;   // Base64
    std::string nonce;    // Base64 of the raw nonce
    std::string created;  // UTC, e.g. 2026-01-31T12:00:00Z
};
// Throws SoapError when the nonce is not Base64.
std::string password_digest(std::string_view nonce_base64, std::string_view created, std::string_view password);
// A fresh token: 16 random bytes of nonce, created now.
UsernameToken make_username_token(const std::string& user, std::string_view password);
// The UsernameToken in an envelope's header, if any (PasswordDigest only).
std::optional<UsernameToken> username_token(const Envelope& envelope);

// ONVIF's generic spaces are linear over a range: -1..1 over [lo, hi] for pan and tilt,
// 0..1 over magnification 1..zoom_max.
inline double to_generic(double value, double lo, double hi) { return 2.0 * (value - lo) / (hi - lo) - 1.0; }
inline double from_generic(double x, double lo, double hi) { return lo + (x + 1.0) * 0.5 * (hi - lo); }
inline double zoom_to_generic(double magnification, double zoom_max)
{
    return (magnification - 1.0) / (zoom_max - 1.0);
}
inline double zoom_from_generic(double x, double zoom_max) { return 1.0 + x * (zoom_max - 1.0); }

// The text of a remote party's message (a fault's reason) fit for an error message: printable
// ASCII, at most 160 characters.
std::string printable(std::string_view text);

struct PanTilt {
    double x = 0.0;
    double y = 0.0;
};

// What a PTZ request asks for, in generic-space values.
struct PtzRequest {
    std::string operation;  // GetStatus, AbsoluteMove, ...
    std::string profile;
    std::optional<PanTilt> pan_tilt;  // AbsoluteMove position, ContinuousMove velocity
    std::optional<double> zoom;
    std::string preset_token;  // SetPreset (may be empty), GotoPreset
};

std::string request_envelope(const PtzRequest& request, const std::optional<UsernameToken>& token);
// The operation, the profile and the values of a request; throws SoapError.
PtzRequest parse_request(const Envelope& envelope);

struct PtzStatus {
    PanTilt pan_tilt;
    double zoom = 0.0;
    bool pan_tilt_moving = false;
    bool zoom_moving = false;
};

struct Preset {
    std::string token;
    std::string name;
};

struct Fault {
    std::string code;     // Sender, Receiver
    std::string subcode;  // ONVIF's ter: subcode, e.g. NotAuthorized
    std::string reason;
};

std::string status_response(const PtzStatus& status);
std::string presets_response(const std::vector<Preset>& presets);
std::string set_preset_response(const std::string& preset_token);
// The empty response of AbsoluteMove, ContinuousMove, Stop, GotoPreset, GotoHomePosition.
std::string empty_response(std::string_view operation);
std::string fault_envelope(const Fault& fault);

// Read a response; each throws SoapError when the envelope holds something else (a fault
// included: check fault() first).
std::optional<Fault> fault(const Envelope& envelope);
PtzStatus parse_status(const Envelope& envelope);
std::vector<Preset> parse_presets(const Envelope& envelope);
std::string parse_set_preset(const Envelope& envelope);
void expect_response(const Envelope& envelope, std::string_view operation);

}  // namespace gc::headctl::onvif
