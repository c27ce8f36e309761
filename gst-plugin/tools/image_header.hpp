// The image size a PNG or JPEG file declares in its header, read from its first bytes before
// anything is decoded: a small file that claims a huge image is refused without allocating
// it. Fuzzed by tests/fuzz/fuzz_image_header.cpp.
#pragma once

#include <opencv2/core/types.hpp>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>

namespace gc::tools {

namespace image_header_detail {

inline std::uint32_t big_endian(std::string_view b, std::size_t at, int bytes)
{
    std::uint32_t v = 0;
    for (int i = 0; i < bytes; ++i) v = (v << 8) | static_cast<unsigned char>(b[at + static_cast<std::size_t>(i)]);
    return v;
}

// PNG: the signature, then the IHDR chunk whose first fields are the width and the height.
inline std::optional<cv::Size> png_size(std::string_view b)
{
    if (b.size() < 24 || b.substr(0, 8) != std::string_view("\x89PNG\r\n\x1a\n", 8) || b.substr(12, 4) != "IHDR")
        return std::nullopt;
    const std::uint32_t w = big_endian(b, 16, 4), h = big_endian(b, 20, 4);
    // The PNG limit is 2^31 - 1 a side; larger is not a PNG.
    if (w == 0 || h == 0 || w > 0x7fffffffu || h > 0x7fffffffu) return std::nullopt;
    return cv::Size(static_cast<int>(w), static_cast<int>(h));
}

// JPEG: walks the marker segments from SOI to the first start-of-frame (SOF0..SOF15 but
// DHT, JPG and DAC), which holds the height and the width.
inline std::optional<cv::Size> jpeg_size(std::string_view b)
{
    if (b.size() < 4 || static_cast<unsigned char>(b[0]) != 0xFF || static_cast<unsigned char>(b[1]) != 0xD8)
        return std::nullopt;
    std::size_t at = 2;
    while (at + 4 <= b.size()) {
        if (static_cast<unsigned char>(b[at]) != 0xFF) return std::nullopt;
        const unsigned marker = static_cast<unsigned char>(b[at + 1]);
        if (marker == 0xFF) {  // fill byte
            ++at;
            continue;
        }
        if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {  // no length field
            at += 2;
            continue;
        }
        if (marker == 0xD9 || marker == 0xDA)  // end of image or scan data before any frame
            return std::nullopt;
        const std::size_t length = big_endian(b, at + 2, 2);
        if (length < 2) return std::nullopt;
        const bool frame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
        if (frame) {
            if (length < 7 || at + 9 > b.size()) return std::nullopt;
            const std::uint32_t h = big_endian(b, at + 5, 2), w = big_endian(b, at + 7, 2);
            // A height of 0 is given later (DNL): unknown here.
            if (w == 0 || h == 0) return std::nullopt;
            return cv::Size(static_cast<int>(w), static_cast<int>(h));
        }
        at += 2 + length;
    }
    return std::nullopt;
}

}  // namespace image_header_detail

// The size declared by the PNG or JPEG header at the start of `bytes`; nullopt for other
// formats, or when the header is not (entirely) within `bytes`.
inline std::optional<cv::Size> image_header_size(std::string_view bytes)
{
    if (auto png = image_header_detail::png_size(bytes)) return png;
    return image_header_detail::jpeg_size(bytes);
}

// Bytes read from the start of a file to find its header: JPEG metadata segments (EXIF, ICC,
// XMP) before the frame header rarely exceed this.
inline constexpr std::size_t kImageHeaderBytes = 256 * 1024;

// The size the header of the image file at `path` declares; nullopt when unknown.
inline std::optional<cv::Size> image_file_size(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::string head(kImageHeaderBytes, '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
    return image_header_size(head);
}

}  // namespace gc::tools
