#include "common/types.hpp"

namespace gc {

std::string_view to_string(TrackState s)
{
    switch (s) {
    case TrackState::Acquiring:
        return "acquiring";
    case TrackState::Tracking:
        return "tracking";
    case TrackState::Lost:
        return "lost";
    }
    return "lost";
}

std::string_view to_string(Gesture g)
{
    switch (g) {
    case Gesture::Unknown:
        return "unknown";
    case Gesture::Pointing:
        return "pointing";
    case Gesture::Open:
        return "open";
    case Gesture::Fist:
        return "fist";
    case Gesture::Other:
        return "other";
    }
    return "unknown";
}

}  // namespace gc
