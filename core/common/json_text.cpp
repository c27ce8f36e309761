#include "common/json_text.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace gc::json {

void append_number(std::string& out, double v, int decimals)
{
    if (!std::isfinite(v)) {
        out += "null";
        return;
    }
    const double scale = std::pow(10.0, decimals);
    double rounded = std::round(v * scale) / scale;
    if (!std::isfinite(rounded)) rounded = v;  // so large that v * scale overflowed: nothing to round
    if (rounded == 0.0) rounded = 0.0;         // no "-0"
    // Fixed notation of the largest double needs 309 digits before the point.
    std::array<char, 352> buf{};
    const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), rounded, std::chars_format::fixed, decimals);
    std::string_view text(buf.data(), static_cast<std::size_t>(res.ptr - buf.data()));
    if (text.find('.') != std::string_view::npos) {
        while (text.back() == '0') text.remove_suffix(1);
        if (text.back() == '.') text.remove_suffix(1);
    }
    out.append(text);
}

void append_integer(std::string& out, std::int64_t v)
{
    std::array<char, 24> buf{};
    const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v);
    out.append(buf.data(), res.ptr);
}

void append_string(std::string& out, std::string_view s)
{
    out += '"';
    for (const char c : s) {
        switch (c) {
        case '"':
            out += "\\\"";
            break;
        case '\\':
            out += "\\\\";
            break;
        case '\n':
            out += "\\n";
            break;
        case '\t':
            out += "\\t";
            break;
        default:
            if (static_cast<unsigned char>(c) < 0x20) {
                char esc[8];
                std::snprintf(esc, sizeof esc, "\\u%04x", static_cast<unsigned>(c));
                out += esc;
            } else {
                out += c;
            }
        }
    }
    out += '"';
}

}  // namespace gc::json
