// The files of a printf image-sequence pattern such as left/%05d.png: one %d conversion
// (optionally zero-padded to a width), numbered from 0 or 1 without gaps. The names are
// built here rather than by printf, so that a pattern is never a format string.
#pragma once

#include "tools/image_file.hpp"

#include <cctype>
#include <cstdint>
#include <filesystem>
#include <string>

namespace gc::tools {

class ImageSequence {
public:
    // Throws InputError (prefixed with `what`) for a pattern without exactly one %[0][width]d
    // and for one that matches no file at index 0 or 1.
    ImageSequence(const std::string& pattern, const std::string& what)
    {
        const std::size_t at = pattern.find('%');
        std::size_t end = at + 1;
        zero_pad_ = end < pattern.size() && pattern[end] == '0';
        end += zero_pad_ ? 1 : 0;
        while (end < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[end])) && width_ < 100)
            width_ = width_ * 10 + (pattern[end++] - '0');
        if (at == std::string::npos || end >= pattern.size() || pattern[end] != 'd' ||
            pattern.find('%', end) != std::string::npos || width_ > 20)
            throw InputError(what + ": the pattern must hold one %d conversion, such as %05d");
        prefix_ = pattern.substr(0, at);
        suffix_ = pattern.substr(end + 1);
        std::error_code ec;
        first_ = std::filesystem::exists(path(0), ec) ? 0 : 1;
        while (std::filesystem::exists(path(length_), ec)) ++length_;
        if (length_ == 0)
            throw InputError(what + ": no image matches the pattern (the sequence must start at index 0 or 1)");
    }

    // The file of frame `index` (counted from the first file of the sequence).
    std::string path(std::int64_t index) const
    {
        std::string number = std::to_string(first_ + index);
        if (number.size() < static_cast<std::size_t>(width_))
            number.insert(0, static_cast<std::size_t>(width_) - number.size(), zero_pad_ ? '0' : ' ');
        return prefix_ + number + suffix_;
    }

    std::int64_t length() const { return length_; }

private:
    std::string prefix_;
    std::string suffix_;
    bool zero_pad_ = false;
    int width_ = 0;
    std::int64_t first_ = 0;
    std::int64_t length_ = 0;
};

}  // namespace gc::tools
