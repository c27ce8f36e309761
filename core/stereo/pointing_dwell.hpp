// What a held pointing picks for the attended view: a pointing whose direction stays steady
// for a dwell time picks where its ray meets a configured plane (a wall, a table), or else the
// point a set distance along it; a pointing that is not held
// picks nothing, and the target is let go once no pointing has been seen for a while. The
// target lives in the head frame, which stays put while the head turns, so the view can
// keep the speaker's hand in sight and still frame what was pointed at.
#pragma once

#include "common/types.hpp"
#include "stereo/calibration.hpp"
#include "stereo/pointing.hpp"
#include "stereo/ray_geometry.hpp"

#include <opencv2/core.hpp>

#include <optional>

namespace gc {

// Where a pointing's target lies: where its ray meets `plane` ahead of the fingertip (a wall,
// a table); `distance_mm` along the ray when there is no plane, or the ray runs away from it
// or meets it more than 100 m away.
struct TargetPlacement {
    double distance_mm = 2000.0;
    std::optional<Plane> plane;  // head frame, mm
};

struct DwellParams {
    double dwell_s = 1.0;     // a pointing held this long picks its target
    double steady_deg = 6.0;  // ...while its direction stays this close to its start
    double release_s = 1.0;   // no pointing for this long lets the target go
    double gap_s = 0.3;       // a dwell survives the tracker missing the ray this long
    TargetPlacement target;   // where the picked target lies along the ray
};

// The point a pointing designates under `placement`.
cv::Vec3d pointed_target(const Pointing3D& pointing, const TargetPlacement& placement);

class PointingDwell {
public:
    // One frame taken at `t_s` (seconds, increasing) with what the tracker saw; returns the
    // target (head frame, millimetres) while one is held.
    std::optional<cv::Vec3d> update(double t_s, const Pointing3D& pointing, const DwellParams& params);
    // How many targets have been picked so far: it grows on the frame of each pick, also
    // when a pick lands where the previous target was.
    int picks() const { return picks_; }

private:
    void start_dwell(double t_s, const Pointing3D& pointing);

    std::optional<double> dwell_start_s_;
    cv::Vec3d dwell_direction_;
    cv::Vec3d fingertip_sum_, direction_sum_;  // of the dwell's rays so far
    int ray_count_ = 0;
    std::optional<cv::Vec3d> held_;
    cv::Vec3d held_direction_;
    double last_pointing_s_ = 0.0;
    int picks_ = 0;
};

// A head-frame region of `size_mm` around `centre_mm` as the left camera sees it at `pose`
// (its zoom included): where its centre lands (pixels, lens distortion left out) and how wide
// it looks.
struct ImageRegion {
    cv::Point2d centre;
    double width_px = 0.0;
};
// Nullopt when the point lies behind the camera.
std::optional<ImageRegion> region_in_left_view(const cv::Vec3d& centre_mm, double size_mm,
                                               const StereoCalibration& calibration, const HeadPose& pose);

}  // namespace gc
