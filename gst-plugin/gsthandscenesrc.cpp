// handscenesrc: GObject glue over gc::sim::Scene. Frame n of the scene is rendered for
// buffer offset n, so two instances with the same scene, motion and seed (one per eye)
// form a consistent stereo pair whatever order they run in. With a head URI the cameras
// sit on that head: each frame is rendered from the head's pose at its capture time.
#include "gsthandscenesrc.hpp"

#include "handscenesrc_frames.hpp"
#include "handscenesrc_settings.hpp"
#include "handscenesrc_state.hpp"
#include "head_connection.hpp"
#include "head_uri_property.hpp"
#include "video_bgr.hpp"

#include "headctl/head_client.hpp"
#include "headctl/uri.hpp"
#include "sim/scene.hpp"

#include <gst/video/video.h>

#include <chrono>
#include <exception>
#include <memory>
#include <string>

GST_DEBUG_CATEGORY(gst_hand_scene_src_debug);
#define GST_CAT_DEFAULT gst_hand_scene_src_debug

using namespace gc::gst;

G_DEFINE_TYPE(GstHandSceneSrc, gst_hand_scene_src, GST_TYPE_PUSH_SRC)
GST_ELEMENT_REGISTER_DEFINE(handscenesrc, "handscenesrc", GST_RANK_NONE, GST_TYPE_HAND_SCENE_SRC)

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
    config.aim_mm = settings.aim;
    config.gesture = settings.gesture;
    config.gesture_cycle_s = settings.gesture_cycle_s;
    try {
        self->state->scene.emplace(config);
    } catch (const std::exception& err) {
        GST_ELEMENT_ERROR(self, CORE, NEGOTIATION, ("Cannot build the scene for %" GST_PTR_FORMAT ".", caps),
                          ("%s", err.what()));
        return FALSE;
    }
    self->state->stream.info = info;
    return TRUE;
}

// Buffers of a full frame from a video buffer pool (downstream's when it offers one).
static gboolean gst_hand_scene_src_decide_allocation(GstBaseSrc* src, GstQuery* query)
{
    GstCaps* caps = nullptr;
    gst_query_parse_allocation(query, &caps, nullptr);
    GstVideoInfo info;
    if (!caps || !gst_video_info_from_caps(&info, caps)) return FALSE;
    GstBufferPool* pool = nullptr;
    guint size = guint(GST_VIDEO_INFO_SIZE(&info)), min = 0, max = 0;
    const bool update = gst_query_get_n_allocation_pools(query) > 0;
    if (update) {
        guint offered = 0;
        gst_query_parse_nth_allocation_pool(query, 0, &pool, &offered, &min, &max);
        size = MAX(size, offered);
    }
    if (!pool) pool = gst_video_buffer_pool_new();
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
    if (!gst_base_src_is_live(GST_BASE_SRC(self))) return frame_time(st.stream.info, frame);
    if (!GST_CLOCK_TIME_IS_VALID(st.stream.live_origin)) {
        st.stream.live_origin = 0;
        if (GstClock* clock = gst_element_get_clock(GST_ELEMENT(self))) {
            const GstClockTime now = gst_clock_get_time(clock);
            const GstClockTime base = gst_element_get_base_time(GST_ELEMENT(self));
            st.stream.live_origin = now > base ? now - base : 0;
            gst_object_unref(clock);
        }
    }
    return st.stream.live_origin + frame_time(st.stream.info, frame);
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
    if (!clock) return true;
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
    if (self->state->capture_wait) gst_clock_id_unschedule(self->state->capture_wait);
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
    const GstVideoInfo& info = self->state->stream.info;
    segment->time = segment->start;
    if (info.finfo && GST_VIDEO_INFO_FPS_N(&info) > 0) {
        // The first frame that starts at or after the segment start.
        const guint64 d = GST_SECOND * guint64(GST_VIDEO_INFO_FPS_D(&info));
        const guint64 n = guint64(GST_VIDEO_INFO_FPS_N(&info));
        self->state->stream.next_frame = gst_util_uint64_scale_ceil(segment->start, n, d);
    } else {
        self->state->stream.next_frame = 0;
    }
    return TRUE;
}

static gboolean gst_hand_scene_src_query(GstBaseSrc* src, GstQuery* query)
{
    GstHandSceneSrc* self = GST_HAND_SCENE_SRC(src);
    if (GST_QUERY_TYPE(query) == GST_QUERY_LATENCY && gst_base_src_is_live(src)) {
        const GstVideoInfo& info = self->state->stream.info;
        if (!info.finfo || GST_VIDEO_INFO_FPS_N(&info) <= 0) return FALSE;
        // A frame is complete one frame duration after its timestamp. Every frame is rendered
        // into a buffer of its own, so downstream may hold any number of them: no maximum.
        const GstClockTime latency = frame_time(info, 1);
        gst_query_set_latency(query, TRUE, latency, GST_CLOCK_TIME_NONE);
        return TRUE;
    }
    return GST_BASE_SRC_CLASS(gst_hand_scene_src_parent_class)->query(src, query);
}

