// Command-line parsing shared by the tools: "--name value" and "--name=value" options, strict
// numbers (the whole text must parse, inside the allowed range) and comma-separated lists.
#pragma once

#include <charconv>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace gc::cli {

// A wrong command line; the tools print the message and the usage, and exit with status 2.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Walks argv option by option.
class ArgReader {
public:
    ArgReader(int argc, char** argv) : args_(argv + 1, argc > 0 ? argc - 1 : 0) {}

    // Moves to the next option; false when there is none left.
    bool next()
    {
        if (pos_ >= args_.size())
            return false;
        std::string_view arg = args_[pos_++];
        if (!arg.starts_with("--") || arg.size() == 2)
            throw UsageError("unexpected argument '" + std::string(arg) + "' (options start with --)");
        const std::size_t eq = arg.find('=');
        name_ = arg.substr(0, eq);
        has_inline_ = eq != std::string_view::npos;
        inline_value_ = has_inline_ ? arg.substr(eq + 1) : std::string_view{};
        return true;
    }

    std::string_view name() const { return name_; }

    // The option's value: after '=' or the next argument.
    std::string_view value()
    {
        if (has_inline_) {
            has_inline_ = false;
            return inline_value_;
        }
        if (pos_ >= args_.size())
            throw UsageError("option " + std::string(name_) + " needs a value");
        return args_[pos_++];
    }

    // For options that take no value.
    void no_value() const
    {
        if (has_inline_)
            throw UsageError("option " + std::string(name_) + " takes no value");
    }

private:
    std::span<char*> args_;
    std::size_t pos_ = 0;
    std::string_view name_;
    std::string_view inline_value_;
    bool has_inline_ = false;
};

// The shortest text that reads back as `v` (locale-independent).
template <typename T>
std::string number_text(T v)
{
    char buf[64];
    const auto res = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, res.ptr);
}

template <typename T>
T parse_number(std::string_view option, std::string_view text,
               T min = std::numeric_limits<T>::lowest(), T max = std::numeric_limits<T>::max())
{
    T v{};
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, v);
    const auto quoted = [&] { return std::string(option) + " value '" + std::string(text) + "'"; };
    if (text.empty() || ec == std::errc::invalid_argument || ptr != end)
        throw UsageError(quoted() + " is not a number");
    if (ec == std::errc::result_out_of_range || v < min || v > max || v != v)
        throw UsageError(quoted() + " is out of range [" + number_text(min) + ", " +
                         number_text(max) + "]");
    return v;
}

// Comma-separated items, each turned into a T by `parse_item(option, item)`; no empty items.
template <typename T, typename F>
std::vector<T> parse_list(std::string_view option, std::string_view text, F parse_item)
{
    std::vector<T> out;
    while (true) {
        const std::size_t comma = text.find(',');
        const std::string_view item = text.substr(0, comma);
        if (item.empty())
            throw UsageError(std::string(option) + " has an empty item in its list");
        out.push_back(parse_item(option, item));
        if (comma == std::string_view::npos)
            break;
        text.remove_prefix(comma + 1);
    }
    return out;
}

}  // namespace gc::cli
