#include "headctl/protocol.hpp"

#include "common/enum_names.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <vector>

namespace gc::headctl {

namespace {

constexpr EnumNames<ErrorCode, 9> kErrorNames{{
    {ErrorCode::Syntax, "syntax"},
    {ErrorCode::AuthRequired, "auth-required"},
    {ErrorCode::AuthFailed, "auth-failed"},
    {ErrorCode::UnknownCommand, "unknown-command"},
    {ErrorCode::LineTooLong, "line-too-long"},
    {ErrorCode::OutOfRange, "out-of-range"},
    {ErrorCode::BadArgument, "bad-argument"},
    {ErrorCode::Internal, "internal"},
    {ErrorCode::Busy, "busy"},
}};

[[noreturn]] void fail(ErrorCode code, const std::string& message) { throw ProtocolError(code, message); }

// Shows a piece of untrusted input in an error message: bounded, printable.
std::string quoted(std::string_view s)
{
    constexpr std::size_t kShown = 32;
    std::string out = "'";
    for (char c : s.substr(0, kShown)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
    if (s.size() > kShown) out += "...";
    return out + "'";
}

// Strips the optional '\r', checks the length and the alphabet, splits on blanks.
std::vector<std::string_view> split_line(std::string_view line)
{
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.size() > kMaxLineLength)
        fail(ErrorCode::LineTooLong,
             "line of " + std::to_string(line.size()) + " bytes exceeds " + std::to_string(kMaxLineLength));
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < line.size()) {
        const unsigned char c = static_cast<unsigned char>(line[i]);
        if (c == ' ' || c == '\t') {
            ++i;
            continue;
        }
        std::size_t j = i;
        while (j < line.size() && line[j] != ' ' && line[j] != '\t') {
            const unsigned char d = static_cast<unsigned char>(line[j]);
            if (d < 0x20 || d >= 0x7f) {
                char hex[8];
                std::snprintf(hex, sizeof hex, "0x%02x", d);
                fail(ErrorCode::Syntax,
                     std::string("non-printable byte ") + hex + " at column " + std::to_string(j + 1));
            }
            ++j;
        }
        words.push_back(line.substr(i, j - i));
        i = j;
    }
    return words;
}

bool iequals(std::string_view a, std::string_view b)
{
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               auto lower = [](char c) { return (c >= 'A' && c <= 'Z') ? char(c - 'A' + 'a') : c; };
               return lower(x) == lower(y);
           });
}

double parse_number(std::string_view what, std::string_view text)
{
    double v = 0.0;
    const char* end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(text.data(), end, v, std::chars_format::general);
    if (text.empty() || ec == std::errc::invalid_argument || ptr != end)
        fail(ErrorCode::BadArgument, std::string(what) + " value " + quoted(text) + " is not a number");
    if (ec == std::errc::result_out_of_range || !std::isfinite(v))
        fail(ErrorCode::BadArgument, std::string(what) + " value " + quoted(text) + " is not finite");
    if (std::abs(v) > kMaxWireValue)
        fail(ErrorCode::BadArgument, std::string(what) + " value " + quoted(text) + " exceeds +-1e5");
    return v;
}

template <typename Int>
Int parse_integer(std::string_view what, std::string_view text)
{
    Int v{};
    const char* end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(text.data(), end, v);
    if (text.empty() || ec != std::errc{} || ptr != end)
        fail(ErrorCode::BadArgument, std::string(what) + " value " + quoted(text) + " is not a valid integer");
    return v;
}

