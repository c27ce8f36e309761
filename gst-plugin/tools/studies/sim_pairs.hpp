// Rendered stereo pairs of the synthetic scene with a placed hand, and the adapter that
// turns the scene's ground truth into the per-eye estimates the 3D step consumes (what a
// perfect tracker would report); and a scripted scene tracked end to end, its rays scored
// against the truth.
#pragma once

#include "common/types.hpp"
#include "sim/scene.hpp"
#include "stereo/pointing.hpp"
#include "tracker/stereo_tracker.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace gc::test {

inline double angle_between_deg(const cv::Vec3d& a, const cv::Vec3d& b)
{
    const double c = a.dot(b) / (cv::norm(a) * cv::norm(b));
    return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / CV_PI;
}

// The estimate a perfect tracker would give: the truth mask's outline, fingertip and palm.
inline EyeEstimate estimate_from_truth(const sim::EyeTruth& truth)
{
    EyeEstimate e;
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(truth.mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
    if (!truth.visible || contours.empty()) return e;
    const auto largest = std::max_element(contours.begin(), contours.end(), [](const auto& a, const auto& b) {
        return cv::contourArea(a) < cv::contourArea(b);
    });
    e.state = TrackState::Tracking;
    e.confidence = 1.0;
    e.contour.assign(largest->begin(), largest->end());
    e.bbox = cv::boundingRect(*largest);
    e.fingertip = truth.fingertip_px;
    e.palm = truth.palm_px;
    e.pointing_deg = truth.pointing_deg;
    return e;
}

struct PoseResult {
    bool visible = false;
    Pointing3D estimate;
    sim::HandTruth truth;
    double angle_error_deg = 0.0;
    double depth_error_mm = 0.0;  // fingertip, head frame z, estimated - true
};

// Renders `hand` with the head at `render_head` and estimates with `nominal_head` (they
// differ to simulate motor-angle error).
inline PoseResult run_pose(const sim::Scene& scene, PointingEstimator& estimator, const sim::HandPose& hand,
                           const HeadPose& render_head, const HeadPose& nominal_head, int frame, cv::Mat& left,
                           cv::Mat& right)
{
    PoseResult r;
    sim::EyeTruth lt, rt;
    scene.render_pose(hand, frame, Eye::Left, render_head, left, &lt);
    scene.render_pose(hand, frame, Eye::Right, render_head, right, &rt);
    const EyeEstimate le = estimate_from_truth(lt), re = estimate_from_truth(rt);
    r.visible = le.valid() && re.valid();
    r.truth = scene.hand_truth(hand);
    if (!r.visible) return r;
    r.estimate = estimator.estimate(left, right, le, re, nominal_head);
    if (r.estimate.valid) {
        r.angle_error_deg = angle_between_deg(r.estimate.direction_head, r.truth.direction);
        r.depth_error_mm = r.estimate.fingertip_head_mm[2] - r.truth.fingertip_mm[2];
    }
    return r;
}

inline double percentile(std::vector<double> v, double p)
{
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    const double idx = p * (v.size() - 1);
    const auto lo = static_cast<std::size_t>(std::floor(idx));
    const auto hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (idx - lo) * (v[hi] - v[lo]);
}

// The first `frames` frames of `scene` tracked in stereo (the contour-based path) and the 3D
// step on them: how many frames both eyes tracked, and each ray's angle and fingertip depth
// error against the truth.
struct TrackedRays {
    int tracking = 0;
    std::vector<double> angle, depth;
};

inline TrackedRays track_scene(const sim::Scene& scene, int particles, int frames)
{
    TrackerParams params;
    params.detector = HandDetector::Motion;  // the contour-based path
    params.particles = particles;
    StereoHandTracker trackers(params);
    PointingEstimator estimator(scene.calibration());
    cv::Mat left, right;
    TrackedRays r;
    for (int f = 0; f < frames; ++f) {
        scene.render(f, Eye::Left, {}, left);
        scene.render(f, Eye::Right, {}, right);
        const StereoEstimate est = trackers.process(left, right);
        if (!est.left.valid() || !est.right.valid()) continue;
        ++r.tracking;
        const Pointing3D p = estimator.estimate(left, right, est.left, est.right);
        if (!p.valid) continue;
        const sim::HandTruth truth = scene.hand_truth(scene.hand_pose(f));
        r.angle.push_back(angle_between_deg(p.direction_head, truth.direction));
        r.depth.push_back(std::abs(p.fingertip_head_mm[2] - truth.fingertip_mm[2]));
    }
    return r;
}

}  // namespace gc::test
