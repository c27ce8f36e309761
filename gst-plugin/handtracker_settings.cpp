#include "handtracker_settings.hpp"

#include "head_uri_property.hpp"
#include "string_property.hpp"
#include "target_plane_property.hpp"
#include "headctl/head_backend.hpp"

namespace gc::gst {

namespace {

enum {
    PROP_0,
    PROP_PARTICLES,
    PROP_SEED,
    PROP_CALIBRATION,
    PROP_OUTPUT,
    PROP_DRAW,
    PROP_LOST_THRESHOLD,
    PROP_LOST_FRAMES,
    PROP_MESSAGE_UPDATES,
    PROP_JSON_LOCATION,
    PROP_HEAD,
    PROP_HEAD_TOKEN_FILE,
    PROP_STEER,
    PROP_TARGET_DISTANCE,
    PROP_HOME_PRESET,
    PROP_WIDEN_AFTER,
    PROP_HOME_AFTER,
    PROP_DETECTOR,
    PROP_MODEL_DIR,
    PROP_INPUT_MODE_OVERRIDE,
    PROP_DWELL,
    PROP_TARGET_REGION,
    PROP_INPUT_FLAGS_OVERRIDE,
    PROP_LOOK_TIME,
    PROP_MANUAL_PAUSE,
    PROP_DIRECTOR,
    PROP_DIRECTOR_HOME_PRESET,
    PROP_DIRECTOR_TOKEN_FILE,
    PROP_TARGET_PLANE,
    PROP_TRACKING_WIDTH,
};
static_assert(kStatsProperty > PROP_TRACKING_WIDTH, "the stats property's id follows the settings'");

#define GST_TYPE_HAND_TRACKER_OUTPUT (gst_hand_tracker_output_get_type())
static GType gst_hand_tracker_output_get_type()
{
    static GType type = 0;
    static const GEnumValue values[] = {
        {GST_HAND_TRACKER_OUTPUT_LEFT, "The left view", "left"},
        {GST_HAND_TRACKER_OUTPUT_RIGHT, "The right view (the left one for mono input)", "right"},
        {GST_HAND_TRACKER_OUTPUT_ATTENDED,
         "A smoothed crop of the left view around the hand and where it points, scaled to the output size", "attended"},
        {0, nullptr, nullptr},
    };
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstHandTrackerOutput", values));
    return type;
}

#define GST_TYPE_HAND_TRACKER_MESSAGE_UPDATES (gst_hand_tracker_message_updates_get_type())
static GType gst_hand_tracker_message_updates_get_type()
{
    static GType type = 0;
    static const GEnumValue values[] = {
        {GST_HAND_TRACKER_MESSAGES_EVERY_FRAME, "A hand-pointing message for every output frame", "every-frame"},
        {GST_HAND_TRACKER_MESSAGES_ON_CHANGE, "A hand-pointing message when the tracking state changes", "on-change"},
        {GST_HAND_TRACKER_MESSAGES_NONE, "No hand-pointing messages", "none"},
        {0, nullptr, nullptr},
    };
    if (g_once_init_enter(&type))
        g_once_init_leave(&type, g_enum_register_static("GstHandTrackerMessageUpdates", values));
    return type;
}

#define GST_TYPE_HAND_TRACKER_STEER (gst_hand_tracker_steer_get_type())
static GType gst_hand_tracker_steer_get_type()
{
    static GType type = 0;
    static const GEnumValue values[] = {
        {int(gc::headctl::SteerMode::Off), "Only read the head's pose (for the camera-motion offsets)", "off"},
        {int(gc::headctl::SteerMode::Fixate), "Keep the hand in the middle of the left view and verge on its depth",
         "fixate"},
        {int(gc::headctl::SteerMode::Point),
         "As fixate; a pointing held for dwell seconds turns the head to target-distance along its ray for "
         "look-time seconds, then back to the hand",
         "point"},
        {0, nullptr, nullptr},
    };
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstHandTrackerSteer", values));
    return type;
}

#define GST_TYPE_HAND_TRACKER_DETECTOR (gst_hand_tracker_detector_get_type())
static GType gst_hand_tracker_detector_get_type()
{
    static GType type = 0;
    static const GEnumValue values[] = {
        {int(gc::HandDetector::Learned),
         "Learned palm detector and landmark model: finds the hand anywhere, checks the contour, gives the gesture",
         "learned"},
        {int(gc::HandDetector::Motion), "The thesis's detection of a waving skin-coloured hand, nothing learned",
         "motion"},
        {0, nullptr, nullptr},
    };
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstHandTrackerDetector", values));
    return type;
}

// Changeable while playing.
constexpr auto kMutablePlaying = GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_PLAYING);

// The particle filters, the calibration, the output view and the loss rule.
void install_tracking_properties(GObjectClass* gobject_class)
{
    g_object_class_install_property(
        gobject_class, PROP_PARTICLES,
        g_param_spec_int("particles", "Particles",
                         "Sample-set size N of each eye's particle filter; a change restarts tracking", 1,
                         kMaxParticles, kDefaultParticles, kMutablePlaying));
    g_object_class_install_property(
        gobject_class, PROP_TRACKING_WIDTH,
        g_param_spec_int("tracking-width", "Tracking width",
                         "Track views wider than this many pixels scaled down to it (aspect kept, at least 64): "
                         "less CPU for HD cameras; every position reported stays in the views' pixels. "
                         "0: track at the views' own size; a change restarts tracking",
                         0, kMaxTrackingWidth, 0, kMutablePlaying));
    g_object_class_install_property(
        gobject_class, PROP_SEED,
        g_param_spec_uint64("seed", "Seed",
                            "Seed of the particle filters: the same seed and frames give the same output; "
                            "a change restarts tracking",
                            0, G_MAXUINT64, kDefaultSeed, kMutablePlaying));
    g_object_class_install_property(
        gobject_class, PROP_CALIBRATION,
        g_param_spec_string("calibration", "Calibration file",
                            "Stereo calibration (OpenCV YAML or XML: image_width, image_height, M1, D1, M2, D2, R, "
                            "T in millimetres); unset: the nominal rig (60 degree field of view, 120 mm baseline)",
                            nullptr,
                            GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
    g_object_class_install_property(gobject_class, PROP_OUTPUT,
                                    g_param_spec_enum("output", "Output", "The view on the src pad",
                                                      GST_TYPE_HAND_TRACKER_OUTPUT, kDefaultOutput, kMutablePlaying));
    g_object_class_install_property(
        gobject_class, PROP_DRAW,
        g_param_spec_boolean("draw", "Draw",
                             "Draw the tracked contour, the particles' marginal distributions along the borders, "
                             "the pointing direction and the state on the output",
                             FALSE, kMutablePlaying));
    g_object_class_install_property(
        gobject_class, PROP_LOST_THRESHOLD,
        g_param_spec_double("lost-threshold", "Lost threshold",
                            "A view is lost when every particle's likelihood stays below this fraction of the "
                            "likelihood at acquisition for lost-frames frames",
                            0.0, 1.0, kDefaultLostThreshold, kMutablePlaying));
    g_object_class_install_property(gobject_class, PROP_LOST_FRAMES,
                                    g_param_spec_int("lost-frames", "Lost frames",
                                                     "Consecutive frames below lost-threshold before a view is lost", 1,
                                                     1000, kDefaultLostFrames, kMutablePlaying));
}

// Where the results go besides the buffer: bus messages and JSON lines.
void install_report_properties(GObjectClass* gobject_class)
{
    g_object_class_install_property(
        gobject_class, PROP_MESSAGE_UPDATES,
        g_param_spec_enum("message-updates", "Message updates", "When to post hand-pointing element messages",
                          GST_TYPE_HAND_TRACKER_MESSAGE_UPDATES, kDefaultMessageUpdates, kMutablePlaying));
    g_object_class_install_property(
        gobject_class, PROP_JSON_LOCATION,
        g_param_spec_string("json-location", "JSON lines file",
                            "Write one JSON line per tracked frame to this file (the gesturecam-track schema); "
                            "unset: none",
                            nullptr,
                            GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
}

// The head and how it is steered.
void install_head_properties(GObjectClass* gobject_class)
{
    g_object_class_install_property(
        gobject_class, PROP_HEAD,
        g_param_spec_string("head", "Head URI",
                            "The motorised head carrying the cameras: tcp://host:port[?token=...] (the GCHP "
                            "protocol, e.g. headsim), visca-udp://host[:port], visca-tcp://host[:port], "
                            "visca-serial:///dev/ttyUSB0?baud=9600, pelco-d:///dev/ttyUSB0?address=1&baud=2400 or "
                            "onvif://host[:port][/path]?user=U (the token is its password); unset: "
                            "static cameras. Its pose at each frame's capture enters the tracker as camera motion; "
                            "`steer` says how it is moved. Connection changes are posted as head-connection "
                            "messages and a warning. A token reads back as token=***: prefer head-token-file",
                            nullptr,
                            GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
    g_object_class_install_property(
        gobject_class, PROP_HEAD_TOKEN_FILE,
        g_param_spec_string("head-token-file", "Head token file",
                            "A file whose first line is the head's token (GCHP), read at start; it replaces a "
                            "token in the head URI. Unset: the URI's token, if any",
                            nullptr,
                            GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
    g_object_class_install_property(gobject_class, PROP_STEER,
                                    g_param_spec_enum("steer", "Steer", "How the head is moved (needs head)",
                                                      GST_TYPE_HAND_TRACKER_STEER, int(kDefaultSteer),
                                                      kMutablePlaying));
    g_object_class_install_property(
        gobject_class, PROP_TARGET_DISTANCE,
        g_param_spec_double("target-distance", "Target distance",
                            "How far along a held pointing's ray, from the fingertip, its target lies (mm): where "
                            "steer=point looks and what output=attended and the director frame, unless the ray "
                            "meets target-plane",
                            1.0, 1.0e6, kDefaultTargetDistanceMm, kMutablePlaying));
    g_object_class_install_property(gobject_class, PROP_TARGET_PLANE, target_plane_param_spec(kMutablePlaying));
    g_object_class_install_property(
        gobject_class, PROP_LOOK_TIME,
        g_param_spec_double("look-time", "Look time",
                            "steer=point: seconds the head looks at a target a held pointing picked before it "
                            "turns back to where it left the hand",
                            0.1, 3600.0, kDefaultLookS, kMutablePlaying));
    g_object_class_install_property(
        gobject_class, PROP_MANUAL_PAUSE,
        g_param_spec_double("manual-pause", "Manual pause",
                            "steer=fixate or point: when the head moves without the element's command (someone "
                            "runs headctl move), steering leaves it alone for this many seconds after the move, "
                            "then resumes from there (a head-steering message says when); the director likewise "
                            "(director messages); 0: never pause",
                            0.0, 3600.0, kDefaultManualPauseS, kMutablePlaying));
}

// The loss behaviour's timing, how the hand is found, the dwell and the target region, and
// the packed input's layout.
void install_detector_properties(GObjectClass* gobject_class)
{
    g_object_class_install_property(
        gobject_class, PROP_HOME_PRESET,
        g_param_spec_int("home-preset", "Home preset",
                         "steer=fixate: the head's preset (saved on the head, e.g. headctl preset save N) that it "
                         "returns to once the hand has been lost for a while; -1: the head's home position",
                         -1, gc::headctl::kMaxPreset, -1,
                         GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
    g_object_class_install_property(
        gobject_class, PROP_WIDEN_AFTER,
        g_param_spec_double("widen-after", "Widen after",
                            "steer=fixate: once the hand has been lost this long (s) the head zooms out towards its "
                            "widest view until it is found again or goes home; 0: never",
                            0.0, 3600.0, 0.0,
                            GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
    g_object_class_install_property(
        gobject_class, PROP_HOME_AFTER,
        g_param_spec_double("home-after", "Home after",
                            "steer=fixate: once the hand has been lost this long (s) the head goes home (or to "
                            "home-preset); until then it holds still where the hand was last seen",
                            0.0, 3600.0, 2.0,
                            GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
    g_object_class_install_property(
        gobject_class, PROP_DETECTOR,
        g_param_spec_enum("detector", "Detector", "How the hand is found and checked", GST_TYPE_HAND_TRACKER_DETECTOR,
                          int(gc::HandDetector::Learned),
                          GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
    g_object_class_install_property(
        gobject_class, PROP_MODEL_DIR,
        g_param_spec_string("model-dir", "Model folder",
                            "Folder of the learned models (palm_detection.onnx, hand_landmark.onnx); unset: "
                            "GESTURECAM_MODEL_DIR, else the installed models, else the source tree's core/models",
                            nullptr,
                            GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
    g_object_class_install_property(
        gobject_class, PROP_DWELL,
        g_param_spec_double("dwell", "Dwell",
                            "Seconds a pointing must be held steady before it picks what it points at "
                            "(on target-plane, else target-distance along the ray): output=attended and the director "
                            "frame it, steer=point "
                            "looks at it; "
                            "lowering the hand for as long lets it go",
                            0.1, 60.0, kDefaultDwellS,
                            GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_PLAYING)));
    g_object_class_install_property(
        gobject_class, PROP_TARGET_REGION,
        g_param_spec_double("target-region", "Target region",
                            "Width in millimetres of the region output=attended and the director frame around a "
                            "pointed-at target",
                            50.0, 20000.0, kDefaultTargetRegionMm,
                            GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_PLAYING)));
    g_object_class_install_property(
        gobject_class, PROP_INPUT_MODE_OVERRIDE,
        g_param_spec_enum("input-mode-override", "Input mode override",
                          "How frames on the sink pad hold both views, when their caps do not say (none: the "
                          "caps' multiview-mode)",
                          GST_TYPE_VIDEO_MULTIVIEW_FRAME_PACKING, GST_VIDEO_MULTIVIEW_FRAME_PACKING_NONE,
                          GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
    g_object_class_install_property(
        gobject_class, PROP_INPUT_FLAGS_OVERRIDE,
        g_param_spec_flags("input-flags-override", "Input flags override",
                           "The multiview flags (right-view-first, half-aspect) of the sink pad's frames, used "
                           "with input-mode-override",
                           GST_TYPE_VIDEO_MULTIVIEW_FLAGS, GST_VIDEO_MULTIVIEW_FLAGS_NONE,
                           GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
}

// The director: a second PTZ camera framing what is pointed at.
void install_director_properties(GObjectClass* gobject_class)
{
    g_object_class_install_property(
        gobject_class, PROP_DIRECTOR,
        g_param_spec_string("director", "Director URI",
                            "A second PTZ camera that frames what a held pointing picks (target-region wide, "
                            "zoomed in) while the head keeps the hand in view; any URI `head` takes. Where it "
                            "stands comes from the calibration's director_* keys (without them: at the head's "
                            "origin, facing ahead, 60 degrees across at its widest). Released targets send it "
                            "home (or to director-home-preset). Connection changes are posted as head-connection "
                            "messages with its URI",
                            nullptr,
                            GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
    g_object_class_install_property(
        gobject_class, PROP_DIRECTOR_TOKEN_FILE,
        g_param_spec_string("director-token-file", "Director token file",
                            "A file whose first line is the director's token (GCHP), read at start; it replaces a "
                            "token in the director URI. Unset: the URI's token, if any",
                            nullptr,
                            GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
    g_object_class_install_property(
        gobject_class, PROP_DIRECTOR_HOME_PRESET,
        g_param_spec_int("director-home-preset", "Director home preset",
                         "The director's preset (e.g. a view of the whole room) it returns to when a target is "
                         "released; -1: its home position",
                         -1, gc::headctl::kMaxPreset, -1,
                         GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
}

}  // namespace

void install_tracker_properties(GObjectClass* gobject_class)
{
    install_tracking_properties(gobject_class);
    install_report_properties(gobject_class);
    install_head_properties(gobject_class);
    install_detector_properties(gobject_class);
    install_director_properties(gobject_class);
    g_object_class_install_property(
        gobject_class, kStatsProperty,
        g_param_spec_boxed("stats", "Statistics",
                           "Counts since start: tracked (frames tracked), skipped-qos (output frames dropped under "
                           "QoS: no meta, message or JSON line; the next JSON line says how many), "
                           "processing-time-max (ns, the longest of the last 30 frames) and latency (ns, the "
                           "processing time added to the latency the element reports)",
                           GST_TYPE_STRUCTURE, GParamFlags(G_PARAM_READABLE | G_PARAM_STATIC_STRINGS)));
}

void mark_tracker_enums_as_plugin_api()
{
    gst_type_mark_as_plugin_api(GST_TYPE_HAND_TRACKER_OUTPUT, GstPluginAPIFlags(0));
    gst_type_mark_as_plugin_api(GST_TYPE_HAND_TRACKER_MESSAGE_UPDATES, GstPluginAPIFlags(0));
    gst_type_mark_as_plugin_api(GST_TYPE_HAND_TRACKER_STEER, GstPluginAPIFlags(0));
    gst_type_mark_as_plugin_api(GST_TYPE_HAND_TRACKER_DETECTOR, GstPluginAPIFlags(0));
}

namespace {

// The properties of the head, its steering and the director; false for another id.
bool set_head_setting(TrackerSettings& s, guint prop_id, const GValue* value)
{
    switch (prop_id) {
    case PROP_HEAD:
        set_head_uri(s.head, value);
        break;
    case PROP_HEAD_TOKEN_FILE:
        s.head_token_file = string_value(value);
        break;
    case PROP_STEER:
        s.steer = gc::headctl::SteerMode(g_value_get_enum(value));
        break;
    case PROP_TARGET_DISTANCE:
        s.target.distance_mm = g_value_get_double(value);
        break;
    case PROP_TARGET_PLANE:
        set_target_plane(s.target.plane, value);
        break;
    case PROP_HOME_PRESET:
        s.home_preset = g_value_get_int(value);
        break;
    case PROP_WIDEN_AFTER:
        s.widen_after_s = g_value_get_double(value);
        break;
    case PROP_HOME_AFTER:
        s.home_after_s = g_value_get_double(value);
        break;
    case PROP_LOOK_TIME:
        s.look_s = g_value_get_double(value);
        break;
    case PROP_MANUAL_PAUSE:
        s.manual_pause_s = g_value_get_double(value);
        break;
    case PROP_DIRECTOR:
        set_head_uri(s.director, value);
        break;
    case PROP_DIRECTOR_HOME_PRESET:
        s.director_home_preset = g_value_get_int(value);
        break;
    case PROP_DIRECTOR_TOKEN_FILE:
        s.director_token_file = string_value(value);
        break;
    default:
        return false;
    }
    return true;
}

}  // namespace

bool set_tracker_setting(TrackerSettings& s, guint prop_id, const GValue* value, bool& rebuild)
{
    switch (prop_id) {
    case PROP_PARTICLES:
        s.particles = g_value_get_int(value);
        rebuild = true;
        break;
    case PROP_SEED:
        s.seed = g_value_get_uint64(value);
        rebuild = true;
        break;
    case PROP_TRACKING_WIDTH:
        s.tracking_width = g_value_get_int(value);
        rebuild = true;
        break;
    case PROP_CALIBRATION:
        s.calibration = string_value(value);
        rebuild = true;
        break;
    case PROP_OUTPUT:
        s.output = GstHandTrackerOutput(g_value_get_enum(value));
        break;
    case PROP_DRAW:
        s.draw = g_value_get_boolean(value);
        break;
    case PROP_LOST_THRESHOLD:
        s.lost_threshold = g_value_get_double(value);
        rebuild = true;
        break;
    case PROP_LOST_FRAMES:
        s.lost_frames = g_value_get_int(value);
        rebuild = true;
        break;
    case PROP_MESSAGE_UPDATES:
        s.message_updates = GstHandTrackerMessageUpdates(g_value_get_enum(value));
        break;
    case PROP_JSON_LOCATION:
        s.json_location = string_value(value);
        break;
    case PROP_DETECTOR:
        s.detector = gc::HandDetector(g_value_get_enum(value));
        rebuild = true;
        break;
    case PROP_MODEL_DIR:
        s.model_dir = string_value(value);
        rebuild = true;
        break;
    case PROP_DWELL:
        s.dwell_s = g_value_get_double(value);
        break;
    case PROP_TARGET_REGION:
        s.target_region_mm = g_value_get_double(value);
        break;
    case PROP_INPUT_MODE_OVERRIDE:
        s.input_mode_override = GstVideoMultiviewFramePacking(g_value_get_enum(value));
        break;
    case PROP_INPUT_FLAGS_OVERRIDE:
        s.input_flags_override = GstVideoMultiviewFlags(g_value_get_flags(value));
        break;
    default:
        return set_head_setting(s, prop_id, value);
    }
    return true;
}

namespace {

// The properties of the head, its steering and the director; false for another id.
bool get_head_setting(const TrackerSettings& s, guint prop_id, GValue* value)
{
    switch (prop_id) {
    case PROP_HEAD:
        get_head_uri(s.head, value);
        break;
    case PROP_HEAD_TOKEN_FILE:
        set_string_value(value, s.head_token_file);
        break;
    case PROP_STEER:
        g_value_set_enum(value, int(s.steer));
        break;
    case PROP_TARGET_DISTANCE:
        g_value_set_double(value, s.target.distance_mm);
        break;
    case PROP_TARGET_PLANE:
        get_target_plane(s.target.plane, value);
        break;
    case PROP_HOME_PRESET:
        g_value_set_int(value, s.home_preset);
        break;
    case PROP_WIDEN_AFTER:
        g_value_set_double(value, s.widen_after_s);
        break;
    case PROP_HOME_AFTER:
        g_value_set_double(value, s.home_after_s);
        break;
    case PROP_LOOK_TIME:
        g_value_set_double(value, s.look_s);
        break;
    case PROP_MANUAL_PAUSE:
        g_value_set_double(value, s.manual_pause_s);
        break;
    case PROP_DIRECTOR:
        get_head_uri(s.director, value);
        break;
    case PROP_DIRECTOR_HOME_PRESET:
        g_value_set_int(value, s.director_home_preset);
        break;
    case PROP_DIRECTOR_TOKEN_FILE:
        set_string_value(value, s.director_token_file);
        break;
    default:
        return false;
    }
    return true;
}

}  // namespace

bool get_tracker_setting(const TrackerSettings& s, guint prop_id, GValue* value)
{
    switch (prop_id) {
    case PROP_PARTICLES:
        g_value_set_int(value, s.particles);
        break;
    case PROP_SEED:
        g_value_set_uint64(value, s.seed);
        break;
    case PROP_TRACKING_WIDTH:
        g_value_set_int(value, s.tracking_width);
        break;
    case PROP_CALIBRATION:
        set_string_value(value, s.calibration);
        break;
    case PROP_OUTPUT:
        g_value_set_enum(value, s.output);
        break;
    case PROP_DRAW:
        g_value_set_boolean(value, s.draw);
        break;
    case PROP_LOST_THRESHOLD:
        g_value_set_double(value, s.lost_threshold);
        break;
    case PROP_LOST_FRAMES:
        g_value_set_int(value, s.lost_frames);
        break;
    case PROP_MESSAGE_UPDATES:
        g_value_set_enum(value, s.message_updates);
        break;
    case PROP_JSON_LOCATION:
        set_string_value(value, s.json_location);
        break;
    case PROP_DETECTOR:
        g_value_set_enum(value, int(s.detector));
        break;
    case PROP_MODEL_DIR:
        set_string_value(value, s.model_dir);
        break;
    case PROP_DWELL:
        g_value_set_double(value, s.dwell_s);
        break;
    case PROP_TARGET_REGION:
        g_value_set_double(value, s.target_region_mm);
        break;
    case PROP_INPUT_MODE_OVERRIDE:
        g_value_set_enum(value, s.input_mode_override);
        break;
    case PROP_INPUT_FLAGS_OVERRIDE:
        g_value_set_flags(value, s.input_flags_override);
        break;
    default:
        return get_head_setting(s, prop_id, value);
    }
    return true;
}

}  // namespace gc::gst
