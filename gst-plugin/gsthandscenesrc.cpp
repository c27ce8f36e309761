// handscenesrc: GObject glue over gc::sim::Scene. Frame n of the scene is rendered for
// buffer offset n, so two instances with the same scene, motion and seed (one per eye)
// form a consistent stereo pair whatever order they run in. With a head URI the cameras
// sit on that head: each frame is rendered from the head's pose at its capture time.
#include "gsthandscenesrc.hpp"

#include "head_connection.hpp"
#include "pointing_report.hpp"
#include "video_bgr.hpp"

#include "headctl/head_client.hpp"
#include "headctl/uri.hpp"
#include "sim/scene.hpp"

#include <gst/video/video.h>
#include <opencv2/core.hpp>

#include <chrono>
#include <exception>
#include <memory>
#include <optional>
#include <string>

GST_DEBUG_CATEGORY_STATIC(gst_hand_scene_src_debug);
#define GST_CAT_DEFAULT gst_hand_scene_src_debug

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
    PROP_IS_LIVE,
    PROP_TRUTH_MESSAGES,
    PROP_HEAD,
};

constexpr guint64 kDefaultSeed = 1;
constexpr double kDefaultNoise = 2.0;

struct SceneSettings {
    gc::Eye eye = gc::Eye::Left;
    gc::sim::Preset preset = gc::sim::Preset::Clean;
    gc::sim::Motion motion = gc::sim::Motion::Mixed;
    guint64 seed = kDefaultSeed;
    double noise = kDefaultNoise;
    bool lighting_change = false;
    gc::sim::Variety variety = gc::sim::Variety::None;
    bool truth_messages = true;
    std::string head;  // URI of the head the cameras sit on; empty: a fixed rig at home pose
};

struct SceneState {
    std::optional<gc::sim::Scene> scene;
    GstVideoInfo info;
    guint64 next_frame = 0;  // the offset of the next buffer
    // Live: the running time at which frame 0 was taken; NONE until then.
    GstClockTime live_origin = GST_CLOCK_TIME_NONE;
    // Live: the wait for the next frame's capture time, and whether basesrc asked us to stop
    // waiting. Both under the object lock.
    GstClockID capture_wait = nullptr;
    bool unlocked = false;
    cv::Mat bgr;
    gc::gst::BgrWriter writer;
    gc::sim::EyeTruth truth;
    gc::HeadPose pose;  // the pose the last frame was rendered from
    bool warned_pose = false;  // about a head pose the room cannot be rendered from
    std::unique_ptr<gc::headctl::HeadClient> head;
};

}  // namespace

struct _GstHandSceneSrc {
    GstPushSrc parent;
    SceneSettings* settings;
    SceneState* state;
};

G_DEFINE_TYPE(GstHandSceneSrc, gst_hand_scene_src, GST_TYPE_PUSH_SRC)
GST_ELEMENT_REGISTER_DEFINE(handscenesrc, "handscenesrc", GST_RANK_NONE, GST_TYPE_HAND_SCENE_SRC)

#define GST_TYPE_HAND_SCENE_EYE (gst_hand_scene_eye_get_type())
static GType gst_hand_scene_eye_get_type()
{
    static GType type = 0;
    static const GEnumValue values[] = {
        {int(gc::Eye::Left), "The left camera", "left"},
        {int(gc::Eye::Right), "The right camera", "right"},
        {0, nullptr, nullptr},
    };
    if (g_once_init_enter(&type))
        g_once_init_leave(&type, g_enum_register_static("GstHandSceneEye", values));
    return type;
}

