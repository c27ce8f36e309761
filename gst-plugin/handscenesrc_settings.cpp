#include "handscenesrc_settings.hpp"

#include "head_uri_property.hpp"
#include "string_property.hpp"

#include <gst/gst.h>

namespace gc::gst {

namespace {

enum {
    PROP_0,
    PROP_EYE,
    PROP_SCENE,
    PROP_MOTION,
    PROP_SEED,
    PROP_NOISE,
    PROP_LIGHTING_CHANGE,
    PROP_VARIETY,
    PROP_GESTURE,
    PROP_GESTURE_CYCLE,
    PROP_IS_LIVE,
    PROP_TRUTH_MESSAGES,
    PROP_HEAD,
    PROP_HEAD_TOKEN_FILE,
    PROP_HEAD_PAN,
    PROP_HEAD_TILT,
    PROP_AIM,
};

#define GST_TYPE_HAND_SCENE_EYE (gst_hand_scene_eye_get_type())
GType gst_hand_scene_eye_get_type()
{
    static GType type = 0;
    static const GEnumValue values[] = {
        {int(gc::Eye::Left), "The left camera", "left"},
        {int(gc::Eye::Right), "The right camera", "right"},
        {0, nullptr, nullptr},
    };
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstHandSceneEye", values));
    return type;
}

#define GST_TYPE_HAND_SCENE_PRESET (gst_hand_scene_preset_get_type())
GType gst_hand_scene_preset_get_type()
{
    static GType type = 0;
    static const GEnumValue values[] = {
        {int(gc::sim::Preset::Clean), "Plain background (0.03 % skin-like pixels)", "clean"},
        {int(gc::sim::Preset::Light), "Light clutter (3.7 % skin-like pixels)", "light"},
        {int(gc::sim::Preset::Heavy), "Heavy clutter (9.4 % skin-like pixels)", "heavy"},
        {int(gc::sim::Preset::FacePass), "Light clutter and a face that the hand's path crosses", "face-pass"},
        {int(gc::sim::Preset::Varied),
         "A room of any kind, often skin-coloured, pictures of faces and hands, "
         "up to two people; always of the wide variety",
         "varied"},
        {0, nullptr, nullptr},
    };
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstHandScenePreset", values));
    return type;
}

#define GST_TYPE_HAND_SCENE_VARIETY (gst_hand_scene_variety_get_type())
GType gst_hand_scene_variety_get_type()
{
    static GType type = 0;
    static const GEnumValue values[] = {
        {int(gc::sim::Variety::None), "The preset's one hand, light and camera", "none"},
        {int(gc::sim::Variety::Wide),
         "Hand shape and skin, sleeve, people, light and camera (noise, blur, exposure, white balance, "
         "vignetting, compression) drawn from the seed",
         "wide"},
        {0, nullptr, nullptr},
    };
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstHandSceneVariety", values));
    return type;
}

#define GST_TYPE_HAND_SCENE_MOTION (gst_hand_scene_motion_get_type())
GType gst_hand_scene_motion_get_type()
{
    static GType type = 0;
    static const GEnumValue values[] = {
        {int(gc::sim::Motion::Static), "Holds still after the initial wave", "static"},
        {int(gc::sim::Motion::Translate), "Moves in the image plane", "translate"},
        {int(gc::sim::Motion::Rotate), "Rotates the pointing direction in the image plane", "rotate"},
        {int(gc::sim::Motion::Scale), "Moves towards and away from the cameras", "scale"},
        {int(gc::sim::Motion::Yaw), "Turns the hand plane about the vertical", "yaw"},
        {int(gc::sim::Motion::Mixed), "All of the above at once", "mixed"},
        {int(gc::sim::Motion::LeaveReturn), "Leaves the view, stays out for a while, comes back", "leave-return"},
        {0, nullptr, nullptr},
    };
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstHandSceneMotion", values));
    return type;
}

// Three coordinates name a point; anything else (an empty array) leaves the seed's direction.
std::optional<cv::Vec3d> aim_from_array(const GValue* value)
{
    if (gst_value_array_get_size(value) != 3) return std::nullopt;
    cv::Vec3d aim;
    for (guint i = 0; i < 3; ++i) aim[int(i)] = g_value_get_double(gst_value_array_get_value(value, i));
    return aim;
}

void aim_to_array(const std::optional<cv::Vec3d>& aim, GValue* value)
{
    for (int i = 0; aim && i < 3; ++i) {
        GValue v = G_VALUE_INIT;
        g_value_init(&v, G_TYPE_DOUBLE);
        g_value_set_double(&v, (*aim)[i]);
        gst_value_array_append_and_take_value(value, &v);
    }
}

#define GST_TYPE_HAND_SCENE_GESTURE (gst_hand_scene_gesture_get_type())
GType gst_hand_scene_gesture_get_type()
{
    static GType type = 0;
    static const GEnumValue values[] = {
        {int(gc::Gesture::Pointing), "The index finger extended, the thumb along it, the other fingers curled",
         "pointing"},
        {int(gc::Gesture::Open), "All five fingers extended and slightly spread, the thumb out", "open"},
        {int(gc::Gesture::Fist), "All four fingers curled, the thumb across them", "fist"},
        {0, nullptr, nullptr},
    };
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstHandSceneGesture", values));
    return type;
}

// What the hand does: its gesture and where it points.
void install_hand_properties(GObjectClass* klass, GParamFlags flags)
{
    g_object_class_install_property(
        klass, PROP_GESTURE,
        g_param_spec_enum("gesture", "Gesture",
                          "What the hand does; only a pointing hand has a pointing ray in the ground truth",
                          GST_TYPE_HAND_SCENE_GESTURE, int(gc::Gesture::Pointing), flags));
    g_object_class_install_property(
        klass, PROP_GESTURE_CYCLE,
        g_param_spec_double("gesture-cycle", "Gesture cycle",
                            "Seconds: 0 holds the gesture throughout; T > 0 shows the gesture for T s, then points "
                            "for T s, and so on",
                            0.0, 3600.0, 0.0, flags));
    g_object_class_install_property(
        klass, PROP_AIM,
        gst_param_spec_array("aim", "Aim",
                             "Where the hand points at rest: a point <x, y, z> in the head frame, millimetres (x "
                             "right, y down, z ahead; the room's wall is 3000 mm ahead). Empty: the seed's "
                             "direction, obliquely up to one side",
                             g_param_spec_double("coordinate", "Coordinate", "mm", -1.0e5, 1.0e5, 0.0,
                                                 GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS)),
                             flags));
}

// The head the cameras sit on: a simulated head to follow, or a fixed rig's pose.
void install_head_properties(GObjectClass* klass, GParamFlags flags)
{
    g_object_class_install_property(
        klass, PROP_HEAD,
        g_param_spec_string("head", "Head URI",
                            "The head the simulated cameras sit on (tcp://host:port, e.g. headsim): every frame is "
                            "rendered from its pose at the frame's capture time, so handtracker steering that head "
                            "closes the loop; use with is-live=true. Unset: a fixed rig (head-pan, head-tilt). "
                            "A token reads back as token=***: prefer head-token-file",
                            nullptr, flags));
    g_object_class_install_property(
        klass, PROP_HEAD_TOKEN_FILE,
        g_param_spec_string("head-token-file", "Head token file",
                            "A file whose first line is the head's token (GCHP), read at start; it replaces a "
                            "token in the head URI. Unset: the URI's token, if any",
                            nullptr, flags));
    // Controllable, so that a GstController can move the rig frame by frame (the element
    // syncs them to each frame's timestamp).
    const auto rig_flags =
        GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_PLAYING | GST_PARAM_CONTROLLABLE);
    g_object_class_install_property(klass, PROP_HEAD_PAN,
                                    g_param_spec_double("head-pan", "Head pan",
                                                        "Without head: the fixed rig's pan, degrees (positive: right)",
                                                        -90.0, 90.0, 0.0, rig_flags));
    g_object_class_install_property(klass, PROP_HEAD_TILT,
                                    g_param_spec_double("head-tilt", "Head tilt",
                                                        "Without head: the fixed rig's tilt, degrees (positive: up)",
                                                        -90.0, 90.0, 0.0, rig_flags));
}

}  // namespace