// ---------------------------------------------------------------------------------------
// Frames

static GstFlowReturn gst_hand_scene_src_fill(GstPushSrc* src, GstBuffer* buffer)
{
    GstHandSceneSrc* self = GST_HAND_SCENE_SRC(src);
    SceneState& st = *self->state;
    if (!st.scene) {
        GST_ELEMENT_ERROR(self, CORE, NEGOTIATION, ("No caps were negotiated before the first frame."), (nullptr));
        return GST_FLOW_NOT_NEGOTIATED;
    }
    const guint64 frame = st.stream.next_frame;
    if (frame > guint64(G_MAXINT)) {
        GST_ELEMENT_ERROR(self, STREAM, FAILED, ("The scene has no frame %" G_GUINT64_FORMAT ".", frame), (nullptr));
        return GST_FLOW_ERROR;
    }
    const GstClockTime pts = capture_timestamp(self, frame);
    gst_object_sync_values(GST_OBJECT(self), pts);  // head-pan, head-tilt may be driven by a controller
    GST_OBJECT_LOCK(self);
    const SceneSettings settings = *self->settings;
    GST_OBJECT_UNLOCK(self);
    if (gst_base_src_is_live(GST_BASE_SRC(self)) && !wait_for_running_time(self, pts)) return GST_FLOW_FLUSHING;
    if (const GstFlowReturn ret = render_frame(self, settings, frame, pose_at_capture(self, settings, pts), buffer);
        ret != GST_FLOW_OK)
        return ret;

    GST_BUFFER_PTS(buffer) = pts;
    GST_BUFFER_DTS(buffer) = GST_CLOCK_TIME_NONE;
    GST_BUFFER_DURATION(buffer) = frame_time(st.stream.info, frame + 1) - frame_time(st.stream.info, frame);
    GST_BUFFER_OFFSET(buffer) = frame;
    GST_BUFFER_OFFSET_END(buffer) = frame + 1;
    if (frame == 0) GST_BUFFER_FLAG_SET(buffer, GST_BUFFER_FLAG_DISCONT);
    st.stream.next_frame = frame + 1;

    if (settings.truth_messages) post_truth(self, frame, pts, settings);
    return GST_FLOW_OK;
}

static gboolean gst_hand_scene_src_start(GstBaseSrc* src)
{
    GstHandSceneSrc* self = GST_HAND_SCENE_SRC(src);
    SceneState& st = *self->state;
    st.stream = {};
    GST_OBJECT_LOCK(self);
    const std::string uri = self->settings->head;
    const std::string token_file = self->settings->head_token_file;
    GST_OBJECT_UNLOCK(self);
    if (uri.empty()) return TRUE;
    // Only the pose is read: this client never sends a command.
    gc::headctl::HeadClientConfig config;
    config.uri = uri;
    if (!gc::gst::read_head_token(GST_ELEMENT(self), token_file, config.token)) return FALSE;
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
    if (is_live_property(prop_id)) {
        gst_base_src_set_live(GST_BASE_SRC(self), g_value_get_boolean(value));
        return;
    }
    GST_OBJECT_LOCK(self);
    const bool known = set_scene_setting(*self->settings, prop_id, value);
    GST_OBJECT_UNLOCK(self);
    if (!known) G_OBJECT_WARN_INVALID_PROPERTY_ID(object, prop_id, pspec);
}

static void gst_hand_scene_src_get_property(GObject* object, guint prop_id, GValue* value, GParamSpec* pspec)
{
    GstHandSceneSrc* self = GST_HAND_SCENE_SRC(object);
    if (is_live_property(prop_id)) {
        g_value_set_boolean(value, gst_base_src_is_live(GST_BASE_SRC(self)));
        return;
    }
    GST_OBJECT_LOCK(self);
    const bool known = get_scene_setting(*self->settings, prop_id, value);
    GST_OBJECT_UNLOCK(self);
    if (!known) G_OBJECT_WARN_INVALID_PROPERTY_ID(object, prop_id, pspec);
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

    install_scene_properties(gobject_class);

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

    mark_scene_enums_as_plugin_api();
}

static void gst_hand_scene_src_init(GstHandSceneSrc* self)
{
    self->settings = new SceneSettings();
    self->state = new SceneState();
    GstBaseSrc* base = GST_BASE_SRC(self);
    gst_base_src_set_format(base, GST_FORMAT_TIME);
    gst_base_src_set_live(base, FALSE);
}