#define GST_TYPE_HAND_SCENE_PRESET (gst_hand_scene_preset_get_type())
static GType gst_hand_scene_preset_get_type()
{
    static GType type = 0;
    static const GEnumValue values[] = {
        {int(gc::sim::Preset::Clean), "Plain background (0.03 % skin-like pixels)", "clean"},
        {int(gc::sim::Preset::Light), "Light clutter (3.7 % skin-like pixels)", "light"},
        {int(gc::sim::Preset::Heavy), "Heavy clutter (9.4 % skin-like pixels)", "heavy"},
        {int(gc::sim::Preset::FacePass), "Light clutter and a face that the hand's path crosses", "face-pass"},
        {int(gc::sim::Preset::Varied), "A room of any kind, often skin-coloured, pictures of faces and hands, "
                                       "up to two people; always of the wide variety", "varied"},
        {0, nullptr, nullptr},
    };
    if (g_once_init_enter(&type))
        g_once_init_leave(&type, g_enum_register_static("GstHandScenePreset", values));
    return type;
}

#define GST_TYPE_HAND_SCENE_VARIETY (gst_hand_scene_variety_get_type())
static GType gst_hand_scene_variety_get_type()
{
    static GType type = 0;
    static const GEnumValue values[] = {
        {int(gc::sim::Variety::None), "The preset's one hand, light and camera", "none"},
        {int(gc::sim::Variety::Wide),
         "Hand shape and skin, sleeve, people, light and camera (noise, blur, exposure, white balance, "
         "vignetting, compression) drawn from the seed", "wide"},
        {0, nullptr, nullptr},
    };
    if (g_once_init_enter(&type))
        g_once_init_leave(&type, g_enum_register_static("GstHandSceneVariety", values));
    return type;
}

#define GST_TYPE_HAND_SCENE_MOTION (gst_hand_scene_motion_get_type())
static GType gst_hand_scene_motion_get_type()
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
    if (g_once_init_enter(&type))
        g_once_init_leave(&type, g_enum_register_static("GstHandSceneMotion", values));
    return type;
}

static GstStaticPadTemplate src_template = GST_STATIC_PAD_TEMPLATE(
    "src", GST_PAD_SRC, GST_PAD_ALWAYS,
    GST_STATIC_CAPS("video/x-raw, format = (string) { " GC_OUTPUT_FORMATS " }, width = (int) [ 32, 4096 ], "
                    "height = (int) [ 32, 4096 ], framerate = (fraction) [ 1/1, 240/1 ]"));

// ---------------------------------------------------------------------------------------
// Negotiation

static GstCaps* gst_hand_scene_src_fixate(GstBaseSrc* src, GstCaps* caps)
{
    caps = gst_caps_make_writable(caps);
    GstStructure* s = gst_caps_get_structure(caps, 0);
    gst_structure_fixate_field_nearest_int(s, "width", 640);
    gst_structure_fixate_field_nearest_int(s, "height", 480);
    gst_structure_fixate_field_nearest_fraction(s, "framerate", 30, 1);
    return GST_BASE_SRC_CLASS(gst_hand_scene_src_parent_class)->fixate(src, caps);
}

static gboolean gst_hand_scene_src_set_caps(GstBaseSrc* src, GstCaps* caps)
{
    GstHandSceneSrc* self = GST_HAND_SCENE_SRC(src);
    GstVideoInfo info;
    if (!gst_video_info_from_caps(&info, caps) || GST_VIDEO_INFO_FPS_N(&info) <= 0) {
        GST_ELEMENT_ERROR(self, CORE, NEGOTIATION, ("handscenesrc needs raw video caps with a frame rate."),
                          ("got %" GST_PTR_FORMAT, caps));
        return FALSE;
    }
    GST_OBJECT_LOCK(self);
    const SceneSettings settings = *self->settings;
    GST_OBJECT_UNLOCK(self);
    gc::sim::SceneConfig config;
    config.preset = settings.preset;
    config.motion = settings.motion;
    config.seed = settings.seed;
    config.width = GST_VIDEO_INFO_WIDTH(&info);
    config.height = GST_VIDEO_INFO_HEIGHT(&info);
    config.fps = double(GST_VIDEO_INFO_FPS_N(&info)) / GST_VIDEO_INFO_FPS_D(&info);
    config.noise_sigma = settings.noise;
    config.lighting_change = settings.lighting_change;
    config.variety = settings.variety;
    try {
        self->state->scene.emplace(config);
    } catch (const std::exception& err) {
        GST_ELEMENT_ERROR(self, CORE, NEGOTIATION, ("Cannot build the scene for %" GST_PTR_FORMAT ".", caps),
                          ("%s", err.what()));
        return FALSE;
    }
    self->state->info = info;
    return TRUE;
}

