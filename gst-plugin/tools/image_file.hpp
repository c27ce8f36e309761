// Reading one image file for the tools, within the product's frame-size limit: the size a
// PNG or JPEG header declares is checked before decoding, any other format's after.
#pragma once

#include "common/frame_limits.hpp"
#include "tools/image_header.hpp"

#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

namespace gc::tools {

// An input that cannot be used; the message names the input and the cause.
class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Throws InputError, prefixed with `what`, when `size` exceeds kMaxFrameSide on either side.
inline void check_frame_size(cv::Size size, const std::string& what)
{
    if (size.width <= kMaxFrameSide && size.height <= kMaxFrameSide) return;
    const std::string limit = std::to_string(kMaxFrameSide);
    throw InputError(what + ": " + std::to_string(size.width) + "x" + std::to_string(size.height) +
                     " is larger than the limit of " + limit + "x" + limit + " pixels");
}

// The image at `path` as cv::imread(path, flags) gives it; empty when it cannot be decoded.
// Throws InputError (prefixed with `what`) for a path that is not a regular file and for an
// image larger than kMaxFrameSide a side, before decoding when the header says so.
inline cv::Mat read_image_file(const std::string& path, int flags, const std::string& what)
{
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw InputError(what + ": '" + path + "' is not a regular file");
    if (const std::optional<cv::Size> declared = image_file_size(path)) check_frame_size(*declared, what);
    cv::Mat image = cv::imread(path, flags);
    check_frame_size(image.size(), what);
    return image;
}

}  // namespace gc::tools