// "#123" -> 123, if the word is an id.
std::optional<std::uint32_t> parse_id(std::string_view word)
{
    if (word.empty() || word.front() != '#') return std::nullopt;
    const std::string_view digits = word.substr(1);
    if (digits.empty() || digits.size() > 10 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
        fail(ErrorCode::Syntax, "request id " + quoted(word) + " must be '#' followed by 1 to 10 digits");
    std::uint64_t v = 0;
    std::from_chars(digits.data(), digits.data() + digits.size(), v);
    if (v > UINT32_MAX) fail(ErrorCode::Syntax, "request id " + quoted(word) + " exceeds 4294967295");
    return static_cast<std::uint32_t>(v);
}

std::pair<std::string_view, std::string_view> split_key_value(std::string_view word)
{
    const auto eq = word.find('=');
    if (eq == std::string_view::npos || eq == 0) fail(ErrorCode::Syntax, "expected key=value, got " + quoted(word));
    return {word.substr(0, eq), word.substr(eq + 1)};
}

Axis parse_axis(std::string_view name)
{
    auto axis = axis_from_name(name);
    if (!axis) fail(ErrorCode::BadArgument, "unknown axis " + quoted(name) + " (pan, tilt, verge_l, verge_r, zoom)");
    return *axis;
}

std::string format_number(double v)
{
    if (!std::isfinite(v)) throw std::invalid_argument("cannot send a value that is not finite");
    if (std::abs(v) > kMaxWireValue) throw std::invalid_argument("cannot send a value beyond +-1e5");
    char buf[32];
    auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 4);
    if (ec != std::errc{}) throw std::invalid_argument("cannot format a number");
    std::string s(buf, ptr);
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
    if (s == "-0") s = "0";
    return s;
}

// The axes every STATE and LIMITS carries; zoom may be missing (a head without one).
constexpr std::size_t kAngleAxes = 4;

void append_id(std::string& out, const std::optional<std::uint32_t>& id)
{
    if (!id) return;
    out += " #";
    out += std::to_string(*id);
}

struct Verb {
    std::string_view word;
    Command command;
};
constexpr std::array<Verb, 6> kSimpleVerbs{{
    {"STATUS", Command::Status},
    {"STOP", Command::Stop},
    {"HOME", Command::Home},
    {"LIMITS", Command::Limits},
    {"QUIT", Command::Quit},
    {"AUTH", Command::Auth},
}};

}  // namespace

std::string_view error_code_name(ErrorCode code) { return name_in(kErrorNames, code, "unknown"); }

std::optional<ErrorCode> error_code_from_number(int number)
{
    for (const auto& [code, name] : kErrorNames)
        if (static_cast<int>(code) == number) return code;
    return std::nullopt;
}

Greeting parse_greeting(std::string_view line)
{
    const auto words = split_line(line);
    if (words.size() < 2 || words[0] != "HELLO")
        fail(ErrorCode::Syntax, "greeting must start with 'HELLO GCHP/<version>'");
    const std::string_view proto = words[1];
    const std::string prefix = std::string(kProtocolName) + "/";
    if (proto.substr(0, prefix.size()) != prefix)
        fail(ErrorCode::Syntax, "greeting names protocol " + quoted(proto) + ", expected GCHP/<version>");
    Greeting g;
    g.version = parse_integer<int>("protocol version", proto.substr(prefix.size()));
    bool have_axes = false;
    bool have_caps = false;
    for (std::size_t i = 2; i < words.size(); ++i) {
        auto [key, value] = split_key_value(words[i]);
        std::vector<std::string_view> items;
        for (std::size_t s = 0; s <= value.size();) {
            const auto comma = std::min(value.find(',', s), value.size());
            if (comma > s) items.push_back(value.substr(s, comma - s));
            s = comma + 1;
        }
        if (key == "axes") {
            have_axes = true;
            g.axes.fill(false);
            for (auto item : items) g.axes[static_cast<std::size_t>(parse_axis(item))] = true;
        } else if (key == "caps") {
            have_caps = true;
            g.caps = Capabilities{false, false, false, false, false};
            for (auto item : items) {  // unknown capabilities are a later minor version's: ignored
                if (item == "abs")
                    g.caps.absolute = true;
                else if (item == "rel")
                    g.caps.relative = true;
                else if (item == "vel")
                    g.caps.velocity = true;
                else if (item == "auth")
                    g.caps.auth_required = true;
                else if (item == "preset")
                    g.caps.presets = true;
            }
        }
    }
    if (!have_axes || !have_caps) fail(ErrorCode::Syntax, "greeting lacks axes= or caps=");
    return g;
}

