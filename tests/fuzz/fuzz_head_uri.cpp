// Fuzzes head URI parsing: any text either parses or throws std::invalid_argument; what
// parses prints to a URI that parses back to the same parts. Redacting any text leaves no
// token value other than "***".
#include "headctl/uri.hpp"
#include "headctl/visca_backend.hpp"

#include <cstdint>
#include <cstdlib>
#include <string>

using namespace gc::headctl;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string text(reinterpret_cast<const char*>(data), size);
    const std::string shown = redact_uri(text);
    for (const TextSpan& value : token_values(shown))
        if (shown.compare(value.offset, value.length, "***") != 0) std::abort();
    HeadUri uri;
    try {
        uri = parse_head_uri(text);
    } catch (const std::invalid_argument&) {
        return 0;
    }
    const HeadUri again = parse_head_uri(to_string(uri));
    if (again.scheme != uri.scheme || again.host != uri.host || again.port != uri.port || again.path != uri.path ||
        again.params != uri.params)
        std::abort();
    if (uri.scheme != HeadScheme::Gchp) {
        try {
            ViscaSettings::from_uri(uri);
        } catch (const std::invalid_argument&) {
        }
    }
    return 0;
}
