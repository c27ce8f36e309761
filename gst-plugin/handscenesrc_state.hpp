// handscenesrc's instance as its parts see it: the properties (SceneSettings, under the
// object lock) apart from what the streaming thread builds up (SceneState).
#pragma once

#include "gsthandscenesrc.hpp"
#include "handscenesrc_settings.hpp"

#include "headctl/head_client.hpp"
#include "sim/scene.hpp"

#include <gst/video/video.h>
#include <opencv2/core.hpp>

#include <memory>
#include <optional>

GST_DEBUG_CATEGORY_EXTERN(gst_hand_scene_src_debug);

namespace gc::gst {

// What one run of the stream builds up; each start begins from SceneStream{}.
struct SceneStream {
    GstVideoInfo info = [] {
        GstVideoInfo blank;
        gst_video_info_init(&blank);
        return blank;
    }();
    guint64 next_frame = 0;  // the offset of the next buffer
    // Live: the running time at which frame 0 was taken; NONE until then.
    GstClockTime live_origin = GST_CLOCK_TIME_NONE;
    HeadPose pose;             // the pose the last frame was rendered from
    bool warned_pose = false;  // about a head pose the room cannot be rendered from
};

// Everything the streaming thread owns.
struct SceneState {
    std::optional<sim::Scene> scene;
    SceneStream stream;
    // Live: the wait for the next frame's capture time, and whether basesrc asked us to stop
    // waiting. Both under the object lock.
    GstClockID capture_wait = nullptr;
    bool unlocked = false;
    cv::Mat bgr;
    cv::Mat yuv_scratch;
    sim::EyeTruth truth;
    std::unique_ptr<headctl::HeadClient> head;
};

}  // namespace gc::gst

struct _GstHandSceneSrc {
    GstPushSrc parent;
    gc::gst::SceneSettings* settings;
    gc::gst::SceneState* state;
};
