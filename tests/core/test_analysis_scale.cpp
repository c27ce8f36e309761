// Wide frames tracked at a smaller size: the analysed size, the calibration scaled to it, the
// way back to the frame's pixels, and a rendered HD stereo pair tracked that way.
#include "sim/scene.hpp"
#include "stereo/calibration.hpp"
#include "tracker/analysis_scale.hpp"
#include "tracker/pointing_tracker.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <vector>

namespace {

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v.empty() ? NAN : v[v.size() / 2];
}

cv::Point2d project(const cv::Matx33d& M, const cv::Vec3d& X)
{
    const cv::Vec3d p = M * X;
    return {p[0] / p[2], p[1] / p[2]};
}

TEST(AnalysisScale, ScalesOnlyFramesWiderThanTheWidthAndKeepsTheirAspect)
{
    const gc::AnalysisScale hd = gc::analysis_scale({1920, 1080}, 640);
    EXPECT_TRUE(hd.active());
    EXPECT_EQ(hd.analysed, cv::Size(640, 360));
    EXPECT_DOUBLE_EQ(hd.sx, 1.0 / 3.0);
    EXPECT_DOUBLE_EQ(hd.sy, 1.0 / 3.0);
    EXPECT_FALSE(gc::analysis_scale({1920, 1080}, 0).active());
    EXPECT_FALSE(gc::analysis_scale({640, 480}, 640).active());
    EXPECT_FALSE(gc::analysis_scale({640, 480}, 1280).active());
    EXPECT_EQ(gc::analysis_scale({720, 720}, 480).analysed, cv::Size(480, 480));
}

TEST(AnalysisScale, NeverBelowTheTrackersSmallestFrame)
{
    EXPECT_EQ(gc::analysis_scale({1920, 1080}, 10).analysed, cv::Size(64, 36));
    // A wide strip keeps 32 lines rather than its aspect's few.
    EXPECT_EQ(gc::analysis_scale({4000, 100}, 64).analysed, cv::Size(1280, 32));
    EXPECT_FALSE(gc::analysis_scale({100, 32}, 64).active());
}

// Fine detail averages out rather than aliasing into false edges: a one-pixel checkerboard
// becomes an even grey at every factor, a flat colour stays itself.
TEST(AnalysisScale, DownscaleAveragesFineDetail)
{
    gc::DownscaleBuffers buffers;
    cv::Mat out;
    for (const cv::Size& frame : {cv::Size(1920, 1080), cv::Size(2560, 1440), cv::Size(720, 720)}) {
        cv::Mat3b board(frame);
        for (int y = 0; y < frame.height; ++y)
            for (int x = 0; x < frame.width; ++x) board(y, x) = cv::Vec3b::all((x + y) % 2 ? 255 : 0);
        const cv::Size to = gc::analysis_scale(frame, frame.width == 720 ? 300 : 640).analysed;
        gc::downscale(board, to, buffers, out);
        ASSERT_EQ(out.size(), to);
        double lo = 0.0, hi = 0.0;
        cv::minMaxLoc(out.reshape(1), &lo, &hi);
        EXPECT_GE(lo, 120.0) << frame;
        EXPECT_LE(hi, 135.0) << frame;
        gc::downscale(cv::Mat3b(frame, cv::Vec3b(30, 140, 220)), to, buffers, out);
        EXPECT_EQ(cv::norm(out, cv::Mat3b(to, cv::Vec3b(30, 140, 220)), cv::NORM_INF), 0.0) << frame;
    }
}

TEST(AnalysisScale, ScaledCalibrationProjectsWhereTheFramesPixelLands)
{
    gc::StereoCalibration frame = gc::default_calibration({1280, 720});
    frame.M1(0, 2) = 650.3;  // off-centre, as a real calibration has it
    frame.M1(0, 1) = 0.8;    // and skewed
    frame.M2(1, 2) = 351.7;
    frame.D1 = (cv::Mat_<double>(1, 5) << -0.1, 0.02, 0.0, 0.0, 0.0);
    const gc::AnalysisScale a = gc::analysis_scale(frame.image_size, 640);
    const gc::StereoCalibration analysed = gc::scaled_calibration(frame, a);
    EXPECT_EQ(analysed.image_size, cv::Size(640, 360));
    EXPECT_EQ(analysed.T, frame.T);  // millimetres unchanged
    EXPECT_EQ(cv::norm(analysed.D1, frame.D1), 0.0);
    for (const cv::Vec3d& X : {cv::Vec3d(0, 0, 1000), cv::Vec3d(-300, 150, 1800), cv::Vec3d(420, -260, 900)}) {
        for (const auto& [M, Ma] : {std::pair{frame.M1, analysed.M1}, std::pair{frame.M2, analysed.M2}}) {
            const cv::Point2d p = project(M, X), q = project(Ma, X);
            // Pixel centres at integers on both grids: (q + 0.5) / s = p + 0.5.
            EXPECT_NEAR((q.x + 0.5) / a.sx - 0.5, p.x, 1e-9);
            EXPECT_NEAR((q.y + 0.5) / a.sy - 0.5, p.y, 1e-9);
        }
    }
}

