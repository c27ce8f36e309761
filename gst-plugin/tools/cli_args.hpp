// Option values shared by the tools (CLI11 reads the command line, tools/cli_app.hpp): strict
// numbers (the whole text must parse, inside the allowed range) and comma-separated lists.
#pragma once

#include <charconv>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace gc::cli {

// A wrong command line; the tools print the message on one line and exit with status 2.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
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
T parse_number(std::string_view option, std::string_view text, T min = std::numeric_limits<T>::lowest(),
               T max = std::numeric_limits<T>::max())
{
    T v{};
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, v);
    const auto quoted = [&] { return std::string(option) + " value '" + std::string(text) + "'"; };
    if (text.empty() || ec == std::errc::invalid_argument || ptr != end)
        throw UsageError(quoted() + " is not a number");
    if (ec == std::errc::result_out_of_range || v < min || v > max || v != v)
        throw UsageError(quoted() + " is out of range [" + number_text(min) + ", " + number_text(max) + "]");
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
        if (item.empty()) throw UsageError(std::string(option) + " has an empty item in its list");
        out.push_back(parse_item(option, item));
        if (comma == std::string_view::npos) break;
        text.remove_prefix(comma + 1);
    }
    return out;
}

}  // namespace gc::cli
