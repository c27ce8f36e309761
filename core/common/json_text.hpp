// JSON scalars for the product's machine-readable output (gesturecam-track lines, bench rows):
// independent of the locale, every line valid JSON.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace gc::json {

// At most `decimals` digits after the point (rounded), trailing zeros and "-0" dropped;
// a non-finite value is written as null.
void append_number(std::string& out, double v, int decimals);
void append_integer(std::string& out, std::int64_t v);
// A quoted, escaped string.
void append_string(std::string& out, std::string_view s);

}  // namespace gc::json