// Buffers of a full frame from a video buffer pool (downstream's when it offers one).
static gboolean gst_hand_scene_src_decide_allocation(GstBaseSrc* src, GstQuery* query)
{
    GstCaps* caps = nullptr;
    gst_query_parse_allocation(query, &caps, nullptr);
    GstVideoInfo info;
    if (!caps || !gst_video_info_from_caps(&info, caps))
        return FALSE;
    GstBufferPool* pool = nullptr;
    guint size = guint(GST_VIDEO_INFO_SIZE(&info)), min = 0, max = 0;
    const bool update = gst_query_get_n_allocation_pools(query) > 0;
    if (update) {
        guint offered = 0;
        gst_query_parse_nth_allocation_pool(query, 0, &pool, &offered, &min, &max);
        size = MAX(size, offered);
    }
    if (!pool)
        pool = gst_video_buffer_pool_new();
    GstStructure* config = gst_buffer_pool_get_config(pool);
    gst_buffer_pool_config_set_params(config, caps, size, min, max);
    if (gst_query_find_allocation_meta(query, GST_VIDEO_META_API_TYPE, nullptr))
        gst_buffer_pool_config_add_option(config, GST_BUFFER_POOL_OPTION_VIDEO_META);
    if (!gst_buffer_pool_set_config(pool, config)) {
        // A downstream pool may refuse the options; fall back to one of our own.
        gst_object_unref(pool);
        pool = gst_video_buffer_pool_new();
        config = gst_buffer_pool_get_config(pool);
        gst_buffer_pool_config_set_params(config, caps, size, min, max);
        gst_buffer_pool_set_config(pool, config);
    }
    if (update)
        gst_query_set_nth_allocation_pool(query, 0, pool, size, min, max);
    else
        gst_query_add_allocation_pool(query, pool, size, min, max);
    gst_object_unref(pool);
    return GST_BASE_SRC_CLASS(gst_hand_scene_src_parent_class)->decide_allocation(src, query);
}

// ---------------------------------------------------------------------------------------
// Timing

static GstClockTime frame_time(const GstVideoInfo& info, guint64 frame)
{
    return gst_util_uint64_scale(frame, GST_SECOND * GST_VIDEO_INFO_FPS_D(&info), GST_VIDEO_INFO_FPS_N(&info));
}

// A live frame's timestamp is the running time it is taken at: frame 0 when the first frame
// is asked for, then one frame duration apart. Not live: the frame's place in the stream.
static GstClockTime capture_timestamp(GstHandSceneSrc* self, guint64 frame)
{
    SceneState& st = *self->state;
    if (!gst_base_src_is_live(GST_BASE_SRC(self)))
        return frame_time(st.info, frame);
    if (!GST_CLOCK_TIME_IS_VALID(st.live_origin)) {
        st.live_origin = 0;
        if (GstClock* clock = gst_element_get_clock(GST_ELEMENT(self))) {
            const GstClockTime now = gst_clock_get_time(clock);
            const GstClockTime base = gst_element_get_base_time(GST_ELEMENT(self));
            st.live_origin = now > base ? now - base : 0;
            gst_object_unref(clock);
        }
    }
    return st.live_origin + frame_time(st.info, frame);
}

// A live source waits for its frames' capture times itself (fill), so basesrc does not sync:
// when it does, it also shifts every timestamp by the startup delay of the first frame, and
// downstream would see other times than the ones the head's pose was read at.
static void gst_hand_scene_src_get_times(GstBaseSrc*, GstBuffer*, GstClockTime* start, GstClockTime* end)
{
    *start = GST_CLOCK_TIME_NONE;
    *end = GST_CLOCK_TIME_NONE;
}

