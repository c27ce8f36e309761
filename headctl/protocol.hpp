// GCHP/1, the line protocol of a GestureCAM head: pure parsing and formatting, no I/O.
// The wire format is specified in docs/head-protocol.md.
#pragma once

#include "headctl/axes.hpp"

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace gc::headctl {

inline constexpr std::string_view kProtocolName = "GCHP";
inline constexpr int kProtocolVersion = 1;
// Longest line either side may send, excluding the terminating '\n'.
inline constexpr std::size_t kMaxLineLength = 512;
// Largest magnitude of an angle, velocity or acceleration on the wire.
inline constexpr double kMaxWireValue = 1e5;
inline constexpr std::size_t kMaxTokenLength = 64;

enum class ErrorCode {
    Syntax = 400,
    AuthRequired = 401,
    AuthFailed = 403,
    UnknownCommand = 404,
    LineTooLong = 413,
    OutOfRange = 416,
    BadArgument = 422,
    Internal = 500,
    Busy = 503,
};

std::string_view error_code_name(ErrorCode code);
std::optional<ErrorCode> error_code_from_number(int number);

// A malformed or unacceptable line; code is what the server answers with.
class ProtocolError : public std::runtime_error {
public:
    ProtocolError(ErrorCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
    ErrorCode code() const { return code_; }

private:
    ErrorCode code_;
};

struct Capabilities {
    bool absolute = true;
    bool relative = true;
    bool velocity = true;
    bool auth_required = false;
    bool presets = false;  // PRESET SAVE / RECALL
    bool operator==(const Capabilities&) const = default;
};

// The server's first line: "HELLO GCHP/1 axes=pan,tilt,verge_l,verge_r,zoom caps=abs,rel,vel[,preset][,auth]".
struct Greeting {
    int version = kProtocolVersion;
    std::array<bool, kAxisCount> axes{true, true, true, true, true};
    Capabilities caps;
    bool operator==(const Greeting&) const = default;
};

enum class Command {
    Auth,
    Status,
    MoveAbsolute,
    MoveRelative,
    MoveVelocity,
    Stop,
    Home,
    Limits,
    Quit,
    PresetSave,
    PresetRecall
};

// Preset numbers on the wire.
inline constexpr int kMaxWirePreset = 255;

// A client line: "[#id ]VERB args".
struct Request {
    std::optional<std::uint32_t> id;
    Command command = Command::Status;
    AxisValues values;  // the moves: degrees, or degrees per second for MoveVelocity
    std::string token;  // Auth
    int preset = 0;     // PresetSave, PresetRecall
    bool operator==(const Request&) const = default;
};

enum class ReplyBody { None, State, Limits };

// A server line: "OK [#id][ STATE ...| LIMITS ...]" or "ERR [#id] <code> <text>".
struct Reply {
    std::optional<std::uint32_t> id;
    bool ok = true;
    ErrorCode error = ErrorCode::Internal;  // when !ok
    std::string message;                    // when !ok
    ReplyBody body = ReplyBody::None;
    HeadState state;    // body == State
    HeadLimits limits;  // body == Limits
};

// Each parser takes one line without its '\n' (one trailing '\r' is ignored) and throws
// ProtocolError naming what is wrong. Formatters return the line without '\n' and throw
// std::invalid_argument for values that cannot go on the wire (not finite, too large).
Greeting parse_greeting(std::string_view line);
std::string format_greeting(const Greeting& greeting);

Request parse_request(std::string_view line);
std::string format_request(const Request& request);

Reply parse_reply(std::string_view line);

// The id of a request line that may be malformed after it, so an error reply can carry it.
std::optional<std::uint32_t> peek_request_id(std::string_view line) noexcept;
std::string format_reply(const Reply& reply);

Reply make_error_reply(std::optional<std::uint32_t> id, ErrorCode code, std::string message);

}  // namespace gc::headctl
