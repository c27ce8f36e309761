// A lexical pre-check of FileStorage text. OpenCV 4.6's YAML and XML parsers crash (null
// dereference, or an exception escaping a noexcept path) on a few malformed inputs, such as
// an XML attribute cut after '=' or a YAML key of zero length; this check finds those
// constructs first so that a broken file is reported, never fatal.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace gc {

// Nullopt when the text is safe to hand to cv::FileStorage; otherwise what is wrong with it.
std::optional<std::string> file_storage_hazard(std::string_view text);

}  // namespace gc