// Waits until the clock reaches the running time `until`. False when basesrc unlocked the
// source (flushing or stopping) meanwhile.
static bool wait_for_running_time(GstHandSceneSrc* self, GstClockTime until)
{
    GstClock* clock = gst_element_get_clock(GST_ELEMENT(self));
    if (!clock)
        return true;
    SceneState& st = *self->state;
    const GstClockTime at = gst_element_get_base_time(GST_ELEMENT(self)) + until;
    GST_OBJECT_LOCK(self);
    if (st.unlocked) {
        GST_OBJECT_UNLOCK(self);
        gst_object_unref(clock);
        return false;
    }
    GstClockID wait = gst_clock_new_single_shot_id(clock, at);
    st.capture_wait = wait;
    GST_OBJECT_UNLOCK(self);
    const GstClockReturn r = gst_clock_id_wait(wait, nullptr);
    GST_OBJECT_LOCK(self);
    st.capture_wait = nullptr;
    GST_OBJECT_UNLOCK(self);
    gst_clock_id_unref(wait);
    gst_object_unref(clock);
    return r != GST_CLOCK_UNSCHEDULED;
}

static gboolean gst_hand_scene_src_unlock(GstBaseSrc* src)
{
    GstHandSceneSrc* self = GST_HAND_SCENE_SRC(src);
    GST_OBJECT_LOCK(self);
    self->state->unlocked = true;
    if (self->state->capture_wait)
        gst_clock_id_unschedule(self->state->capture_wait);
    GST_OBJECT_UNLOCK(self);
    return TRUE;
}

static gboolean gst_hand_scene_src_unlock_stop(GstBaseSrc* src)
{
    GstHandSceneSrc* self = GST_HAND_SCENE_SRC(src);
    GST_OBJECT_LOCK(self);
    self->state->unlocked = false;
    GST_OBJECT_UNLOCK(self);
    return TRUE;
}

static gboolean gst_hand_scene_src_is_seekable(GstBaseSrc* src) { return !gst_base_src_is_live(src); }

static gboolean gst_hand_scene_src_do_seek(GstBaseSrc* src, GstSegment* segment)
{
    GstHandSceneSrc* self = GST_HAND_SCENE_SRC(src);
    const GstVideoInfo& info = self->state->info;
    segment->time = segment->start;
    if (info.finfo && GST_VIDEO_INFO_FPS_N(&info) > 0) {
        // The first frame that starts at or after the segment start.
        const guint64 d = GST_SECOND * guint64(GST_VIDEO_INFO_FPS_D(&info));
        const guint64 n = guint64(GST_VIDEO_INFO_FPS_N(&info));
        self->state->next_frame = gst_util_uint64_scale_ceil(segment->start, n, d);
    } else {
        self->state->next_frame = 0;
    }
    return TRUE;
}

static gboolean gst_hand_scene_src_query(GstBaseSrc* src, GstQuery* query)
{
    GstHandSceneSrc* self = GST_HAND_SCENE_SRC(src);
    if (GST_QUERY_TYPE(query) == GST_QUERY_LATENCY && gst_base_src_is_live(src)) {
        const GstVideoInfo& info = self->state->info;
        if (!info.finfo || GST_VIDEO_INFO_FPS_N(&info) <= 0)
            return FALSE;
        // A frame is complete one frame duration after its timestamp.
        const GstClockTime latency = frame_time(info, 1);
        gst_query_set_latency(query, TRUE, latency, latency);
        return TRUE;
    }
    return GST_BASE_SRC_CLASS(gst_hand_scene_src_parent_class)->query(src, query);
}

// ---------------------------------------------------------------------------------------
// Frames

