// A strict reader for the JSON the tools write (RFC 8259 grammar; numbers as double), used
// to check their output: anything malformed throws std::runtime_error naming the offset.
#pragma once

#include <charconv>
#include <cstddef>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace gc::tools {

struct JsonValue {
    using Array = std::vector<JsonValue>;
    using Object = std::map<std::string, JsonValue, std::less<>>;
    std::variant<std::nullptr_t, bool, double, std::string, std::shared_ptr<Array>, std::shared_ptr<Object>> v =
        nullptr;

    bool is_null() const { return std::holds_alternative<std::nullptr_t>(v); }
    bool is_number() const { return std::holds_alternative<double>(v); }
    bool is_string() const { return std::holds_alternative<std::string>(v); }
    bool is_array() const { return std::holds_alternative<std::shared_ptr<Array>>(v); }
    bool is_object() const { return std::holds_alternative<std::shared_ptr<Object>>(v); }

    double number() const { return std::get<double>(v); }
    const std::string& string() const { return std::get<std::string>(v); }
    const Array& array() const { return *std::get<std::shared_ptr<Array>>(v); }
    const Object& object() const { return *std::get<std::shared_ptr<Object>>(v); }

    bool has(std::string_view key) const { return is_object() && object().contains(key); }
    const JsonValue& operator[](std::string_view key) const
    {
        const auto it = object().find(key);
        if (it == object().end()) throw std::out_of_range("no key '" + std::string(key) + "'");
        return it->second;
    }
    const JsonValue& operator[](std::size_t i) const { return array().at(i); }
};

class JsonReader {
public:
    // Parses one complete JSON text; trailing non-space characters are an error.
    static JsonValue parse(std::string_view text)
    {
        JsonReader r(text);
        JsonValue v = r.value(0);
        r.space();
        if (r.pos_ != text.size()) r.fail("trailing characters");
        return v;
    }

private:
    explicit JsonReader(std::string_view text) : s_(text) {}

    [[noreturn]] void fail(const std::string& what) const
    {
        throw std::runtime_error("JSON: " + what + " at offset " + std::to_string(pos_));
    }

    void space()
    {
        while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\n' || s_[pos_] == '\r'))
            ++pos_;
    }

    bool eat(char c)
    {
        space();
        if (pos_ < s_.size() && s_[pos_] == c) {
            ++pos_;
            return true;
        }
        return false;
    }

    void expect(char c)
    {
        if (!eat(c)) fail(std::string("expected '") + c + "'");
    }

    bool literal(std::string_view word)
    {
        if (s_.substr(pos_, word.size()) != word) return false;
        pos_ += word.size();
        return true;
    }

    JsonValue value(int depth)
    {
        if (depth > 64) fail("nesting too deep");
        space();
        if (pos_ >= s_.size()) fail("unexpected end");
        const char c = s_[pos_];
        JsonValue out;
        if (c == '{') {
            ++pos_;
            auto obj = std::make_shared<JsonValue::Object>();
            if (!eat('}')) {
                do {
                    space();
                    std::string key = string();
                    expect(':');
                    if (!obj->emplace(std::move(key), value(depth + 1)).second) fail("duplicate key");
                } while (eat(','));
                expect('}');
            }
            out.v = std::move(obj);
        } else if (c == '[') {
            ++pos_;
            auto arr = std::make_shared<JsonValue::Array>();
            if (!eat(']')) {
                do arr->push_back(value(depth + 1));
                while (eat(','));
                expect(']');
            }
            out.v = std::move(arr);
        } else if (c == '"') {
            out.v = string();
        } else if (literal("null")) {
            out.v = nullptr;
        } else if (literal("true")) {
            out.v = true;
        } else if (literal("false")) {
            out.v = false;
        } else {
            out.v = number();
        }
        return out;
    }

    std::string string()
    {
        if (pos_ >= s_.size() || s_[pos_] != '"') fail("expected a string");
        ++pos_;
        std::string out;
        while (pos_ < s_.size() && s_[pos_] != '"') {
            char c = s_[pos_++];
            if (static_cast<unsigned char>(c) < 0x20) fail("control character in a string");
            if (c == '\\') {
                if (pos_ >= s_.size()) fail("unfinished escape");
                c = s_[pos_++];
                switch (c) {
                case '"':
                case '\\':
                case '/':
                    out += c;
                    break;
                case 'n':
                    out += '\n';
                    break;
                case 't':
                    out += '\t';
                    break;
                case 'r':
                    out += '\r';
                    break;
                case 'b':
                    out += '\b';
                    break;
                case 'f':
                    out += '\f';
                    break;
                case 'u':
                    if (pos_ + 4 > s_.size()) fail("short \\u escape");
                    out += '?';  // the checks only need to know the escape is well formed
                    pos_ += 4;
                    break;
                default:
                    fail("bad escape");
                }
            } else {
                out += c;
            }
        }
        if (pos_ >= s_.size()) fail("unterminated string");
        ++pos_;
        return out;
    }

    double number()
    {
        // JSON's grammar is stricter than from_chars: no '+', no leading zeros, no "inf"/"nan".
        const std::size_t start = pos_;
        if (pos_ < s_.size() && s_[pos_] == '-') ++pos_;
        const auto digits = [&] {
            const std::size_t d = pos_;
            while (pos_ < s_.size() && s_[pos_] >= '0' && s_[pos_] <= '9') ++pos_;
            return pos_ - d;
        };
        const std::size_t int_start = pos_;
        const std::size_t n = digits();
        if (n == 0 || (n > 1 && s_[int_start] == '0')) fail("bad number");
        if (pos_ < s_.size() && s_[pos_] == '.') {
            ++pos_;
            if (digits() == 0) fail("bad fraction");
        }
        if (pos_ < s_.size() && (s_[pos_] == 'e' || s_[pos_] == 'E')) {
            ++pos_;
            if (pos_ < s_.size() && (s_[pos_] == '+' || s_[pos_] == '-')) ++pos_;
            if (digits() == 0) fail("bad exponent");
        }
        double v = 0.0;
        const auto res = std::from_chars(s_.data() + start, s_.data() + pos_, v);
        if (res.ec != std::errc()) fail("number out of range");
        return v;
    }

    std::string_view s_;
    std::size_t pos_ = 0;
};

}  // namespace gc::tools
