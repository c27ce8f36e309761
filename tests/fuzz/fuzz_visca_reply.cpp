// Fuzzes the VISCA reply parser and the VISCA-over-IP unwrapping: any bytes either parse or
// throw ViscaError; a parsed pan-tilt or zoom position re-encodes to the same nibbles.
#include "headctl/visca.hpp"

#include <cstdint>
#include <cstdlib>

using namespace gc::headctl;

namespace {

void parse(std::span<const std::uint8_t> bytes)
{
    try {
        const visca::Reply r = visca::parse_reply(bytes);
        if (r.kind == visca::ReplyKind::Position) {
            // The inquiry's own encoder must reproduce the nibbles it was parsed from.
            const auto again = visca::pan_tilt_absolute(1, 1, 1, r.pan_units, r.tilt_units);
            for (std::size_t i = 0; i < 8; ++i)
                if (again[6 + i] != bytes[2 + i]) std::abort();
        }
        if (r.kind == visca::ReplyKind::ZoomPosition) {
            const auto again = visca::zoom_direct(1, r.zoom_units);
            for (std::size_t i = 0; i < 4; ++i)
                if (again[4 + i] != bytes[2 + i]) std::abort();
        }
        visca::describe_error(r.error);
    } catch (const visca::ViscaError&) {
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::span<const std::uint8_t> bytes(data, size);
    parse(bytes);
    try {
        const visca::IpMessage m = visca::unwrap_ip(bytes);
        parse(m.payload);
        if (visca::wrap_ip(m.payload_type, m.sequence, m.payload) != visca::Bytes(bytes.begin(), bytes.end()))
            std::abort();
    } catch (const visca::ViscaError&) {
    }
    return 0;
}
