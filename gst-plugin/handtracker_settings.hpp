// handtracker's properties: their values, the GParamSpecs that describe them, the enum
// types they use, and the copy between GValues and the values.
#pragma once

#include "gsthandtracker.hpp"

#include "common/frame_limits.hpp"
#include "headctl/steering/head_link.hpp"
#include "tracker/hand_tracker.hpp"

#include <glib-object.h>
#include <gst/video/video.h>

#include <string>

namespace gc::gst {

constexpr int kDefaultParticles = 1000;
constexpr int kMaxParticles = 100000;
constexpr guint64 kDefaultSeed = 1;
constexpr int kMaxTrackingWidth = gc::kMaxFrameSide;
constexpr double kDefaultLostThreshold = 0.6;
constexpr int kDefaultLostFrames = 3;
constexpr GstHandTrackerOutput kDefaultOutput = GST_HAND_TRACKER_OUTPUT_LEFT;
constexpr GstHandTrackerMessageUpdates kDefaultMessageUpdates = GST_HAND_TRACKER_MESSAGES_EVERY_FRAME;
constexpr gc::headctl::SteerMode kDefaultSteer = gc::headctl::SteerMode::Fixate;
constexpr double kDefaultTargetDistanceMm = 2000.0;
constexpr double kDefaultDwellS = 1.0;
constexpr double kDefaultTargetRegionMm = 500.0;
constexpr double kDefaultLookS = 4.0;
constexpr double kDefaultManualPauseS = 10.0;

// Property values, read and written under the object lock.
struct TrackerSettings {
    int particles = kDefaultParticles;
    int tracking_width = 0;  // views wider than this are tracked scaled down to it; 0: at their size
    guint64 seed = kDefaultSeed;
    std::string calibration;  // empty: the nominal rig for the stream's size
    GstHandTrackerOutput output = kDefaultOutput;
    bool draw = false;
    double lost_threshold = kDefaultLostThreshold;
    int lost_frames = kDefaultLostFrames;
    GstHandTrackerMessageUpdates message_updates = kDefaultMessageUpdates;
    std::string json_location;
    std::string head;             // the head's URI; empty: no head
    std::string head_token_file;  // empty: the URI's token, if any
    gc::headctl::SteerMode steer = kDefaultSteer;
    gc::TargetPlacement target{kDefaultTargetDistanceMm, {}};  // where a held pointing's target lies
    double dwell_s = kDefaultDwellS;                           // a pointing held this long picks the attended target
    double target_region_mm = kDefaultTargetRegionMm;          // the width the attended view frames there
    int home_preset = -1;                          // the head's preset that steering returns to; -1: its home position
    double widen_after_s = 0.0;                    // lost this long, the head zooms out; 0: never
    double home_after_s = 2.0;                     // lost this long, the head goes home (or to home_preset)
    double look_s = kDefaultLookS;                 // steer=point: how long the head looks at a target
    double manual_pause_s = kDefaultManualPauseS;  // someone else moved the head: steering waits this long
    std::string director;                          // a second PTZ camera's URI; empty: none
    int director_home_preset = -1;                 // where it goes when a target is released; -1: its home position
    std::string director_token_file;               // empty: the director URI's token, if any
    gc::HandDetector detector = gc::HandDetector::Learned;
    std::string model_dir;  // empty: the learned models are found without configuration
    // How `sink` frames hold both views when their caps do not say (or say wrongly).
    GstVideoMultiviewFramePacking input_mode_override = GST_VIDEO_MULTIVIEW_FRAME_PACKING_NONE;
    GstVideoMultiviewFlags input_flags_override = GST_VIDEO_MULTIVIEW_FLAGS_NONE;
};

// The id of the read-only `stats` property (TrackerStats), after those of the settings.
constexpr guint kStatsProperty = 100;

// Installs every property of the element's class.
void install_tracker_properties(GObjectClass* klass);
// Marks the properties' enum types as plugin API (documented with the element).
void mark_tracker_enums_as_plugin_api();

// Stores `value` as property `prop_id`; false for an unknown id. `rebuild` is set when the
// change needs a new tracker.
bool set_tracker_setting(TrackerSettings& s, guint prop_id, const GValue* value, bool& rebuild);
// Reads property `prop_id` into `value`; false for an unknown id.
bool get_tracker_setting(const TrackerSettings& s, guint prop_id, GValue* value);

}  // namespace gc::gst
