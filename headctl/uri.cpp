#include "headctl/uri.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace gc::headctl {

namespace {

struct SchemeInfo {
    HeadScheme scheme;
    std::string_view name;
    std::uint16_t port;
};
constexpr std::array<SchemeInfo, 6> kSchemes{{
    {HeadScheme::Gchp, "tcp", 5050},
    {HeadScheme::ViscaUdp, "visca-udp", 52381},
    {HeadScheme::ViscaTcp, "visca-tcp", 5678},
    {HeadScheme::ViscaSerial, "visca-serial", 0},
    {HeadScheme::PelcoD, "pelco-d", 0},
    {HeadScheme::Onvif, "onvif", 80},
}};

constexpr std::array<std::string_view, 1> kGchpKeys{"token"};
constexpr std::array<std::string_view, 6> kPelcoKeys{"address",  "baud",      "pan_max_speed_dps", "tilt_max_speed_dps",
                                                     "zoom_max", "timeout_ms"};
constexpr std::array<std::string_view, 10> kViscaKeys{
    "address",  "pan_units_per_deg", "tilt_units_per_deg", "pan_max_speed_dps", "tilt_max_speed_dps",
    "zoom_max", "zoom_tele_units",   "zoom_max_speed",     "timeout_ms",        "baud"};
constexpr std::array<std::string_view, 12> kOnvifKeys{
    "user",         "token",    "profile",           "pan_min_deg",        "pan_max_deg",    "tilt_min_deg",
    "tilt_max_deg", "zoom_max", "pan_max_speed_dps", "tilt_max_speed_dps", "zoom_max_speed", "timeout_ms"};

[[noreturn]] void fail(const std::string& message) { throw std::invalid_argument("head URI: " + message); }

// A piece of the URI quoted for an error message: a token in it hidden, at most 64 characters.
std::string shown(std::string_view text)
{
    const std::string s = redact_uri(text);
    std::string out;
    for (char c : std::string_view(s).substr(0, 64)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
    return "'" + out + (s.size() > 64 ? "...'" : "'");
}

bool is_host_char(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '.' ||
           c == '_';
}

bool is_param_char(char c) { return c > 0x20 && c < 0x7f && c != '&' && c != '=' && c != '#' && c != '?'; }

// An absolute path of plain, non-empty segments ("/dev/ttyUSB0", "/onvif/PTZ"): no "//", no
// trailing '/', no "..", so the path printed back by to_string parses to the same path.
bool is_plain_path(std::string_view path)
{
    const bool plain = std::all_of(path.begin(), path.end(), [](char c) { return is_host_char(c) || c == '/'; });
    return plain && path.size() >= 2 && path.size() <= 256 && path.front() == '/' && path.back() != '/' &&
           path.find("//") == std::string_view::npos && path.find("..") == std::string_view::npos;
}

}  // namespace

std::string_view scheme_name(HeadScheme scheme)
{
    for (const auto& s : kSchemes)
        if (s.scheme == scheme) return s.name;
    return "?";
}

std::optional<std::string> HeadUri::param(std::string_view key) const
{
    for (const auto& [k, v] : params)
        if (k == key) return v;
    return std::nullopt;
}

double HeadUri::number_param(std::string_view key, double fallback, double min, double max) const
{
    const auto text = param(key);
    if (!text) return fallback;
    double v = 0.0;
    const char* end = text->data() + text->size();
    auto [ptr, ec] = std::from_chars(text->data(), end, v);
    if (ec != std::errc{} || ptr != end || !std::isfinite(v))
        fail("parameter " + std::string(key) + "=" + shown(*text) + " is not a finite number");
    if (v < min || v > max)
        fail("parameter " + std::string(key) + "=" + shown(*text) + " is outside [" + std::to_string(min) + ", " +
             std::to_string(max) + "]");
    return v;
}

namespace {

// The query's key=value pairs into uri.params, each key checked against the scheme's.
void parse_query(HeadUri& uri, std::string_view query, std::string_view scheme)
{
    while (!query.empty()) {
        const auto amp = query.find('&');
        const std::string_view pair = query.substr(0, amp);
        query = amp == std::string_view::npos ? std::string_view{} : query.substr(amp + 1);
        const auto eq = pair.find('=');
        if (eq == std::string_view::npos || eq == 0 || eq + 1 == pair.size())
            fail("query part " + shown(pair) + " is not key=value");
        const std::string_view key = pair.substr(0, eq);
        const std::string_view value = pair.substr(eq + 1);
        if (!std::all_of(value.begin(), value.end(), is_param_char))
            fail("value of " + shown(key) + " contains a blank or reserved character");
        const auto among = [&](const auto& keys) { return std::find(keys.begin(), keys.end(), key) != keys.end(); };
        bool known = false;
        switch (uri.scheme) {
        case HeadScheme::Gchp:
            known = among(kGchpKeys);
            break;
        case HeadScheme::PelcoD:
            known = among(kPelcoKeys);
            break;
        case HeadScheme::Onvif:
            known = among(kOnvifKeys);
            break;
        default:  // a baud rate only where there is a serial line
            known = among(kViscaKeys) && (key != "baud" || uri.scheme == HeadScheme::ViscaSerial);
        }
        if (!known) fail("parameter " + shown(key) + " is not known for " + std::string(scheme) + "://");
        if (uri.param(key)) fail("parameter " + shown(key) + " given twice");
        uri.params.emplace_back(std::string(key), std::string(value));
    }
}

// onvif://host:port/path: the path after the authority, of plain characters.
void split_service_path(HeadUri& uri, std::string_view& rest)
{
    const auto slash = rest.find('/', rest.empty() || rest.front() != '[' ? 0 : rest.find(']'));
    if (slash == std::string_view::npos) return;
    const std::string_view path = rest.substr(slash);
    if (!is_plain_path(path))
        fail("service path " + shown(path) +
             " is not like /onvif/PTZ (letters, digits, '-', '_', '.' between single '/')");
    uri.path = std::string(path);
    rest = rest.substr(0, slash);
}

}  // namespace

HeadUri parse_head_uri(std::string_view text)
{
    if (text.size() > kMaxUriLength) fail("longer than " + std::to_string(kMaxUriLength) + " characters");
    const auto sep = text.find("://");
    if (sep == std::string_view::npos) fail(shown(text) + " lacks '://' (e.g. tcp://127.0.0.1:5050)");
    const std::string_view scheme = text.substr(0, sep);
    HeadUri uri;
    const auto info = std::find_if(kSchemes.begin(), kSchemes.end(), [&](const auto& s) { return s.name == scheme; });
    if (info == kSchemes.end())
        fail("unknown scheme " + shown(scheme) + " (tcp, visca-udp, visca-tcp, visca-serial, pelco-d, onvif)");
    uri.scheme = info->scheme;
    uri.port = info->port;

    std::string_view rest = text.substr(sep + 3);
    std::string_view query;
    if (const auto q = rest.find('?'); q != std::string_view::npos) {
        query = rest.substr(q + 1);
        rest = rest.substr(0, q);
    }
    if (!rest.empty() && rest.back() == '/') rest.remove_suffix(1);
    if (uri.scheme == HeadScheme::Onvif) split_service_path(uri, rest);

    std::string_view host;
    std::string_view port;
    if (is_serial(uri.scheme)) {
        // visca-serial:///dev/ttyUSB0: an absolute device path of plain characters.
        if (!is_plain_path(rest)) fail("device " + shown(rest) + " is not an absolute path like /dev/ttyUSB0");
        uri.path = std::string(rest);
    } else if (!rest.empty() && rest.front() == '[') {
        const auto close = rest.find(']');
        if (close == std::string_view::npos) fail("IPv6 address lacks its closing ']'");
        host = rest.substr(1, close - 1);
        // At least one ':' and at most the 45 characters of the longest textual IPv6 address.
        if (host.size() > 45 || host.find(':') == std::string_view::npos ||
            !std::all_of(host.begin(), host.end(),
                         [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) || c == ':' || c == '.'; }))
            fail("IPv6 address " + shown(host) + " is malformed");
        const std::string_view after = rest.substr(close + 1);
        if (!after.empty()) {
            if (after.front() != ':') fail("expected ':port' after ']'");
            port = after.substr(1);
            if (port.empty()) fail("empty port");
        }
    } else {
        const auto colon = rest.rfind(':');
        host = rest.substr(0, colon);
        if (colon != std::string_view::npos) {
            port = rest.substr(colon + 1);
            if (port.empty()) fail("empty port");
        }
        if (host.empty()) fail("no host in " + shown(text));
        if (host.size() > 253 || !std::all_of(host.begin(), host.end(), is_host_char))
            fail("host " + shown(host) + " may contain only letters, digits, '-', '_' and '.'");
    }
    uri.host = std::string(host);
    if (!port.empty()) {
        unsigned value = 0;
        auto [ptr, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
        if (ec != std::errc{} || ptr != port.data() + port.size() || value == 0 || value > 65535)
            fail("port " + shown(port) + " is not a number in 1..65535");
        uri.port = static_cast<std::uint16_t>(value);
    }

    parse_query(uri, query, info->name);
    return uri;
}

std::vector<TextSpan> token_values(std::string_view text)
{
    // Every "token=" wherever it stands (a malformed URI may carry it outside its query),
    // in any case, up to the next separator.
    constexpr std::string_view kKey = "token=";
    auto is_key_at = [&](std::size_t i) {
        for (std::size_t k = 0; k < kKey.size(); ++k)
            if (std::tolower(static_cast<unsigned char>(text[i + k])) != kKey[k]) return false;
        return true;
    };
    auto ends_value = [](char c) { return c == '&' || c == '#' || c == '?' || c == '"' || c == '\'' || c <= 0x20; };
    std::vector<TextSpan> spans;
    for (std::size_t i = 0; i + kKey.size() <= text.size(); ++i) {
        if (!is_key_at(i)) continue;
        TextSpan value{i + kKey.size(), 0};
        while (value.offset + value.length < text.size() && !ends_value(text[value.offset + value.length]))
            ++value.length;
        spans.push_back(value);
        i = value.offset + value.length - 1;
    }
    return spans;
}

std::string redact_uri(std::string_view text)
{
    std::string out;
    std::size_t from = 0;
    for (const TextSpan& value : token_values(text)) {
        out.append(text.substr(from, value.offset - from)).append("***");
        from = value.offset + value.length;
    }
    return out.append(text.substr(from));
}

std::string to_string(const HeadUri& uri)
{
    const bool v6 = uri.host.find(':') != std::string::npos;
    std::string out = std::string(scheme_name(uri.scheme)) + "://";
    if (is_serial(uri.scheme))
        out += uri.path;
    else
        out += (v6 ? "[" + uri.host + "]" : uri.host) + ":" + std::to_string(uri.port) + uri.path;
    char sep = '?';
    for (const auto& [k, v] : uri.params) {
        out += sep + k + "=" + v;
        sep = '&';
    }
    return out;
}

}  // namespace gc::headctl