static void post_truth(GstHandSceneSrc* self, guint64 frame, GstClockTime pts, const SceneSettings& settings)
{
    const gc::sim::Scene& scene = *self->state->scene;
    const gc::sim::EyeTruth& t = self->state->truth;
    const gc::sim::HandTruth hand = scene.hand_truth(scene.hand_pose(int(frame)));
    GstStructure* s = gst_structure_new(
        "hand-truth", "frame", G_TYPE_UINT64, frame, "timestamp", G_TYPE_UINT64, pts, "eye", G_TYPE_STRING,
        settings.eye == gc::Eye::Left ? "left" : "right", "visible", G_TYPE_BOOLEAN, gboolean(t.visible), "palm-x",
        G_TYPE_DOUBLE, t.palm_px.x, "palm-y", G_TYPE_DOUBLE, t.palm_px.y, "fingertip-x", G_TYPE_DOUBLE,
        t.fingertip_px.x, "fingertip-y", G_TYPE_DOUBLE, t.fingertip_px.y, "pointing-deg", G_TYPE_DOUBLE,
        t.pointing_deg, "bbox-x", G_TYPE_INT, t.bbox.x, "bbox-y", G_TYPE_INT, t.bbox.y, "bbox-width", G_TYPE_INT,
        t.bbox.width, "bbox-height", G_TYPE_INT, t.bbox.height, nullptr);
    gc::gst::set_vec3(s, "fingertip-head-mm", hand.fingertip_mm);
    gc::gst::set_vec3(s, "palm-head-mm", hand.palm_mm);
    gc::gst::set_vec3(s, "direction-head", hand.direction);
    const gc::HeadPose& pose = self->state->pose;
    gst_structure_set(s, "head-pan-deg", G_TYPE_DOUBLE, pose.pan_deg, "head-tilt-deg", G_TYPE_DOUBLE, pose.tilt_deg,
                      "head-verge-left-deg", G_TYPE_DOUBLE, pose.verge_left_deg, "head-verge-right-deg", G_TYPE_DOUBLE,
                      pose.verge_right_deg, nullptr);
    gst_element_post_message(GST_ELEMENT(self), gst_message_new_element(GST_OBJECT(self), s));
}

