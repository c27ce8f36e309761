#include "handtracker_settings.hpp"

#include "headctl/head_backend.hpp"
#include "headctl/token.hpp"

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
};

#define GST_TYPE_HAND_TRACKER_OUTPUT (gst_hand_tracker_output_get_type())
static GType gst_hand_tracker_output_get_type()
{
    static GType type = 0;
    static const GEnumValue values[] = {
        {GST_HAND_TRACKER_OUTPUT_LEFT, "The left view", "left"},
        {GST_HAND_TRACKER_OUTPUT_RIGHT, "The right view (the left one for mono input)", "right"},
        {GST_HAND_TRACKER_OUTPUT_ATTENDED,
         "A smoothed crop of the left view around the hand and where it points, scaled to the output size",
         "attended"},
        {0, nullptr, nullptr},
    };
    if (g_once_init_enter(&type))
        g_once_init_leave(&type, g_enum_register_static("GstHandTrackerOutput", values));
    return type;
}

#define GST_TYPE_HAND_TRACKER_MESSAGE_UPDATES (gst_hand_tracker_message_updates_get_type())
static GType gst_hand_tracker_message_updates_get_type()
{
    static GType type = 0;
    static const GEnumValue values[] = {
        {GST_HAND_TRACKER_MESSAGES_EVERY_FRAME, "A hand-pointing message for every output frame",
         "every-frame"},
        {GST_HAND_TRACKER_MESSAGES_ON_CHANGE, "A hand-pointing message when the tracking state changes",
         "on-change"},
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
        {int(gc::headctl::SteerMode::Fixate), "Keep the hand in the middle of the left view and verge on its depth", "fixate"},
        {int(gc::headctl::SteerMode::Point), "Look where the hand points, target-distance along its ray", "point"},
        {0, nullptr, nullptr},
    };
    if (g_once_init_enter(&type))
        g_once_init_leave(&type, g_enum_register_static("GstHandTrackerSteer", values));
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
    if (g_once_init_enter(&type))
        g_once_init_leave(&type, g_enum_register_static("GstHandTrackerDetector", values));
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
                            nullptr, GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
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
    g_object_class_install_property(
        gobject_class, PROP_LOST_FRAMES,
        g_param_spec_int("lost-frames", "Lost frames",
                         "Consecutive frames below lost-threshold before a view is lost", 1, 1000,
                         kDefaultLostFrames, kMutablePlaying));
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
                            nullptr, GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
}