TEST(AnalysisScale, EstimatesAndMotionGoBackToTheFramesPixels)
{
    const gc::AnalysisScale a = gc::analysis_scale({1280, 960}, 640);
    gc::EyeEstimate e;
    e.mean = {99.5, 49.5, 0.3, 1.2};
    e.best = e.mean;
    e.contour = {{99.5f, 49.5f}, {0.0f, 0.0f}};
    e.fingertip = {199.5f, 9.5f};
    e.palm = {-0.5f, -0.5f};
    e.landmarks.assign(21, cv::Point2f(49.5f, 99.5f));
    e.bbox = cv::Rect(0, 0, 100, 50);
    e.pointing_deg = 33.0;
    gc::EyeEstimate none = e;
    none.contour.clear();
    gc::to_frame(e, a);
    EXPECT_DOUBLE_EQ(e.mean.x, 199.5);
    EXPECT_DOUBLE_EQ(e.mean.y, 99.5);
    EXPECT_DOUBLE_EQ(e.mean.rotation, 0.3);  // angles, scale and pointing are size-free
    EXPECT_DOUBLE_EQ(e.mean.scale, 1.2);
    EXPECT_DOUBLE_EQ(e.pointing_deg, 33.0);
    EXPECT_EQ(e.contour[1], cv::Point2f(0.5f, 0.5f));
    EXPECT_EQ(e.fingertip, cv::Point2f(399.5f, 19.5f));
    EXPECT_EQ(e.palm, cv::Point2f(-0.5f, -0.5f));  // the corner of the grid stays the corner
    EXPECT_EQ(e.landmarks[20], cv::Point2f(99.5f, 199.5f));
    EXPECT_EQ(e.bbox, cv::boundingRect(e.contour));  // the box of the contour, as the tracker's
    gc::to_frame(none, a);
    EXPECT_EQ(none.fingertip, cv::Point2f(199.5f, 9.5f)) << "an estimate without a contour is none: left alone";

    const gc::ImageMotion m = gc::to_analysed({8.0, -6.0, 0.1, 1.05}, a);
    EXPECT_DOUBLE_EQ(m.dx, 4.0);
    EXPECT_DOUBLE_EQ(m.dy, -3.0);
    EXPECT_DOUBLE_EQ(m.drotation, 0.1);
    EXPECT_DOUBLE_EQ(m.scale_factor, 1.05);
}

gc::sim::SceneConfig hd_scene(std::uint64_t seed)
{
    gc::sim::SceneConfig config;
    config.preset = gc::sim::Preset::Clean;
    config.motion = gc::sim::Motion::Translate;
    config.width = 1280;
    config.height = 960;
    config.seed = seed;
    return config;
}

// A small sample set, tracking at the frames' size or (`tracking_width`) scaled down.
gc::TrackerParams few_particles(int tracking_width = 0)
{
    gc::TrackerParams params;
    params.particles = 200;
    params.tracking_width = tracking_width;
    return params;
}

// The head's motion on a few frames, in the frame's pixels.
gc::ImageMotion head_motion(int f)
{
    return f >= 30 && f < 34 ? gc::ImageMotion{6.0, -4.0, 0.01, 1.0} : gc::ImageMotion{};
}

void expect_same_estimate(const gc::EyeEstimate& scaled, gc::EyeEstimate analysed, const gc::AnalysisScale& a, int f)
{
    gc::to_frame(analysed, a);
    EXPECT_EQ(scaled.state, analysed.state) << "frame " << f;
    EXPECT_EQ(scaled.contour, analysed.contour) << "frame " << f;
    EXPECT_EQ(scaled.fingertip, analysed.fingertip) << "frame " << f;
    EXPECT_EQ(scaled.landmarks, analysed.landmarks) << "frame " << f;
    EXPECT_EQ(scaled.bbox, analysed.bbox) << "frame " << f;
}

void expect_same_particles(std::span<const gc::Particle> scaled, std::span<const gc::Particle> analysed,
                           const gc::AnalysisScale& a, int f)
{
    std::vector<gc::Particle> mapped;
    gc::to_frame(analysed, a, mapped);
    ASSERT_EQ(scaled.size(), mapped.size()) << "frame " << f;
    for (std::size_t i = 0; i < mapped.size(); ++i) {
        ASSERT_EQ(scaled[i].state.x, mapped[i].state.x) << "frame " << f;
        ASSERT_EQ(scaled[i].state.y, mapped[i].state.y) << "frame " << f;
    }
}

