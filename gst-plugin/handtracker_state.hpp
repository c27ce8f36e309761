// handtracker's instance as its parts see it: the properties (Settings, read and written
// under the object lock) apart from what the streaming thread builds up (State).
#pragma once

#include "gsthandtracker.hpp"

#include "attention_window.hpp"
#include "handtracker_settings.hpp"
#include "handtracker_stats.hpp"
#include "tracking_overlay.hpp"
#include "video_bgr.hpp"

#include "common/line_output.hpp"
#include "headctl/steering/director_camera.hpp"
#include "headctl/steering/head_link.hpp"
#include "stereo/calibration.hpp"
#include "stereo/pointing_dwell.hpp"
#include "tracker/pointing_tracker.hpp"

#include <opencv2/core.hpp>

#include <array>
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

GST_DEBUG_CATEGORY_EXTERN(gst_hand_tracker_debug);

namespace gc::gst {

// What the frames of one stream build up. A new stream (after a flush, a stop or a new
// tracker) starts from StreamState{}.
struct StreamState {
    cv::Size view_size;  // of the tracked views, to reset on renegotiation
    bool stereo = false;
    AttentionWindow attention;
    PointingDwell dwell;
    std::optional<cv::Vec3d> target;  // what a held pointing picked (head frame, mm)
    std::optional<TrackState> last_posted_state;
    // The input timestamps of the views tracked last (packed or left, right).
    std::array<GstClockTime, 2> tracked_inputs = {GST_CLOCK_TIME_NONE, GST_CLOCK_TIME_NONE};
};

// Everything the streaming thread owns.
struct TrackerState {
    std::unique_ptr<PointingTracker> tracker;
    std::optional<StereoCalibration> calibration;
    std::string calibration_path;  // the file `calibration` was loaded from
    StreamState stream;
    BgrReader readers[2];
    cv::Mat halves[2];  // the two views of a side-by-side frame
    cv::Mat canvas;     // the view being drawn on
    cv::Mat scaled;     // the view at the output size
    gc::gst::BgrWriter writer;
    std::vector<float> contour_scratch;
    TrackingOverlay overlay;
    std::optional<LineOutput> json;  // json-location: one whole line per write, each checked
    std::string json_path;
    std::string json_line;
    std::unique_ptr<headctl::HeadLink> head;
    std::unique_ptr<headctl::DirectorCamera> director;  // a second PTZ camera, built at the first frame
    std::string director_token;                         // read from director-token-file at start
    bool director_failed = false;                       // it could not be made: reported once, not tried again
    std::string head_token;                             // read from head-token-file at start
    cv::Size head_view_size;                            // the view size of the head link's calibration
    bool warned_stale_views = false;                    // the current run of too-old views was reported
    guint64 failed_frames = 0;  // frames the tracker failed on and that were passed on untracked
    // What the debug log last said of each view: a line is written when either changes.
    std::array<TrackState, 2> logged_state = {TrackState::Acquiring, TrackState::Acquiring};
    std::array<Gesture, 2> logged_gesture = {Gesture::Unknown, Gesture::Unknown};

    // The frames no longer follow the previous ones: tracking starts over.
    void forget()
    {
        if (tracker) tracker->reset();
        stream = {};
    }
};

}  // namespace gc::gst

struct _GstHandTracker {
    GstVideoAggregator parent;
    gc::gst::TrackerSettings* settings;
    gc::gst::TrackerState* state;
    std::atomic<bool>* rebuild;  // tracker parameters changed
    std::atomic<bool>* flushed;  // a flushing seek: the frames jump
    gc::gst::TrackerStats* stats;
};

namespace gc::gst {

// A copy of the properties, taken under the object lock.
TrackerSettings read_settings(GstHandTracker* self);

}  // namespace gc::gst
