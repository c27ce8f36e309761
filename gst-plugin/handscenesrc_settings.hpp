// handscenesrc's properties: their values, the GParamSpecs that describe them, the enum
// types they use, and the copy between GValues and the values.
#pragma once

#include "common/types.hpp"
#include "sim/scene.hpp"

#include <glib-object.h>

#include <optional>
#include <string>

namespace gc::gst {

constexpr guint64 kDefaultSceneSeed = 1;
constexpr double kDefaultSceneNoise = 2.0;

// Property values, read and written under the object lock.
struct SceneSettings {
    Eye eye = Eye::Left;
    sim::Preset preset = sim::Preset::Clean;
    sim::Motion motion = sim::Motion::Mixed;
    guint64 seed = kDefaultSceneSeed;
    double noise = kDefaultSceneNoise;
    bool lighting_change = false;
    sim::Variety variety = sim::Variety::None;
    Gesture gesture = Gesture::Pointing;
    double gesture_cycle_s = 0.0;
    bool truth_messages = true;
    std::string head;             // URI of the head the cameras sit on; empty: a fixed rig
    std::string head_token_file;  // empty: the URI's token, if any
    HeadPose rig;                 // the fixed rig's pose (head-pan, head-tilt)
    std::optional<cv::Vec3d> aim;  // where the hand points at rest (head frame, mm); unset: the seed's
};

// The is-live property, which basesrc holds rather than SceneSettings.
bool is_live_property(guint prop_id);

// Installs every property of the element's class.
void install_scene_properties(GObjectClass* klass);
// Marks the properties' enum types as plugin API (documented with the element).
void mark_scene_enums_as_plugin_api();

// Stores `value` as property `prop_id`; false for an unknown id.
bool set_scene_setting(SceneSettings& s, guint prop_id, const GValue* value);
// Reads property `prop_id` into `value`; false for an unknown id.
bool get_scene_setting(const SceneSettings& s, guint prop_id, GValue* value);

}  // namespace gc::gst
