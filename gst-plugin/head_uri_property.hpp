// The `head` and `head-token-file` properties as both elements with a head keep them: a
// token in the URI never reads back (it shows as token=***), and setting back what was read
// keeps the URI with its token, so a pipeline's properties can be copied without losing it.
#pragma once

#include <gst/gst.h>

#include <string>

namespace gc::gst {

// Stores `value` as the head URI, unless it is what reading the property gave.
void set_head_uri(std::string& uri, const GValue* value);
// The URI as the property reads back: its token hidden; unset when empty.
void get_head_uri(const std::string& uri, GValue* value);

// The token in `path` (empty path: none). False, with a GST_RESOURCE_ERROR_OPEN_READ posted
// that names the file (never its content), when it cannot be read.
bool read_head_token(GstElement* element, const std::string& path, std::string& token);

}  // namespace gc::gst
