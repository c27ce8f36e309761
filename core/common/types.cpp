#include "common/types.hpp"

#include "common/enum_names.hpp"

#include <cmath>

namespace gc {

namespace {

constexpr EnumNames<TrackState, 3> kTrackStates{{
    {TrackState::Acquiring, "acquiring"},
    {TrackState::Tracking, "tracking"},
    {TrackState::Lost, "lost"},
}};

constexpr EnumNames<Gesture, 5> kGestures{{
    {Gesture::Unknown, "unknown"},
    {Gesture::Pointing, "pointing"},
    {Gesture::Open, "open"},
    {Gesture::Fist, "fist"},
    {Gesture::Other, "other"},
}};

// Far below anything a frame shows (a millionth of a pixel), far above rounding residue.
constexpr double kLeastShiftPx = 1e-6;
constexpr double kLeastTurn = 1e-9;  // radians, and relative scale change

}  // namespace

bool ImageMotion::moves() const
{
    return std::abs(dx) > kLeastShiftPx || std::abs(dy) > kLeastShiftPx || std::abs(drotation) > kLeastTurn ||
           std::abs(scale_factor - 1.0) > kLeastTurn;
}

std::string_view to_string(TrackState s) { return name_in(kTrackStates, s, "lost"); }

std::string_view to_string(Gesture g) { return name_in(kGestures, g, "unknown"); }

}  // namespace gc
