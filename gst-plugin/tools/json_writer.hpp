// Flat JSON objects for the tools' machine-readable output: one object per line, numbers
// written with std::to_chars (independent of the locale), non-finite numbers as null.
#pragma once

#include "common/json_text.hpp"

#include <cstdint>
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
        json::append_integer(out_, v);
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
        json::append_number(out_, v, decimals);
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

    void quote(std::string_view s) { json::append_string(out_, s); }

    std::string out_ = "{";
};

}  // namespace gc::tools