static GstFlowReturn gst_hand_scene_src_fill(GstPushSrc* src, GstBuffer* buffer)
{
    GstHandSceneSrc* self = GST_HAND_SCENE_SRC(src);
    SceneState& st = *self->state;
    if (!st.scene) {
        GST_ELEMENT_ERROR(self, CORE, NEGOTIATION, ("No caps were negotiated before the first frame."), (nullptr));
        return GST_FLOW_NOT_NEGOTIATED;
    }
    GST_OBJECT_LOCK(self);
    const SceneSettings settings = *self->settings;
    GST_OBJECT_UNLOCK(self);

    const guint64 frame = st.next_frame;
    if (frame > guint64(G_MAXINT)) {
        GST_ELEMENT_ERROR(self, STREAM, FAILED, ("The scene has no frame %" G_GUINT64_FORMAT ".", frame), (nullptr));
        return GST_FLOW_ERROR;
    }
    const GstClockTime pts = capture_timestamp(self, frame);
    if (gst_base_src_is_live(GST_BASE_SRC(self)) && !wait_for_running_time(self, pts))
        return GST_FLOW_FLUSHING;
    // The head's pose when this frame is exposed (its running time is its timestamp): a
    // live frame is rendered at that moment, so the pose is extrapolated from the head's
    // last report (at most one status interval old) along its velocity. Home until the
    // head is first heard from; its last pose while it is away.
    gc::HeadPose pose = st.pose;
    if (st.head) {
        const GstClockTime running = gst_segment_to_running_time(&GST_BASE_SRC(self)->segment, GST_FORMAT_TIME, pts);
        if (std::optional<gc::HeadPose> at = st.head->pose_at(gc::gst::capture_time(GST_ELEMENT(self), running)))
            pose = *at;
    }
    GstVideoFrame out;
    if (!gst_video_frame_map(&out, &st.info, buffer, GST_MAP_WRITE)) {
        GST_ELEMENT_ERROR(self, STREAM, FAILED, ("Cannot map the output buffer."), (nullptr));
        return GST_FLOW_ERROR;
    }
    try {
        gc::sim::EyeTruth* truth = settings.truth_messages ? &st.truth : nullptr;
        if (st.head) {
            // A head turned further than the simulated room reaches (one wall ahead): keep
            // the last pose that could be shown rather than stopping the stream.
            try {
                st.scene->render(int(frame), settings.eye, pose, st.bgr, truth);
                st.pose = pose;
            } catch (const std::invalid_argument& err) {
                if (!st.warned_pose)
                    GST_ELEMENT_WARNING(self, STREAM, FAILED,
                                        ("The head turned past what the simulated room can show; rendering from "
                                         "the last pose it could."),
                                        ("%s", err.what()));
                st.warned_pose = true;
                st.scene->render(int(frame), settings.eye, st.pose, st.bgr, truth);
            }
        } else {
            st.scene->render(int(frame), settings.eye, st.pose, st.bgr, truth);
        }
        st.writer.write(st.bgr, out);
    } catch (const std::exception& err) {
        gst_video_frame_unmap(&out);
        GST_ELEMENT_ERROR(self, STREAM, FAILED, ("Cannot render frame %" G_GUINT64_FORMAT ".", frame),
                          ("%s", err.what()));
        return GST_FLOW_ERROR;
    }
    gst_video_frame_unmap(&out);

    GST_BUFFER_PTS(buffer) = pts;
    GST_BUFFER_DTS(buffer) = GST_CLOCK_TIME_NONE;
    GST_BUFFER_DURATION(buffer) = frame_time(st.info, frame + 1) - frame_time(st.info, frame);
    GST_BUFFER_OFFSET(buffer) = frame;
    GST_BUFFER_OFFSET_END(buffer) = frame + 1;
    if (frame == 0)
        GST_BUFFER_FLAG_SET(buffer, GST_BUFFER_FLAG_DISCONT);
    st.next_frame = frame + 1;

    if (settings.truth_messages)
        post_truth(self, frame, pts, settings);
    return GST_FLOW_OK;
}

static gboolean gst_hand_scene_src_start(GstBaseSrc* src)
{
    GstHandSceneSrc* self = GST_HAND_SCENE_SRC(src);
    SceneState& st = *self->state;
    st.next_frame = 0;
    st.live_origin = GST_CLOCK_TIME_NONE;
    st.pose = {};
    st.warned_pose = false;
    gst_video_info_init(&st.info);
    GST_OBJECT_LOCK(self);
    const std::string uri = self->settings->head;
    GST_OBJECT_UNLOCK(self);
    if (uri.empty())
        return TRUE;
    // Only the pose is read: this client never sends a command.
    gc::headctl::HeadClientConfig config;
    config.uri = uri;
    config.backoff_max = std::chrono::milliseconds(500);
    config.clock = gc::gst::element_clock(GST_ELEMENT(self));
    config.on_state_change = gc::gst::connection_reporter(GST_ELEMENT(self), uri);
    try {
        gc::headctl::parse_head_uri(uri);
        st.head = std::make_unique<gc::headctl::HeadClient>(std::move(config));
    } catch (const std::exception& err) {
        GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS, ("Invalid head URI \"%s\".", gc::headctl::redact_uri(uri).c_str()),
                          ("%s", err.what()));
        return FALSE;
    }
    return TRUE;
}

static gboolean gst_hand_scene_src_stop(GstBaseSrc* src)
{
    GstHandSceneSrc* self = GST_HAND_SCENE_SRC(src);
    self->state->head.reset();  // joins the head client's thread
    self->state->scene.reset();
    self->state->bgr.release();
    self->state->truth = {};
    return TRUE;
}

// ---------------------------------------------------------------------------------------
// Properties

