// Fuzzes the GCHP/1 parsers: any input either parses or throws ProtocolError; what parses
// formats to a line that parses back to the same line (formatting is a fixed point).
#include "headctl/protocol.hpp"

#include <cstdint>
#include <cstdlib>
#include <string>

using namespace gc::headctl;

namespace {

void check(bool ok)
{
    if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string_view line(reinterpret_cast<const char*>(data), size);
    peek_request_id(line);
    try {
        const std::string once = format_request(parse_request(line));
        check(once.size() <= kMaxLineLength);
        check(format_request(parse_request(once)) == once);
    } catch (const ProtocolError&) {
    }
    try {
        const std::string once = format_reply(parse_reply(line));
        check(once.size() <= kMaxLineLength);
        check(format_reply(parse_reply(once)) == once);
    } catch (const ProtocolError&) {
    }
    try {
        const std::string once = format_greeting(parse_greeting(line));
        check(parse_greeting(once) == parse_greeting(line));
    } catch (const ProtocolError&) {
    }
    return 0;
}