bool is_live_property(guint prop_id) { return prop_id == PROP_IS_LIVE; }

void install_scene_properties(GObjectClass* klass)
{
    const auto flags = GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY);
    g_object_class_install_property(klass, PROP_EYE,
                                    g_param_spec_enum("eye", "Eye", "Which camera of the stereo head to render",
                                                      GST_TYPE_HAND_SCENE_EYE, int(gc::Eye::Left), flags));
    g_object_class_install_property(klass, PROP_SCENE,
                                    g_param_spec_enum("scene", "Scene", "Background clutter preset",
                                                      GST_TYPE_HAND_SCENE_PRESET, int(gc::sim::Preset::Clean), flags));
    g_object_class_install_property(klass, PROP_MOTION,
                                    g_param_spec_enum("motion", "Motion",
                                                      "Scripted hand motion (every script starts with a short wave)",
                                                      GST_TYPE_HAND_SCENE_MOTION, int(gc::sim::Motion::Mixed), flags));
    g_object_class_install_property(
        klass, PROP_SEED,
        g_param_spec_uint64("seed", "Seed",
                            "Background layout, skin tone and noise: the same seed renders the same scene", 0,
                            G_MAXUINT64, kDefaultSceneSeed, flags));
    g_object_class_install_property(klass, PROP_NOISE,
                                    g_param_spec_double("noise", "Noise",
                                                        "Standard deviation of the sensor noise, grey levels", 0.0,
                                                        64.0, kDefaultSceneNoise, flags));
    g_object_class_install_property(klass, PROP_LIGHTING_CHANGE,
                                    g_param_spec_boolean("lighting-change", "Lighting change",
                                                         "A slow global change of brightness and colour temperature",
                                                         FALSE, flags));
    g_object_class_install_property(
        klass, PROP_VARIETY,
        g_param_spec_enum("variety", "Variety",
                          "What else the seed varies: nothing (the preset as it always was) or the hand, "
                          "people, light and camera",
                          GST_TYPE_HAND_SCENE_VARIETY, int(gc::sim::Variety::None), flags));
    g_object_class_install_property(klass, PROP_IS_LIVE,
                                    g_param_spec_boolean("is-live", "Is live",
                                                         "Behave as a live camera: frames come at the frame rate",
                                                         FALSE, flags));
    g_object_class_install_property(
        klass, PROP_TRUTH_MESSAGES,
        g_param_spec_boolean("truth-messages", "Truth messages",
                             "Post a hand-truth element message with the ground truth of every frame", TRUE,
                             GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_PLAYING)));
    install_hand_properties(klass, flags);
    install_head_properties(klass, flags);
}