static void gst_hand_scene_src_set_property(GObject* object, guint prop_id, const GValue* value, GParamSpec* pspec)
{
    GstHandSceneSrc* self = GST_HAND_SCENE_SRC(object);
    if (prop_id == PROP_IS_LIVE) {
        gst_base_src_set_live(GST_BASE_SRC(self), g_value_get_boolean(value));
        return;
    }
    GST_OBJECT_LOCK(self);
    SceneSettings& s = *self->settings;
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
    case PROP_TRUTH_MESSAGES:
        s.truth_messages = g_value_get_boolean(value);
        break;
    case PROP_HEAD: {
        const gchar* uri = g_value_get_string(value);
        s.head = uri ? uri : "";
        break;
    }
    default:
        G_OBJECT_WARN_INVALID_PROPERTY_ID(object, prop_id, pspec);
        break;
    }
    GST_OBJECT_UNLOCK(self);
}

static void gst_hand_scene_src_get_property(GObject* object, guint prop_id, GValue* value, GParamSpec* pspec)
{
    GstHandSceneSrc* self = GST_HAND_SCENE_SRC(object);
    if (prop_id == PROP_IS_LIVE) {
        g_value_set_boolean(value, gst_base_src_is_live(GST_BASE_SRC(self)));
        return;
    }
    GST_OBJECT_LOCK(self);
    const SceneSettings& s = *self->settings;
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
    case PROP_TRUTH_MESSAGES:
        g_value_set_boolean(value, s.truth_messages);
        break;
    case PROP_HEAD:
        g_value_set_string(value, s.head.empty() ? nullptr : s.head.c_str());
        break;
    default:
        G_OBJECT_WARN_INVALID_PROPERTY_ID(object, prop_id, pspec);
        break;
    }
    GST_OBJECT_UNLOCK(self);
}

static void gst_hand_scene_src_finalize(GObject* object)
{
    GstHandSceneSrc* self = GST_HAND_SCENE_SRC(object);
    delete self->state;
    delete self->settings;
    G_OBJECT_CLASS(gst_hand_scene_src_parent_class)->finalize(object);
}

