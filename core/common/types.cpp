#include "common/types.hpp"

#include "common/enum_names.hpp"

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

}  // namespace

std::string_view to_string(TrackState s) { return name_in(kTrackStates, s, "lost"); }

std::string_view to_string(Gesture g) { return name_in(kGestures, g, "unknown"); }

}  // namespace gc