std::string format_greeting(const Greeting& g)
{
    std::string out = "HELLO " + std::string(kProtocolName) + "/" + std::to_string(g.version) + " axes=";
    bool first = true;
    for (Axis a : kAllAxes) {
        if (!g.axes[static_cast<std::size_t>(a)]) continue;
        if (!first) out += ',';
        out += axis_name(a);
        first = false;
    }
    std::string caps;
    auto add = [&caps](bool on, std::string_view name) {
        if (!on) return;
        if (!caps.empty()) caps += ',';
        caps += name;
    };
    add(g.caps.absolute, "abs");
    add(g.caps.relative, "rel");
    add(g.caps.velocity, "vel");
    add(g.caps.presets, "preset");
    add(g.caps.auth_required, "auth");
    return out + " caps=" + caps;
}

Request parse_request(std::string_view line)
{
    const auto words = split_line(line);
    Request r;
    std::size_t i = 0;
    if (!words.empty()) r.id = parse_id(words[0]);
    if (r.id) ++i;
    if (i >= words.size()) fail(ErrorCode::Syntax, "empty request");
    const std::string_view verb = words[i++];
    const std::size_t nargs = words.size() - i;

    if (iequals(verb, "MOVE")) {
        if (nargs < 2) fail(ErrorCode::Syntax, "MOVE needs a mode (ABS, REL, VEL) and at least one axis=value");
        const std::string_view mode = words[i++];
        if (iequals(mode, "ABS"))
            r.command = Command::MoveAbsolute;
        else if (iequals(mode, "REL"))
            r.command = Command::MoveRelative;
        else if (iequals(mode, "VEL"))
            r.command = Command::MoveVelocity;
        else
            fail(ErrorCode::Syntax, "MOVE mode " + quoted(mode) + " is not ABS, REL or VEL");
        for (; i < words.size(); ++i) {
            auto [key, value] = split_key_value(words[i]);
            const Axis axis = parse_axis(key);
            if (r.values.has(axis)) fail(ErrorCode::BadArgument, "axis " + std::string(key) + " given twice");
            r.values.set(axis, parse_number(key, value));
        }
        return r;
    }
    if (iequals(verb, "PRESET")) {
        if (nargs != 2) fail(ErrorCode::Syntax, "PRESET takes SAVE or RECALL and a number");
        const std::string_view action = words[i];
        if (iequals(action, "SAVE"))
            r.command = Command::PresetSave;
        else if (iequals(action, "RECALL"))
            r.command = Command::PresetRecall;
        else
            fail(ErrorCode::Syntax, "PRESET action " + quoted(action) + " is not SAVE or RECALL");
        r.preset = parse_integer<int>("preset", words[i + 1]);
        if (r.preset < 0 || r.preset > kMaxWirePreset)
            fail(ErrorCode::BadArgument, "preset " + quoted(words[i + 1]) + " is not in 0..255");
        return r;
    }
    for (const auto& v : kSimpleVerbs) {
        if (!iequals(verb, v.word)) continue;
        r.command = v.command;
        if (v.command == Command::Auth) {
            if (nargs != 1) fail(ErrorCode::Syntax, "AUTH takes exactly one token");
            const std::string_view token = words[i];
            if (token.size() > kMaxTokenLength)
                fail(ErrorCode::BadArgument, "token longer than " + std::to_string(kMaxTokenLength) + " characters");
            r.token = std::string(token);
        } else if (nargs != 0) {
            fail(ErrorCode::Syntax, std::string(v.word) + " takes no arguments");
        }
        return r;
    }
    fail(ErrorCode::UnknownCommand, "unknown command " + quoted(verb));
}