// With tracking_width the pipeline gives exactly what it gives on frames scaled beforehand
// with the scaled calibration and motion, mapped back to the frame's pixels: stereo.
TEST(AnalysisScale, StereoTrackingWidthIsTheScaledFramesTrackedAndMappedBack)
{
    const gc::sim::Scene scene(hd_scene(2));
    const gc::AnalysisScale a = gc::analysis_scale({1280, 960}, 640);
    gc::PointingTracker scaled(few_particles(640), scene.calibration());
    gc::PointingTracker analysed(few_particles(), gc::scaled_calibration(scene.calibration(), a));
    cv::Mat left, right, small_left, small_right;
    gc::DownscaleBuffers buffers;
    int rays = 0;
    for (int f = 0; f < 45; ++f) {
        scene.render(f, gc::Eye::Left, {}, left);
        scene.render(f, gc::Eye::Right, {}, right);
        gc::downscale(left, a.analysed, buffers, small_left);
        gc::downscale(right, a.analysed, buffers, small_right);
        const gc::ImageMotion m = head_motion(f);
        const gc::FrameResult& r = scaled.process_stereo(left, right, -1, std::nullopt, m, m);
        const gc::FrameResult& s = analysed.process_stereo(small_left, small_right, -1, std::nullopt,
                                                           gc::to_analysed(m, a), gc::to_analysed(m, a));
        expect_same_estimate(r.left, s.left, a, f);
        expect_same_estimate(r.right, s.right, a, f);
        expect_same_particles(scaled.particles(gc::Eye::Left), analysed.particles(gc::Eye::Left), a, f);
        expect_same_particles(scaled.particles(gc::Eye::Right), analysed.particles(gc::Eye::Right), a, f);
        ASSERT_EQ(r.pointing.valid, s.pointing.valid) << "frame " << f;
        if (r.pointing.valid) {
            EXPECT_EQ(r.pointing.direction, s.pointing.direction) << "frame " << f;
        }
        rays += r.pointing.valid ? 1 : 0;
    }
    EXPECT_GT(rays, 10);
}

// The same in mono.
TEST(AnalysisScale, MonoTrackingWidthIsTheScaledFramesTrackedAndMappedBack)
{
    const gc::sim::Scene scene(hd_scene(3));
    const gc::AnalysisScale a = gc::analysis_scale({1280, 960}, 640);
    gc::PointingTracker scaled(few_particles(640)), analysed(few_particles());
    cv::Mat frame, small;
    gc::DownscaleBuffers buffers;
    int tracked = 0;
    for (int f = 0; f < 45; ++f) {
        scene.render(f, gc::Eye::Left, {}, frame);
        gc::downscale(frame, a.analysed, buffers, small);
        const gc::EyeEstimate& r = scaled.process_mono(frame, -1, head_motion(f)).left;
        const gc::EyeEstimate& s = analysed.process_mono(small, -1, gc::to_analysed(head_motion(f), a)).left;
        expect_same_estimate(r, s, a, f);
        expect_same_particles(scaled.particles(gc::Eye::Left), analysed.particles(gc::Eye::Left), a, f);
        EXPECT_TRUE(scaled.particles(gc::Eye::Right).empty());
        tracked += r.valid() ? 1 : 0;
    }
    EXPECT_GT(tracked, 10);
}

// A rendered 1280x960 stereo pair tracked at 640 wide: the fingertip, the box and the
// particles come back in the frame's pixels, and the 3D ray from the scaled calibration
// points where the hand does.
TEST(AnalysisScale, HdStereoPairTrackedAtHalfWidth)
{
    const gc::sim::Scene scene(hd_scene(2));
    gc::TrackerParams params;
    params.particles = 300;
    params.tracking_width = 640;
    gc::PointingTracker tracker(params, scene.calibration());
    cv::Mat left, right;
    gc::sim::EyeTruth lt, rt;
    std::vector<double> tip_px, ray_deg;
    int tracked = 0, visible = 0;
    for (int f = 0; f < 60; ++f) {
        scene.render(f, gc::Eye::Left, {}, left, &lt);
        scene.render(f, gc::Eye::Right, {}, right, &rt);
        const gc::FrameResult& r = tracker.process_stereo(left, right);
        if (!lt.visible) continue;
        ++visible;
        if (!r.left.valid()) continue;
        ++tracked;
        EXPECT_GT((r.left.bbox & lt.bbox).area(), lt.bbox.area() / 2) << "frame " << f;
        tip_px.push_back(cv::norm(cv::Point2d(r.left.fingertip) - lt.fingertip_px));
        for (const gc::Particle& p : tracker.particles(gc::Eye::Left))
            ASSERT_TRUE(cv::Rect(-640, -480, 2560, 1920).contains(cv::Point(p.state.x, p.state.y))) << "frame " << f;
        const gc::sim::HandTruth truth = scene.hand_truth(scene.hand_pose(f));
        if (r.pointing.valid && truth.points()) {
            const double c = r.pointing.direction_head.dot(truth.direction);
            ray_deg.push_back(std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / CV_PI);
        }
    }
    std::printf("tracked %d of %d, fingertip median %.1f px, %zu rays, median %.1f deg\n", tracked, visible,
                median(tip_px), ray_deg.size(), median(ray_deg));
    EXPECT_GE(tracked, visible * 8 / 10);
    // The hand is about twice as many frame pixels as at 640x480; a few analysed pixels.
    EXPECT_LT(median(tip_px), 16.0);
    ASSERT_GE(ray_deg.size(), 20u);
    EXPECT_LT(median(ray_deg), 6.0);
}

}  // namespace
