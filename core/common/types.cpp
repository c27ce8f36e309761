#include "common/types.hpp"

namespace gc {

std::string_view to_string(TrackState s)
{
    switch (s) {
    case TrackState::Acquiring: return "acquiring";
    case TrackState::Tracking: return "tracking";
    case TrackState::Lost: return "lost";
    }
    return "lost";
}

}  // namespace gc