std::string format_request(const Request& r)
{
    std::string out;
    if (r.id) {
        out += '#';
        out += std::to_string(*r.id);
        out += ' ';
    }
    auto move = [&](std::string_view mode) {
        if (r.values.empty()) throw std::invalid_argument("a move needs at least one axis");
        out += "MOVE ";
        out += mode;
        for (Axis a : kAllAxes) {
            if (!r.values.has(a)) continue;
            out += ' ';
            out += axis_name(a);
            out += '=';
            out += format_number(r.values.get(a));
        }
    };
    switch (r.command) {
    case Command::MoveAbsolute:
        move("ABS");
        break;
    case Command::MoveRelative:
        move("REL");
        break;
    case Command::MoveVelocity:
        move("VEL");
        break;
    case Command::PresetSave:
    case Command::PresetRecall:
        if (r.preset < 0 || r.preset > kMaxWirePreset) throw std::invalid_argument("a preset is 0..255");
        out += r.command == Command::PresetSave ? "PRESET SAVE " : "PRESET RECALL ";
        out += std::to_string(r.preset);
        break;
    case Command::Auth: {
        const bool printable = std::all_of(r.token.begin(), r.token.end(), [](char c) { return c > 0x20 && c < 0x7f; });
        if (r.token.empty() || r.token.size() > kMaxTokenLength || !printable)
            throw std::invalid_argument("a token is 1 to 64 printable characters without blanks");
        out += "AUTH " + r.token;
        break;
    }
    default:
        for (const auto& v : kSimpleVerbs)
            if (v.command == r.command) out += v.word;
    }
    return out;
}

namespace {

HeadState parse_state_fields(const std::vector<std::string_view>& words, std::size_t i)
{
    HeadState s;
    bool have_t = false;
    bool have_moving = false;
    std::array<bool, kAxisCount> have{};
    for (; i < words.size(); ++i) {
        auto [key, value] = split_key_value(words[i]);
        if (key == "t") {
            s.server_time_us = parse_integer<std::int64_t>("t", value);
            have_t = true;
        } else if (key == "moving") {
            // A head without zoom may list the four angle axes only.
            const std::size_t flags = (value.size() + 1) / 2;
            if ((flags != kAxisCount && flags != kAxisCount - 1) || value.size() != 2 * flags - 1)
                fail(ErrorCode::Syntax, "moving must list 4 or 5 flags as 0/1 separated by commas");
            for (std::size_t k = 0; k < flags; ++k) {
                const char flag = value[2 * k];
                if ((flag != '0' && flag != '1') || (k + 1 < flags && value[2 * k + 1] != ','))
                    fail(ErrorCode::Syntax, "moving must list 4 or 5 flags as 0/1 separated by commas");
                s.moving[k] = flag == '1';
            }
            have_moving = true;
        } else if (auto axis = axis_from_name(key)) {
            set_axis_value(s.pose, *axis, parse_number(key, value));
            have[static_cast<std::size_t>(*axis)] = true;
        }  // other keys: later minor versions' additions, ignored
    }
    const bool angles = std::all_of(have.begin(), have.begin() + kAngleAxes, [](bool b) { return b; });
    if (!have_t || !have_moving || !angles)
        fail(ErrorCode::Syntax, "STATE needs t, pan, tilt, verge_l, verge_r and moving");
    if (s.pose.zoom < 1.0) fail(ErrorCode::BadArgument, "zoom below 1 in STATE");
    return s;
}

HeadLimits parse_limit_fields(const std::vector<std::string_view>& words, std::size_t i)
{
    HeadLimits limits;
    std::array<bool, kAxisCount> have{};
    for (; i < words.size(); ++i) {
        auto [key, value] = split_key_value(words[i]);
        auto axis = axis_from_name(key);
        if (!axis) continue;
        std::array<double, 4> v{};
        std::size_t start = 0;
        for (std::size_t k = 0; k < 4; ++k) {
            const auto colon = value.find(':', start);
            const bool last = k == 3;
            if (last != (colon == std::string_view::npos))
                fail(ErrorCode::Syntax, "limits of " + std::string(key) + " must be min:max:vmax:amax");
            const auto end = last ? value.size() : colon;
            v[k] = parse_number(key, value.substr(start, end - start));
            start = end + 1;
        }
        limits[*axis] = AxisLimits{v[0], v[1], v[2], v[3]};
        have[static_cast<std::size_t>(*axis)] = true;
    }
    if (!std::all_of(have.begin(), have.begin() + kAngleAxes, [](bool b) { return b; }))
        fail(ErrorCode::Syntax, "LIMITS needs pan, tilt, verge_l and verge_r");
    try {
        validate(limits);
    } catch (const std::invalid_argument& e) {
        fail(ErrorCode::BadArgument, e.what());
    }
    return limits;
}

}  // namespace

