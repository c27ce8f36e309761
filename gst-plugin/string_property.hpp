// Optional string properties as the elements keep them: unset (NULL) is the empty string,
// both ways.
#pragma once

#include <glib-object.h>

#include <string>

namespace gc::gst {

inline std::string string_value(const GValue* value)
{
    const gchar* text = g_value_get_string(value);
    return text ? text : "";
}

inline void set_string_value(GValue* value, const std::string& text)
{
    g_value_set_string(value, text.empty() ? nullptr : text.c_str());
}

}  // namespace gc::gst
