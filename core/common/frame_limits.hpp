// The largest frame the product accepts, shared by the tools and the handtracker element.
#pragma once

namespace gc {

// Pixels per side. One 8192 x 8192 BGR copy is already 200 MB and the tracker keeps several;
// a larger frame is refused with its size named rather than exhausting memory.
inline constexpr int kMaxFrameSide = 8192;

}  // namespace gc
