#include "stereo/file_storage_guard.hpp"

#include <cstddef>

namespace gc {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

std::string at_line(std::string_view text, std::size_t pos)
{
    std::size_t line = 1;
    for (std::size_t i = 0; i < pos && i < text.size(); ++i) line += text[i] == '\n';
    return " (line " + std::to_string(line) + ")";
}

// Every tag must close, and every attribute's '=' must be followed by a quoted value.
std::optional<std::string> xml_hazard(std::string_view text)
{
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] != '<') continue;
        if (text.substr(i, 4) == "<!--") {
            const std::size_t end = text.find("-->", i + 4);
            if (end == std::string_view::npos) return "unterminated comment" + at_line(text, i);
            i = end + 2;
            continue;
        }
        const std::size_t start = i;
        char quote = 0;
        for (++i; i < text.size(); ++i) {
            const char c = text[i];
            if (quote) {
                if (c == quote) quote = 0;
            } else if (c == '"' || c == '\'') {
                quote = c;
            } else if (c == '=') {
                std::size_t j = i + 1;
                while (j < text.size() && is_space(text[j])) ++j;
                if (j >= text.size() || (text[j] != '"' && text[j] != '\''))
                    return "attribute without a quoted value" + at_line(text, i);
            } else if (c == '>') {
                break;
            } else if (c == '<') {
                return "'<' inside a tag" + at_line(text, i);
            }
        }
        if (i >= text.size()) return "unterminated tag" + at_line(text, start);
    }
    return std::nullopt;
}

// No mapping key may be empty: a ':' value indicator directly after the start of a line,
// '{', ',' or '-' (ignoring blanks), outside quotes and comments. Flow collections ('[ ]',
// '{ }') must nest properly and close before the end of the text: the parser never returns
// from one cut at the end of the file.
std::optional<std::string> yaml_hazard(std::string_view text)
{
    char prev = '\n';  // last significant character
    char quote = 0;
    bool comment = false;
    std::string open_flows;  // the flow brackets not yet closed, innermost last
    std::size_t first_open = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '\n') {
            comment = false;
            quote = 0;
            prev = '\n';
            continue;
        }
        if (comment) continue;
        if (quote) {
            if (c == quote) quote = 0;
            prev = 'x';
            continue;
        }
        if (c == ' ' || c == '\t' || c == '\r') continue;
        if (c == '#') {
            comment = true;
            continue;
        }
        // Not YAML at all; the reader loops forever on such a line among indented keys.
        if (c == '<' && prev == '\n') return "a line starting with '<'" + at_line(text, i);
        if (c == '"' || c == '\'') {
            quote = c;
            continue;
        }
        if (c == ':' && (prev == '\n' || prev == '{' || prev == ',' || prev == '-')) return "empty key" + at_line(text, i);
        if (c == '\0') return "NUL byte" + at_line(text, i);
        if (c == '[' || c == '{') {
            if (open_flows.empty()) first_open = i;
            open_flows += c;
        } else if (c == ']' || c == '}') {
            const char opener = c == ']' ? '[' : '{';
            if (open_flows.empty() || open_flows.back() != opener)
                return std::string("unbalanced '") + c + "'" + at_line(text, i);
            open_flows.pop_back();
        }
        prev = c;
    }
    if (quote) return std::string("unterminated quoted string");
    if (!open_flows.empty()) return "unterminated '" + std::string(1, open_flows.back()) + "'" + at_line(text, first_open);
    return std::nullopt;
}

}  // namespace

std::optional<std::string> file_storage_hazard(std::string_view text)
{
    // cv::FileStorage picks the parser from the first bytes: "<?xml" is XML, "{" JSON,
    // anything else YAML.
    std::string_view head = text;
    if (head.substr(0, 3) == "\xEF\xBB\xBF") head.remove_prefix(3);
    if (head.substr(0, 5) == "<?xml") return xml_hazard(text);
    if (head.substr(0, 1) == "{") return std::nullopt;
    return yaml_hazard(text);
}

}  // namespace gc
