// Fuzzes the Pelco-D report parser: any seven bytes either parse (to a report or to nothing)
// or throw PelcoError; a parsed pan or tilt report re-encodes to the same bytes through the
// matching set-position message.
#include "headctl/pelco_d.hpp"

#include <cstdint>
#include <cstdlib>

using namespace gc::headctl;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size < 7) return 0;
    const std::span<const std::uint8_t, 7> m(data, 7);
    try {
        const auto r = pelco::parse_report(m);
        if (r && r->value <= 35999 && r->address >= 1 && r->reading != pelco::Reading::Zoom) {
            const auto again = r->reading == pelco::Reading::Pan ? pelco::set_pan(r->address, r->value)
                                                                 : pelco::set_tilt(r->address, r->value);
            if (again[4] != m[4] || again[5] != m[5] || again[1] != m[1]) std::abort();
        }
    } catch (const pelco::PelcoError&) {
    }
    return 0;
}
