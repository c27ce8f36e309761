// Flat JSON objects for the tools' machine-readable output: one object per line, numbers
// written with std::to_chars (independent of the locale), non-finite numbers as null.
#pragma once

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace gc::tools {

class JsonObject {
public:
    JsonObject& add(std::string_view key, std::string_view text)
    {
        open(key);
        quote(text);
        return *this;
    }
    JsonObject& add(std::string_view key, const char* text) { return add(key, std::string_view(text)); }

    JsonObject& add(std::string_view key, std::int64_t v)
    {
        open(key);
        std::array<char, 24> buf{};
        const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v);
        out_.append(buf.data(), res.ptr);
        return *this;
    }
    JsonObject& add(std::string_view key, int v) { return add(key, static_cast<std::int64_t>(v)); }

    JsonObject& add(std::string_view key, bool v)
    {
        open(key);
        out_ += v ? "true" : "false";
        return *this;
    }

    // At most `decimals` digits after the point.
    JsonObject& add(std::string_view key, double v, int decimals)
    {
        open(key);
        if (!std::isfinite(v)) {
            out_ += "null";
            return *this;
        }
        // Fixed notation of the largest double needs 309 digits before the point.
        std::array<char, 352> buf{};
        const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v,
                                       std::chars_format::fixed, decimals);
        std::string_view text(buf.data(), static_cast<std::size_t>(res.ptr - buf.data()));
        if (text.find('.') != std::string_view::npos) {
            while (text.back() == '0')
                text.remove_suffix(1);
            if (text.back() == '.')
                text.remove_suffix(1);
        }
        if (text == "-0")
            text = "0";
        out_.append(text);
        return *this;
    }

    std::string str() const { return out_ + '}'; }

private:
    void open(std::string_view key)
    {
        out_ += out_.size() == 1 ? "" : ",";
        quote(key);
        out_ += ':';
    }

    void quote(std::string_view s)
    {
        out_ += '"';
        for (const char c : s) {
            switch (c) {
            case '"': out_ += "\\\""; break;
            case '\\': out_ += "\\\\"; break;
            case '\n': out_ += "\\n"; break;
            case '\t': out_ += "\\t"; break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) {
                    char esc[8];
                    std::snprintf(esc, sizeof esc, "\\u%04x", static_cast<unsigned>(c));
                    out_ += esc;
                } else {
                    out_ += c;
                }
            }
        }
        out_ += '"';
    }

    std::string out_ = "{";
};

}  // namespace gc::tools