static void gst_hand_scene_src_class_init(GstHandSceneSrcClass* klass)
{
    GObjectClass* gobject_class = G_OBJECT_CLASS(klass);
    GstElementClass* element_class = GST_ELEMENT_CLASS(klass);
    GstBaseSrcClass* basesrc_class = GST_BASE_SRC_CLASS(klass);
    GstPushSrcClass* pushsrc_class = GST_PUSH_SRC_CLASS(klass);

    GST_DEBUG_CATEGORY_INIT(gst_hand_scene_src_debug, "handscenesrc", 0, "synthetic pointing-hand camera");

    gobject_class->set_property = gst_hand_scene_src_set_property;
    gobject_class->get_property = gst_hand_scene_src_get_property;
    gobject_class->finalize = gst_hand_scene_src_finalize;

    const auto flags = GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY);
    g_object_class_install_property(gobject_class, PROP_EYE,
                                    g_param_spec_enum("eye", "Eye", "Which camera of the stereo head to render",
                                                      GST_TYPE_HAND_SCENE_EYE, int(gc::Eye::Left), flags));
    g_object_class_install_property(
        gobject_class, PROP_SCENE,
        g_param_spec_enum("scene", "Scene", "Background clutter preset", GST_TYPE_HAND_SCENE_PRESET,
                          int(gc::sim::Preset::Clean), flags));
    g_object_class_install_property(
        gobject_class, PROP_MOTION,
        g_param_spec_enum("motion", "Motion", "Scripted hand motion (every script starts with a short wave)",
                          GST_TYPE_HAND_SCENE_MOTION, int(gc::sim::Motion::Mixed), flags));
    g_object_class_install_property(
        gobject_class, PROP_SEED,
        g_param_spec_uint64("seed", "Seed",
                            "Background layout, skin tone and noise: the same seed renders the same scene", 0,
                            G_MAXUINT64, kDefaultSeed, flags));
    g_object_class_install_property(
        gobject_class, PROP_NOISE,
        g_param_spec_double("noise", "Noise", "Standard deviation of the sensor noise, grey levels", 0.0, 64.0,
                            kDefaultNoise, flags));
    g_object_class_install_property(
        gobject_class, PROP_LIGHTING_CHANGE,
        g_param_spec_boolean("lighting-change", "Lighting change",
                             "A slow global change of brightness and colour temperature", FALSE, flags));
    g_object_class_install_property(
        gobject_class, PROP_VARIETY,
        g_param_spec_enum("variety", "Variety",
                          "What else the seed varies: nothing (the preset as it always was) or the hand, "
                          "people, light and camera",
                          GST_TYPE_HAND_SCENE_VARIETY, int(gc::sim::Variety::None), flags));
    g_object_class_install_property(
        gobject_class, PROP_IS_LIVE,
        g_param_spec_boolean("is-live", "Is live", "Behave as a live camera: frames come at the frame rate",
                             FALSE, flags));
    g_object_class_install_property(
        gobject_class, PROP_TRUTH_MESSAGES,
        g_param_spec_boolean("truth-messages", "Truth messages",
                             "Post a hand-truth element message with the ground truth of every frame", TRUE,
                             GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_PLAYING)));

    g_object_class_install_property(
        gobject_class, PROP_HEAD,
        g_param_spec_string("head", "Head URI",
                            "The head the simulated cameras sit on (tcp://host:port, e.g. headsim): every frame is "
                            "rendered from its pose at the frame's capture time, so handtracker steering that head "
                            "closes the loop; use with is-live=true. Unset: the head at its home pose",
                            nullptr, flags));

    gst_element_class_add_static_pad_template(element_class, &src_template);
    gst_element_class_set_static_metadata(
        element_class, "Pointing hand scene source", "Source/Video",
        "Renders one camera of a synthetic stereo scene with a person pointing, frame n for buffer offset n, and "
        "posts the ground truth of every frame as a hand-truth element message",
        "GestureCAM <gesturecam@localhost>");

    basesrc_class->fixate = gst_hand_scene_src_fixate;
    basesrc_class->set_caps = gst_hand_scene_src_set_caps;
    basesrc_class->decide_allocation = gst_hand_scene_src_decide_allocation;
    basesrc_class->get_times = gst_hand_scene_src_get_times;
    basesrc_class->is_seekable = gst_hand_scene_src_is_seekable;
    basesrc_class->do_seek = gst_hand_scene_src_do_seek;
    basesrc_class->query = gst_hand_scene_src_query;
    basesrc_class->start = gst_hand_scene_src_start;
    basesrc_class->stop = gst_hand_scene_src_stop;
    basesrc_class->unlock = gst_hand_scene_src_unlock;
    basesrc_class->unlock_stop = gst_hand_scene_src_unlock_stop;
    pushsrc_class->fill = gst_hand_scene_src_fill;

    gst_type_mark_as_plugin_api(GST_TYPE_HAND_SCENE_EYE, GstPluginAPIFlags(0));
    gst_type_mark_as_plugin_api(GST_TYPE_HAND_SCENE_PRESET, GstPluginAPIFlags(0));
    gst_type_mark_as_plugin_api(GST_TYPE_HAND_SCENE_MOTION, GstPluginAPIFlags(0));
    gst_type_mark_as_plugin_api(GST_TYPE_HAND_SCENE_VARIETY, GstPluginAPIFlags(0));
}

static void gst_hand_scene_src_init(GstHandSceneSrc* self)
{
    self->settings = new SceneSettings();
    self->state = new SceneState();
    gst_video_info_init(&self->state->info);
    GstBaseSrc* base = GST_BASE_SRC(self);
    gst_base_src_set_format(base, GST_FORMAT_TIME);
    gst_base_src_set_live(base, FALSE);
}