Reply parse_reply(std::string_view line)
{
    const auto words = split_line(line);
    if (words.empty()) fail(ErrorCode::Syntax, "empty reply");
    Reply r;
    std::size_t i = 1;
    if (words[0] == "OK")
        r.ok = true;
    else if (words[0] == "ERR")
        r.ok = false;
    else
        fail(ErrorCode::Syntax, "reply must start with OK or ERR, got " + quoted(words[0]));
    if (i < words.size()) {
        r.id = parse_id(words[i]);
        if (r.id) ++i;
    }
    if (!r.ok) {
        if (i >= words.size()) fail(ErrorCode::Syntax, "ERR reply lacks its code");
        const int number = parse_integer<int>("error code", words[i++]);
        auto code = error_code_from_number(number);
        // An unknown code of a later minor version still reads as an error of its class.
        r.error = code ? *code : (number >= 400 && number < 500 ? ErrorCode::BadArgument : ErrorCode::Internal);
        for (; i < words.size(); ++i) {
            if (!r.message.empty()) r.message += ' ';
            r.message += words[i];
        }
        return r;
    }
    if (i == words.size()) return r;
    if (words[i] == "STATE") {
        r.body = ReplyBody::State;
        r.state = parse_state_fields(words, i + 1);
    } else if (words[i] == "LIMITS") {
        r.body = ReplyBody::Limits;
        r.limits = parse_limit_fields(words, i + 1);
    } else {
        fail(ErrorCode::Syntax, "unknown reply body " + quoted(words[i]));
    }
    return r;
}

std::string format_reply(const Reply& r)
{
    std::string out = r.ok ? "OK" : "ERR";
    append_id(out, r.id);
    if (!r.ok) {
        out += ' ';
        out += std::to_string(static_cast<int>(r.error));
        std::string text = r.message.empty() ? std::string(error_code_name(r.error)) : r.message;
        for (char& c : text)
            if (c < 0x20 || c >= 0x7f) c = '?';
        const std::size_t room = kMaxLineLength - std::min(kMaxLineLength, out.size() + 1);
        text.resize(std::min(text.size(), room));
        while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.pop_back();  // cut at a blank
        out += ' ';
        out += text.empty() ? std::string(error_code_name(r.error)) : text;
        return out;
    }
    if (r.body == ReplyBody::State) {
        const HeadState& s = r.state;
        out += " STATE t=" + std::to_string(s.server_time_us);
        for (Axis a : kAllAxes) {
            out += ' ';
            out += axis_name(a);
            out += '=';
            out += format_number(axis_value(s.pose, a));
        }
        out += " moving=";
        for (std::size_t k = 0; k < kAxisCount; ++k) {
            if (k) out += ',';
            out += s.moving[k] ? '1' : '0';
        }
    } else if (r.body == ReplyBody::Limits) {
        out += " LIMITS";
        for (Axis a : kAllAxes) {
            const AxisLimits& l = r.limits[a];
            out += ' ';
            out += axis_name(a);
            out += '=';
            out += format_number(l.min_deg);
            out += ':';
            out += format_number(l.max_deg);
            out += ':';
            out += format_number(l.max_velocity_dps);
            out += ':';
            out += format_number(l.max_acceleration_dps2);
        }
    }
    return out;
}

std::optional<std::uint32_t> peek_request_id(std::string_view line) noexcept
{
    const auto start = line.find_first_not_of(" \t");
    if (start == std::string_view::npos || line[start] != '#') return std::nullopt;
    const auto end = std::min(line.find_first_of(" \t\r", start), line.size());
    const std::string_view digits = line.substr(start + 1, end - start - 1);
    if (digits.empty() || digits.size() > 10) return std::nullopt;
    std::uint64_t v = 0;
    auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
    if (ec != std::errc{} || ptr != digits.data() + digits.size() || v > UINT32_MAX) return std::nullopt;
    return static_cast<std::uint32_t>(v);
}

Reply make_error_reply(std::optional<std::uint32_t> id, ErrorCode code, std::string message)
{
    Reply r;
    r.id = id;
    r.ok = false;
    r.error = code;
    r.message = std::move(message);
    return r;
}

}  // namespace gc::headctl