void mark_scene_enums_as_plugin_api()
{
    gst_type_mark_as_plugin_api(GST_TYPE_HAND_SCENE_EYE, GstPluginAPIFlags(0));
    gst_type_mark_as_plugin_api(GST_TYPE_HAND_SCENE_PRESET, GstPluginAPIFlags(0));
    gst_type_mark_as_plugin_api(GST_TYPE_HAND_SCENE_MOTION, GstPluginAPIFlags(0));
    gst_type_mark_as_plugin_api(GST_TYPE_HAND_SCENE_VARIETY, GstPluginAPIFlags(0));
    gst_type_mark_as_plugin_api(GST_TYPE_HAND_SCENE_GESTURE, GstPluginAPIFlags(0));
}

bool set_scene_setting(SceneSettings& s, guint prop_id, const GValue* value)
{
    switch (prop_id) {
    case PROP_EYE:
        s.eye = gc::Eye(g_value_get_enum(value));
        break;
    case PROP_SCENE:
        s.preset = gc::sim::Preset(g_value_get_enum(value));
        break;
    case PROP_MOTION:
        s.motion = gc::sim::Motion(g_value_get_enum(value));
        break;
    case PROP_SEED:
        s.seed = g_value_get_uint64(value);
        break;
    case PROP_NOISE:
        s.noise = g_value_get_double(value);
        break;
    case PROP_LIGHTING_CHANGE:
        s.lighting_change = g_value_get_boolean(value);
        break;
    case PROP_VARIETY:
        s.variety = gc::sim::Variety(g_value_get_enum(value));
        break;
    case PROP_GESTURE:
        s.gesture = gc::Gesture(g_value_get_enum(value));
        break;
    case PROP_GESTURE_CYCLE:
        s.gesture_cycle_s = g_value_get_double(value);
        break;
    case PROP_TRUTH_MESSAGES:
        s.truth_messages = g_value_get_boolean(value);
        break;
    case PROP_HEAD:
        set_head_uri(s.head, value);
        break;
    case PROP_HEAD_TOKEN_FILE:
        s.head_token_file = string_value(value);
        break;
    case PROP_HEAD_PAN:
        s.rig.pan_deg = g_value_get_double(value);
        break;
    case PROP_HEAD_TILT:
        s.rig.tilt_deg = g_value_get_double(value);
        break;
    case PROP_AIM:
        s.aim = aim_from_array(value);
        break;
    default:
        return false;
    }
    return true;
}

bool get_scene_setting(const SceneSettings& s, guint prop_id, GValue* value)
{
    switch (prop_id) {
    case PROP_EYE:
        g_value_set_enum(value, int(s.eye));
        break;
    case PROP_SCENE:
        g_value_set_enum(value, int(s.preset));
        break;
    case PROP_MOTION:
        g_value_set_enum(value, int(s.motion));
        break;
    case PROP_SEED:
        g_value_set_uint64(value, s.seed);
        break;
    case PROP_NOISE:
        g_value_set_double(value, s.noise);
        break;
    case PROP_LIGHTING_CHANGE:
        g_value_set_boolean(value, s.lighting_change);
        break;
    case PROP_VARIETY:
        g_value_set_enum(value, int(s.variety));
        break;
    case PROP_GESTURE:
        g_value_set_enum(value, int(s.gesture));
        break;
    case PROP_GESTURE_CYCLE:
        g_value_set_double(value, s.gesture_cycle_s);
        break;
    case PROP_TRUTH_MESSAGES:
        g_value_set_boolean(value, s.truth_messages);
        break;
    case PROP_HEAD:
        get_head_uri(s.head, value);
        break;
    case PROP_HEAD_TOKEN_FILE:
        set_string_value(value, s.head_token_file);
        break;
    case PROP_HEAD_PAN:
        g_value_set_double(value, s.rig.pan_deg);
        break;
    case PROP_HEAD_TILT:
        g_value_set_double(value, s.rig.tilt_deg);
        break;
    case PROP_AIM:
        aim_to_array(s.aim, value);
        break;
    default:
        return false;
    }
    return true;
}

}  // namespace gc::gst
