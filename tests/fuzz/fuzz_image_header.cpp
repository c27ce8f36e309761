// libFuzzer entry point for the image-header reader of the tools (gst-plugin/tools/image_header.hpp):
// arbitrary bytes as the start of an image file. It may only answer with a positive size or
// nothing, without reading outside the bytes.
#include "tools/image_header.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    if (const auto declared = gc::tools::image_header_size(bytes)) {
        if (declared->width <= 0 || declared->height <= 0) std::abort();
    }
    return 0;
}
