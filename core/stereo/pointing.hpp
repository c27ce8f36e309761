// The 3D step (docs/stereo.md): the fingertip and palm triangulated from both views' key
// points, or else correspondence along epipolar lines inside the tracked hand regions and a
// robust plane fit; then the pointing ray.
#pragma once

#include "common/types.hpp"
#include "stereo/calibration.hpp"

#include <opencv2/core.hpp>

#include <memory>

namespace gc {

// Azimuth: atan2(dx, dz), positive to the right. Elevation: atan2(-dy, hypot(dx, dz)),
// positive up. Both in degrees, of the direction in the frame they are given for.
struct Pointing3D {
    bool valid = false;
    // Left camera frame at capture (x right, y down, z forward), millimetres.
    cv::Vec3d fingertip_mm;
    cv::Vec3d palm_mm;
    cv::Vec3d direction;  // unit, palm -> fingertip
    double azimuth_deg = 0.0;
    double elevation_deg = 0.0;
    // The same in the head frame (stereo/head_geometry.hpp) at the capture pose.
    cv::Vec3d fingertip_head_mm;
    cv::Vec3d palm_head_mm;
    cv::Vec3d direction_head;
    double azimuth_head_deg = 0.0;
    double elevation_head_deg = 0.0;
    int correspondences = 0;  // inliers used
};

void direction_angles(const cv::Vec3d& direction, double& azimuth_deg, double& elevation_deg);

class PointingEstimator {
public:
    explicit PointingEstimator(const StereoCalibration& calibration);
    ~PointingEstimator();
    PointingEstimator(PointingEstimator&&) noexcept;
    PointingEstimator& operator=(PointingEstimator&&) noexcept;

    // Both estimates must be valid; otherwise returns {valid = false}. `head` is the pose
    // at capture (vergence changes the epipolar geometry).
    Pointing3D estimate(const cv::Mat& left_bgr, const cv::Mat& right_bgr, const EyeEstimate& left,
                        const EyeEstimate& right, const HeadPose& head = {});

    const StereoCalibration& calibration() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace gc
