#include "head_uri_property.hpp"

#include "headctl/token.hpp"
#include "headctl/uri.hpp"

#include <exception>

namespace gc::gst {

void set_head_uri(std::string& uri, const GValue* value)
{
    const gchar* text = g_value_get_string(value);
    const std::string given = text ? text : "";
    if (given != headctl::redact_uri(uri)) uri = given;
}

void get_head_uri(const std::string& uri, GValue* value)
{
    g_value_set_string(value, uri.empty() ? nullptr : headctl::redact_uri(uri).c_str());
}

bool read_head_token(GstElement* element, const std::string& path, std::string& token)
{
    token.clear();
    if (path.empty()) return true;
    try {
        token = headctl::read_token_file(path);
    } catch (const std::exception& err) {
        GST_ELEMENT_ERROR(element, RESOURCE, OPEN_READ, ("Cannot read the head token file \"%s\".", path.c_str()),
                          ("%s", err.what()));
        return false;
    }
    return true;
}

}  // namespace gc::gst
