// C_t against the synthetic scene: a static hand rendered from two head poses moves in the
// image by what camera_motion predicts.
#include "sim/scene.hpp"
#include "stereo/camera_motion.hpp"
#include "stereo/head_geometry.hpp"

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace gc {
namespace {

constexpr double kPi = std::numbers::pi;

struct Step {
    const char* name;
    HeadPose before;
    HeadPose after;
};

HeadPose pose(double pan, double tilt, double vl = 0.0, double vr = 0.0, double zoom = 1.0)
{
    return {pan, tilt, vl, vr, zoom};
}

sim::SceneConfig scene_config()
{
    sim::SceneConfig c;
    c.preset = sim::Preset::Clean;
    c.motion = sim::Motion::Static;
    c.noise_sigma = 0.0;
    return c;
}

// The hand's palm and fingertip in one eye at one head pose.
sim::EyeTruth truth_at(const sim::Scene& scene, const sim::HandPose& hand, Eye eye, const HeadPose& head)
{
    cv::Mat bgr;
    sim::EyeTruth truth;
    scene.render_pose(hand, 0, eye, head, bgr, &truth);
    return truth;
}

double image_angle(const sim::EyeTruth& t)  // palm -> fingertip, image axes (y down)
{
    const cv::Point2d d = t.fingertip_px - t.palm_px;
    return std::atan2(d.y, d.x);
}

double wrap(double a) { return std::remainder(a, 2.0 * kPi); }

TEST(CameraMotion, PredictsTheSceneForStepsOfAFewDegreesAndOfTheZoom)
{
    const sim::Scene scene(scene_config());
    const StereoCalibration cal = scene.calibration();
    sim::HandPose hand;
    hand.palm_mm = {80.0, -40.0, 1000.0};
    hand.roll_deg = 30.0;

    const Step steps[] = {
        {"pan +3", pose(0, 0), pose(3, 0)},
        {"pan -4 from a turned head", pose(5, 2), pose(1, 2)},
        {"tilt +3", pose(0, 0), pose(0, 3)},
        {"tilt -4 while panned", pose(4, 1), pose(4, -3)},
        {"vergence converge", pose(0, 0), pose(0, 0, 3, -3)},
        {"vergence of one eye", pose(2, 1, 1, -1), pose(2, 1, 4, -1)},
        {"pan, tilt and vergence", pose(-2, 1, 1, -1), pose(1, -2, 3, -4)},
        {"zoom 1 -> 2", pose(0, 0), pose(0, 0, 0, 0, 2)},
        {"zoom 2 -> 1.5 while panning", pose(1, 0, 0, 0, 2), pose(2, 1, 0, 0, 1.5)},
    };
    double worst_px = 0.0, worst_rad = 0.0;
    for (const Step& s : steps) {
        for (Eye eye : {Eye::Left, Eye::Right}) {
            SCOPED_TRACE(std::string(s.name) + (eye == Eye::Left ? ", left eye" : ", right eye"));
            const sim::EyeTruth a = truth_at(scene, hand, eye, s.before);
            const sim::EyeTruth b = truth_at(scene, hand, eye, s.after);
            ASSERT_TRUE(a.visible && b.visible);
            // The default nominal depth, 1000 mm: what the tracker uses before the 3D is known.
            const ImageMotion m = camera_motion(cal, eye, s.before, s.after, a.palm_px);
            EXPECT_NEAR(a.palm_px.x + m.dx, b.palm_px.x, 0.5);
            EXPECT_NEAR(a.palm_px.y + m.dy, b.palm_px.y, 0.5);
            worst_px =
                std::max(worst_px, std::hypot(a.palm_px.x + m.dx - b.palm_px.x, a.palm_px.y + m.dy - b.palm_px.y));
            worst_rad = std::max(worst_rad, std::abs(wrap(image_angle(b) - image_angle(a)) - m.drotation));
            // The palm -> fingertip direction turns by about the predicted rotation (predicted
            // at the palm; the rotation varies a little over the hand's extent).
            EXPECT_NEAR(wrap(image_angle(b) - image_angle(a)), m.drotation, 0.01);
            // ...and its length changes by about the predicted scale (rotations change it a
            // little through perspective).
            const double length_ratio = cv::norm(b.fingertip_px - b.palm_px) / cv::norm(a.fingertip_px - a.palm_px);
            EXPECT_NEAR(m.scale_factor, length_ratio, 0.01);
            // A zoom scales the image by the ratio of the magnifications (pan adds little).
            EXPECT_NEAR(m.scale_factor, s.after.zoom / s.before.zoom, 0.03);
        }
    }
    std::printf("largest position error %.3f px, rotation error %.4f rad\n", worst_px, worst_rad);
}

TEST(CameraMotion, UsesTheDepthWhenTheEyeMovesOffItsOpticalCentre)
{
    // Panning about the neck translates each eye: a near hand moves differently from a far one.
    const sim::Scene scene(scene_config());
    const StereoCalibration cal = scene.calibration();
    sim::HandPose hand;
    hand.palm_mm = {0.0, 0.0, 300.0};
    const HeadPose before = pose(0, 0), after = pose(10, 0);
    const sim::EyeTruth a = truth_at(scene, hand, Eye::Left, before);
    const sim::EyeTruth b = truth_at(scene, hand, Eye::Left, after);
    const cv::Rect2d frame(0, 0, scene.config().width, scene.config().height);
    ASSERT_TRUE(frame.contains(a.palm_px) && frame.contains(b.palm_px));  // the palm; the finger may leave
    const double true_depth = camera_to_head(cal.head, before, Eye::Left).inverse().apply(hand.palm_mm)[2];

    const ImageMotion near = camera_motion(cal, Eye::Left, before, after, a.palm_px, true_depth);
    const ImageMotion nominal = camera_motion(cal, Eye::Left, before, after, a.palm_px);
    EXPECT_NEAR(a.palm_px.x + near.dx, b.palm_px.x, 0.5);
    EXPECT_NEAR(a.palm_px.y + near.dy, b.palm_px.y, 0.5);
    EXPECT_GT(std::abs(nominal.dx - near.dx), 1.0);  // the depth matters here, a little
}

TEST(CameraMotion, VergenceAboutTheOpticalCentreDoesNotDependOnDepth)
{
    const StereoCalibration cal = default_calibration({640, 480});  // nodal offset 0
    const cv::Point2d p(420.0, 130.0);
    const ImageMotion a = camera_motion(cal, Eye::Right, pose(0, 0), pose(0, 0, 0, -5), p, 300.0);
    const ImageMotion b = camera_motion(cal, Eye::Right, pose(0, 0), pose(0, 0, 0, -5), p, 5000.0);
    EXPECT_NEAR(a.dx, b.dx, 1e-9);
    EXPECT_NEAR(a.dy, b.dy, 1e-9);
    EXPECT_GT(a.dx, 20.0);  // the eye turns left, so the scene moves to the right in its image
}

TEST(CameraMotion, NoHeadMotionIsExactlyNoImageMotion)
{
    // Composing and inverting a pose leaves a residue of ~1e-14 px at many poses; a tracker
    // told that the view moved on every frame of a still head starts its background over
    // on each one.
    StereoCalibration cal = default_calibration({640, 480});
    cal.D1 = (cv::Mat_<double>(1, 5) << -0.2, 0.05, 0.001, -0.001, 0.0);
    for (double pan = -90.0; pan <= 90.0; pan += 7.5)
        for (double tilt = -60.0; tilt <= 60.0; tilt += 7.5) {
            const HeadPose p = pose(pan, tilt, 2, -2);
            for (const Eye eye : {Eye::Left, Eye::Right}) {
                const ImageMotion m = camera_motion(cal, eye, p, p, {100.0, 400.0}, 800.0);
                EXPECT_EQ(m.dx, 0.0) << pan << " " << tilt;
                EXPECT_EQ(m.dy, 0.0) << pan << " " << tilt;
                EXPECT_EQ(m.drotation, 0.0);
                EXPECT_EQ(m.scale_factor, 1.0);
            }
        }
}

TEST(CameraMotion, ARoundingResidueIsNoMotion)
{
    EXPECT_FALSE(ImageMotion{}.moves());
    EXPECT_FALSE((ImageMotion{0.0, -2.84217e-14, 0.0, 1.0 - 8.88178e-16}.moves()));
    EXPECT_TRUE((ImageMotion{0.01, 0.0, 0.0, 1.0}.moves()));
    EXPECT_TRUE((ImageMotion{0.0, -0.01, 0.0, 1.0}.moves()));
    EXPECT_TRUE((ImageMotion{0.0, 0.0, 1e-4, 1.0}.moves()));
    EXPECT_TRUE((ImageMotion{0.0, 0.0, 0.0, 1.0001}.moves()));
}

TEST(CameraMotion, ThereAndBackAgainWithDistortionAndOffsetCentres)
{
    StereoCalibration cal = default_calibration({640, 480});
    cal.D1 = (cv::Mat_<double>(1, 5) << -0.25, 0.08, 0.0005, -0.0008, 0.0);
    cal.head.nodal_offset_mm = {0.0, 0.0, 30.0};
    cal.head.tilt_centre_mm = {0.0, -40.0, -60.0};
    const HeadPose a = pose(1, 2, 3, -2), b = pose(-3, 5, 6, -1);
    const cv::Point2d p(180.0, 330.0);
    const double depth = 900.0;
    const ImageMotion go = camera_motion(cal, Eye::Left, a, b, p, depth);
    EXPECT_GT(std::hypot(go.dx, go.dy), 20.0);
    // The point's depth in the moved camera, so that the way back starts from the same 3D point.
    const RigidTransform moved =
        camera_to_head(cal.head, b, Eye::Left).inverse() * camera_to_head(cal.head, a, Eye::Left);
    std::vector<cv::Point2d> undistorted;
    cv::undistortPoints(std::vector<cv::Point2d>{p}, undistorted, cv::Mat(cal.M1), cal.D1);
    const cv::Vec3d x = moved.apply(cv::Vec3d(undistorted[0].x, undistorted[0].y, 1.0) * depth);
    const ImageMotion back = camera_motion(cal, Eye::Left, b, a, p + cv::Point2d(go.dx, go.dy), x[2]);
    EXPECT_NEAR(go.dx + back.dx, 0.0, 1e-3);
    EXPECT_NEAR(go.dy + back.dy, 0.0, 1e-3);
    EXPECT_NEAR(go.drotation + back.drotation, 0.0, 1e-3);
    EXPECT_NEAR(go.scale_factor * back.scale_factor, 1.0, 1e-3);
}

TEST(CameraMotion, RejectsBadInputWithAMessage)
{
    const StereoCalibration cal = default_calibration({640, 480});
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(camera_motion(cal, Eye::Left, pose(nan, 0), pose(0, 0), {1, 1}), std::invalid_argument);
    EXPECT_THROW(camera_motion(cal, Eye::Left, pose(0, 0), pose(0, 0), {nan, 1}), std::invalid_argument);
    EXPECT_THROW(camera_motion(cal, Eye::Left, pose(0, 0), pose(0, 0), {1, 1}, 0.0), std::invalid_argument);
    EXPECT_THROW(camera_motion(cal, Eye::Left, pose(0, 0), pose(0, 0), {1, 1}, -5.0), std::invalid_argument);
    try {
        camera_motion(cal, Eye::Left, pose(0, 0), pose(0, 0), {1, 1}, 0.0);
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("depth"), std::string::npos);
    }
    // Turned half round: the point is behind the camera.
    EXPECT_THROW(camera_motion(cal, Eye::Left, pose(0, 0), pose(170, 0), {320, 240}), std::domain_error);
}

}  // namespace
}  // namespace gc