// The head and how it is steered.
void install_head_properties(GObjectClass* gobject_class)
{
    g_object_class_install_property(
        gobject_class, PROP_HEAD,
        g_param_spec_string("head", "Head URI",
                            "The motorised head carrying the cameras: tcp://host:port[?token=...] (the GCHP "
                            "protocol, e.g. headsim), visca-udp://host[:port], visca-tcp://host[:port], "
                            "visca-serial:///dev/ttyUSB0?baud=9600 or pelco-d:///dev/ttyUSB0?address=1&baud=2400; unset: "
                            "static cameras. Its pose at each frame's capture enters the tracker as camera motion; "
                            "`steer` says how it is moved. Connection changes are posted as head-connection "
                            "messages and a warning. A token reads back as token=***: prefer head-token-file",
                            nullptr, GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
    g_object_class_install_property(
        gobject_class, PROP_HEAD_TOKEN_FILE,
        g_param_spec_string("head-token-file", "Head token file",
                            "A file whose first line is the head's token (GCHP), read at start; it replaces a "
                            "token in the head URI. Unset: the URI's token, if any",
                            nullptr, GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
    g_object_class_install_property(
        gobject_class, PROP_STEER,
        g_param_spec_enum("steer", "Steer", "How the head is moved (needs head)", GST_TYPE_HAND_TRACKER_STEER,
                          int(kDefaultSteer), kMutablePlaying));
    g_object_class_install_property(
        gobject_class, PROP_TARGET_DISTANCE,
        g_param_spec_double("target-distance", "Target distance",
                            "steer=point: how far along the pointing ray, from the fingertip, the head looks (mm)",
                            1.0, 1.0e6, kDefaultTargetDistanceMm, kMutablePlaying));
}

// How the hand is found.
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
                            0.0, 3600.0, 0.0, GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
    g_object_class_install_property(
        gobject_class, PROP_HOME_AFTER,
        g_param_spec_double("home-after", "Home after",
                            "steer=fixate: once the hand has been lost this long (s) the head goes home (or to "
                            "home-preset); until then it holds still where the hand was last seen",
                            0.0, 3600.0, 2.0, GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
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
                            nullptr, GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)));
}

}  // namespace

void install_tracker_properties(GObjectClass* gobject_class)
{
    install_tracking_properties(gobject_class);
    install_report_properties(gobject_class);
    install_head_properties(gobject_class);
    install_detector_properties(gobject_class);
}

void mark_tracker_enums_as_plugin_api()
{
    gst_type_mark_as_plugin_api(GST_TYPE_HAND_TRACKER_OUTPUT, GstPluginAPIFlags(0));
    gst_type_mark_as_plugin_api(GST_TYPE_HAND_TRACKER_MESSAGE_UPDATES, GstPluginAPIFlags(0));
    gst_type_mark_as_plugin_api(GST_TYPE_HAND_TRACKER_STEER, GstPluginAPIFlags(0));
    gst_type_mark_as_plugin_api(GST_TYPE_HAND_TRACKER_DETECTOR, GstPluginAPIFlags(0));
}

namespace {

// The properties of the head and its steering; false for another id.
bool set_head_setting(TrackerSettings& s, guint prop_id, const GValue* value)
{
    switch (prop_id) {
    case PROP_HEAD: {
        // What reading the property gave (the token hidden) leaves the URI as it is.
        const gchar* uri = g_value_get_string(value);
        if (std::string(uri ? uri : "") != gc::headctl::redact_uri(s.head))
            s.head = uri ? uri : "";
        break;
    }
    case PROP_HEAD_TOKEN_FILE: {
        const gchar* path = g_value_get_string(value);
        s.head_token_file = path ? path : "";
        break;
    }
    case PROP_STEER:
        s.steer = gc::headctl::SteerMode(g_value_get_enum(value));
        break;
    case PROP_TARGET_DISTANCE:
        s.target_distance_mm = g_value_get_double(value);
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
    case PROP_CALIBRATION: {
        const gchar* path = g_value_get_string(value);
        s.calibration = path ? path : "";
        rebuild = true;
        break;
    }
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
    case PROP_JSON_LOCATION: {
        const gchar* path = g_value_get_string(value);
        s.json_location = path ? path : "";
        break;
    }
    case PROP_DETECTOR:
        s.detector = gc::HandDetector(g_value_get_enum(value));
        rebuild = true;
        break;
    case PROP_MODEL_DIR: {
        const gchar* dir = g_value_get_string(value);
        s.model_dir = dir ? dir : "";
        rebuild = true;
        break;
    }
    default:
        return set_head_setting(s, prop_id, value);
    }
    return true;
}

bool get_tracker_setting(const TrackerSettings& s, guint prop_id, GValue* value)
{
    switch (prop_id) {
    case PROP_PARTICLES:
        g_value_set_int(value, s.particles);
        break;
    case PROP_SEED:
        g_value_set_uint64(value, s.seed);
        break;
    case PROP_CALIBRATION:
        g_value_set_string(value, s.calibration.empty() ? nullptr : s.calibration.c_str());
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
        g_value_set_string(value, s.json_location.empty() ? nullptr : s.json_location.c_str());
        break;
    case PROP_HEAD:
        g_value_set_string(value, s.head.empty() ? nullptr : gc::headctl::redact_uri(s.head).c_str());
        break;
    case PROP_HEAD_TOKEN_FILE:
        g_value_set_string(value, s.head_token_file.empty() ? nullptr : s.head_token_file.c_str());
        break;
    case PROP_STEER:
        g_value_set_enum(value, int(s.steer));
        break;
    case PROP_TARGET_DISTANCE:
        g_value_set_double(value, s.target_distance_mm);
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
    case PROP_DETECTOR:
        g_value_set_enum(value, int(s.detector));
        break;
    case PROP_MODEL_DIR:
        g_value_set_string(value, s.model_dir.empty() ? nullptr : s.model_dir.c_str());
        break;
    default:
        return false;
    }
    return true;
}

}  // namespace gc::gst
