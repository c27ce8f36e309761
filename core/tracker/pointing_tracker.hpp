// One stereo (or mono) frame in, everything the product reports out: both eyes' estimates
// and the 3D pointing ray. The one code path shared by the handtracker element and the
// gesturecam-track tool, so both give the same output for the same input.
#pragma once

#include "stereo/calibration.hpp"
#include "stereo/pointing.hpp"
#include "tracker/stereo_tracker.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

namespace gc {

struct FrameResult {
    std::int64_t frame = 0;
    std::int64_t pts_ns = -1;                  // -1 when unknown
    TrackState state = TrackState::Acquiring;  // tracking only when every eye tracks
    bool stereo = false;
    EyeEstimate left;
    EyeEstimate right;             // meaningful when stereo
    Pointing3D pointing;           // valid only in stereo when both eyes track
    std::optional<HeadPose> head;  // the head pose at capture, when known
};

class PointingTracker {
public:
    // calibration: nullopt = the nominal default for the first frame's size.
    explicit PointingTracker(const TrackerParams& params, std::optional<StereoCalibration> calibration = std::nullopt);
    ~PointingTracker();

    // BGR frames, CV_8UC3. Throws std::invalid_argument on bad frames (empty, wrong type,
    // left/right size mismatch, or a size that does not match the calibration).
    const FrameResult& process_stereo(const cv::Mat& left_bgr, const cv::Mat& right_bgr, std::int64_t pts_ns = -1,
                                      const std::optional<HeadPose>& head = std::nullopt,
                                      const ImageMotion& left_motion = {}, const ImageMotion& right_motion = {});
    const FrameResult& process_mono(const cv::Mat& bgr, std::int64_t pts_ns = -1, const ImageMotion& motion = {});
    void reset();
    const FrameResult& last() const;
    // The hypotheses behind `eye` in the last frame (for drawing their marginals): the mono
    // tracker's for Left in mono mode, none for Right there; both eyes' in stereo mode.
    std::span<const Particle> particles(Eye eye) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// One JSON line (no trailing newline) in the schema of docs/interfaces.md.
std::string to_json_line(const FrameResult& result);

}  // namespace gc
