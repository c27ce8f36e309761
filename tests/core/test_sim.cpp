#include "sim/scene.hpp"
#include "skin/skin_model.hpp"
#include "stereo/head_geometry.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <numbers>
#include <thread>

namespace {

using gc::Eye;
using gc::HeadPose;
using namespace gc::sim;

SceneConfig config(Preset preset, Motion motion, std::uint64_t seed)
{
    SceneConfig c;
    c.preset = preset;
    c.motion = motion;
    c.seed = seed;
    return c;
}

cv::Point2d project(const cv::Matx33d& K, const cv::Vec3d& X)
{
    const cv::Vec3d p = K * X;
    return {p[0] / p[2], p[1] / p[2]};
}

double distance(cv::Point2d a, cv::Point2d b) { return std::hypot(a.x - b.x, a.y - b.y); }

// The skin-coloured pixels that face-pass adds to the light preset of the same seed (same
// room, noise and hand): the person. `a` gets face-pass's frame and `t` its truth.
cv::Mat1b added_skin(const Scene& face, const Scene& light, int frame, cv::Mat& a, EyeTruth& t)
{
    cv::Mat b, diff;
    face.render(frame, Eye::Left, {}, a, &t);
    light.render(frame, Eye::Left, {}, b);
    cv::absdiff(a, b, diff);
    cv::Mat1b person;
    cv::cvtColor(diff, person, cv::COLOR_BGR2GRAY);
    cv::threshold(person, person, 0, 255, cv::THRESH_BINARY);
    cv::bitwise_and(person, gc::SkinModel::fit(a, t.mask).segment(a), person);
    return person;
}

// The farthest mask pixel from `from` along `dir` (image coordinates).
cv::Point2d extreme_point(const cv::Mat1b& mask, cv::Point2d from, cv::Point2d dir)
{
    double best = -1e9;
    cv::Point2d arg;
    for (int y = 0; y < mask.rows; ++y)
        for (int x = 0; x < mask.cols; ++x)
            if (mask(y, x)) {
                const double s = (x - from.x) * dir.x + (y - from.y) * dir.y;
                if (s > best) best = s, arg = {double(x), double(y)};
            }
    return arg;
}

TEST(SimNames, RoundTrip)
{
    for (Preset p : {Preset::Clean, Preset::Light, Preset::Heavy, Preset::FacePass, Preset::Varied})
        EXPECT_EQ(preset_from_string(to_string(p)), p);
    for (Variety v : {Variety::None, Variety::Wide}) EXPECT_EQ(variety_from_string(to_string(v)), v);
    EXPECT_FALSE(variety_from_string("some").has_value());
    for (Motion m : {Motion::Static, Motion::Translate, Motion::Rotate, Motion::Scale, Motion::Yaw, Motion::Mixed,
                     Motion::LeaveReturn})
        EXPECT_EQ(motion_from_string(to_string(m)), m);
    EXPECT_FALSE(preset_from_string("cluttered").has_value());
    EXPECT_FALSE(motion_from_string("").has_value());
}

// One spelling everywhere: the element's enum nicks (face-pass, leave-return) are the names the
// tools print; what a user types with '_' is read as the same thing.
TEST(SimNames, SpeltLikeTheElementsNicksAndReadEitherWay)
{
    EXPECT_EQ(to_string(Preset::FacePass), "face-pass");
    EXPECT_EQ(to_string(Motion::LeaveReturn), "leave-return");
    EXPECT_EQ(preset_from_string("face_pass"), Preset::FacePass);
    EXPECT_EQ(motion_from_string("leave_return"), Motion::LeaveReturn);
}

TEST(SimScene, RejectsBadConfiguration)
{
    auto bad = [](auto edit) {
        SceneConfig c;
        edit(c);
        return c;
    };
    EXPECT_THROW(Scene(bad([](SceneConfig& c) { c.width = 0; })), std::invalid_argument);
    EXPECT_THROW(Scene(bad([](SceneConfig& c) { c.fps = 0.0; })), std::invalid_argument);
    EXPECT_THROW(Scene(bad([](SceneConfig& c) { c.focal_px = -5.0; })), std::invalid_argument);
    EXPECT_THROW(Scene(bad([](SceneConfig& c) { c.baseline_mm = NAN; })), std::invalid_argument);
    EXPECT_THROW(Scene(bad([](SceneConfig& c) { c.hand_distance_mm = 50.0; })), std::invalid_argument);
    EXPECT_THROW(Scene(bad([](SceneConfig& c) { c.noise_sigma = -1.0; })), std::invalid_argument);
    EXPECT_THROW(Scene(bad([](SceneConfig& c) { c.preset = static_cast<Preset>(42); })), std::invalid_argument);
    EXPECT_THROW(Scene(bad([](SceneConfig& c) { c.variety = static_cast<Variety>(3); })), std::invalid_argument);
}

TEST(SimScene, RejectsBadRenderInput)
{
    const Scene scene(config(Preset::Clean, Motion::Mixed, 1));
    cv::Mat img;
    EXPECT_THROW(scene.render(-1, Eye::Left, {}, img), std::invalid_argument);
    EXPECT_THROW(scene.hand_pose(-3), std::invalid_argument);
    EXPECT_THROW(scene.render(0, static_cast<Eye>(7), {}, img), std::invalid_argument);
    EXPECT_THROW(scene.render(0, Eye::Left, HeadPose{NAN, 0, 0, 0}, img), std::invalid_argument);
    EXPECT_THROW(scene.render(0, Eye::Left, HeadPose{80, 0, 0, 0}, img), std::invalid_argument);
    HandPose pose;
    pose.palm_mm[0] = INFINITY;
    EXPECT_THROW(scene.render_pose(pose, 0, Eye::Left, {}, img), std::invalid_argument);
    pose = HandPose{};
    pose.forearm_mm = 0.0;
    EXPECT_THROW(scene.hand_truth(pose), std::invalid_argument);
}

TEST(SimScene, MovedFromSceneReportsMisuse)
{
    Scene a(config(Preset::Clean, Motion::Static, 1));
    const Scene b(std::move(a));
    cv::Mat img;
    EXPECT_NO_THROW(b.render(0, Eye::Left, {}, img));
    EXPECT_THROW(a.render(0, Eye::Left, {}, img), std::logic_error);  // NOLINT(bugprone-use-after-move)
}

TEST(SimScene, EyesRenderConcurrentlyFromOneScene)
{
    const Scene scene(config(Preset::FacePass, Motion::Mixed, 2));
    cv::Mat seq[2], par[2];
    EyeTruth seq_t[2], par_t[2];
    for (int e = 0; e < 2; ++e) scene.render(90, Eye(e), {}, seq[e], &seq_t[e]);
    std::thread left([&] {
        for (int i = 0; i < 5; ++i) scene.render(90, Eye::Left, {}, par[0], &par_t[0]);
    });
    std::thread right([&] {
        for (int i = 0; i < 5; ++i) scene.render(90, Eye::Right, {}, par[1], &par_t[1]);
    });
    left.join();
    right.join();
    for (int e = 0; e < 2; ++e) {
        EXPECT_EQ(cv::norm(seq[e], par[e], cv::NORM_L1), 0.0);
        EXPECT_EQ(cv::norm(seq_t[e].mask, par_t[e].mask, cv::NORM_L1), 0.0);
    }
}

TEST(SimScene, CalibrationIsTheExactRig)
{
    SceneConfig c;
    c.baseline_mm = 150.0;
    const gc::StereoCalibration cal = Scene(c).calibration();
    const double f = 0.5 * c.width / std::tan(std::numbers::pi / 6.0);
    EXPECT_EQ(cal.image_size, cv::Size(c.width, c.height));
    EXPECT_NEAR(cal.M1(0, 0), f, 1e-9);
    EXPECT_NEAR(cal.M1(1, 1), f, 1e-9);
    EXPECT_NEAR(cal.M1(0, 2), 0.5 * (c.width - 1), 1e-9);
    EXPECT_NEAR(cal.M1(1, 2), 0.5 * (c.height - 1), 1e-9);
    EXPECT_EQ(cv::norm(cal.M1 - cal.M2), 0.0);
    EXPECT_EQ(cv::countNonZero(cal.D1), 0);
    EXPECT_EQ(cv::countNonZero(cal.D2), 0);
    EXPECT_NEAR(cv::norm(cal.R - cv::Matx33d::eye()), 0.0, 1e-12);
    EXPECT_NEAR(cv::norm(cal.T - cv::Vec3d(-150.0, 0.0, 0.0)), 0.0, 1e-9);
    ASSERT_TRUE(cal.has_head_geometry);
    EXPECT_NEAR(cal.head.baseline_mm(), 150.0, 1e-9);
    EXPECT_NEAR(cal.head.left_eye_mm[0], -75.0, 1e-9);
}

// The truth 3D points, taken through calibration() and the shared head kinematics, land on
// the truth pixels; the mask agrees with them.
TEST(SimScene, TruthProjectsConsistentlyInBothEyes)
{
    for (Motion motion : {Motion::Mixed, Motion::Yaw}) {
        const Scene scene(config(Preset::Light, motion, 3));
        const gc::StereoCalibration cal = scene.calibration();
        const HeadPose heads[] = {{}, {4.0, -3.0, 2.5, -1.5}};
        for (const HeadPose& head : heads)
            for (int frame : {0, 45, 120, 200}) {
                const HandTruth t3 = scene.hand_truth(scene.hand_pose(frame));
                const gc::RigidTransform head_to_left = gc::camera_to_head(cal.head, head, Eye::Left).inverse();
                const gc::RigidTransform head_to_right = gc::camera_to_head(cal.head, head, Eye::Right).inverse();
                for (Eye eye : {Eye::Left, Eye::Right}) {
                    cv::Mat img;
                    EyeTruth truth;
                    scene.render(frame, eye, head, img, &truth);
                    ASSERT_TRUE(truth.visible) << "frame " << frame;
                    cv::Point2d palm, tip;
                    if (eye == Eye::Left) {
                        palm = project(cal.M1, head_to_left.apply(t3.palm_mm));
                        tip = project(cal.M1, head_to_left.apply(t3.fingertip_mm));
                    } else if (head.pan_deg == 0.0 && head.verge_left_deg == 0.0) {
                        // At the zero pose the right eye follows from R, T alone.
                        const cv::Vec3d pl = head_to_left.apply(t3.palm_mm), tl = head_to_left.apply(t3.fingertip_mm);
                        palm = project(cal.M2, cal.R * pl + cal.T);
                        tip = project(cal.M2, cal.R * tl + cal.T);
                    } else {
                        palm = project(cal.M2, head_to_right.apply(t3.palm_mm));
                        tip = project(cal.M2, head_to_right.apply(t3.fingertip_mm));
                    }
                    EXPECT_LT(distance(palm, truth.palm_px), 0.5);
                    EXPECT_LT(distance(tip, truth.fingertip_px), 0.5);

                    // The palm centre is on the hand; the mask's extreme point along the
                    // pointing direction is the fingertip.
                    EXPECT_EQ(truth.mask(cv::Point(cvRound(palm.x), cvRound(palm.y))), 255);
                    const double a = truth.pointing_deg * std::numbers::pi / 180.0;
                    const cv::Point2d dir(std::cos(a), -std::sin(a));
                    EXPECT_LT(distance(extreme_point(truth.mask, palm, dir), tip), 2.5)
                        << "frame " << frame << " eye " << int(eye);
                    EXPECT_EQ(truth.bbox, cv::boundingRect(truth.mask));
                }
            }
    }
}

TEST(SimScene, PointingAngleFollowsRoll)
{
    const Scene scene(config(Preset::Clean, Motion::Static, 2));
    for (double roll : {0.0, 45.0, 90.0, 150.0}) {
        HandPose pose;
        pose.palm_mm = {-60.0, 0.0, 900.0};  // straight ahead of the left eye
        pose.roll_deg = roll;
        cv::Mat img;
        EyeTruth truth;
        scene.render_pose(pose, 0, Eye::Left, {}, img, &truth);
        EXPECT_NEAR(truth.pointing_deg, roll, 1e-6);
        const HandTruth t3 = scene.hand_truth(pose);
        EXPECT_NEAR(cv::norm(t3.direction), 1.0, 1e-12);
        EXPECT_NEAR(cv::norm(t3.palm_mm - pose.palm_mm), 0.0, 1e-9);
        EXPECT_NEAR(cv::norm(t3.elbow_mm - t3.palm_mm), pose.forearm_mm, 1e-9);
        EXPECT_GT(cv::norm(t3.fingertip_mm - t3.palm_mm), 100.0);
    }
}

TEST(SimScene, AnAimedHandPointsAtItsAimAndStaysInView)
{
    // Across the room, to either side and up or down: the finger points at the aim from the
    // first still frame on, and both eyes see the hand.
    for (const cv::Vec3d& aim : {cv::Vec3d(800, -300, 3500), cv::Vec3d(-900, 200, 2500), cv::Vec3d(0, -500, 2000)}) {
        SceneConfig c = config(Preset::Light, Motion::Static, 5);
        c.aim_mm = aim;
        const Scene scene(c);
        const int still = int(2.0 * c.fps);  // after the wave
        const HandTruth t = scene.hand_truth(scene.hand_pose(still));
        const cv::Vec3d to_aim = (aim - t.palm_mm) * (1.0 / cv::norm(aim - t.palm_mm));
        EXPECT_GT(t.direction.dot(to_aim), std::cos(0.5 * std::numbers::pi / 180.0)) << aim;
        cv::Mat img;
        EyeTruth truth;
        for (Eye eye : {Eye::Left, Eye::Right}) {
            scene.render(still, eye, {}, img, &truth);
            EXPECT_TRUE(truth.visible) << aim;
        }
    }
}

// Two scenes of config `c` render the same frames and truth; one of `other_seed` differs.
void expect_seeded(SceneConfig c, std::uint64_t other_seed)
{
    const Scene a(c), b(c);
    c.seed = other_seed;
    const Scene other(c);
    cv::Mat ia, ib, ic;
    EyeTruth ta, tb;
    for (int frame : {0, 60, 77}) {
        for (Eye eye : {Eye::Left, Eye::Right}) {
            a.render(frame, eye, {}, ia, &ta);
            b.render(frame, eye, {}, ib, &tb);
            other.render(frame, eye, {}, ic);
            EXPECT_EQ(cv::norm(ia, ib, cv::NORM_L1), 0.0);
            EXPECT_EQ(cv::norm(ta.mask, tb.mask, cv::NORM_L1), 0.0);
            EXPECT_EQ(cv::norm(ta.face, tb.face, cv::NORM_L1), 0.0);
            EXPECT_GT(cv::norm(ia, ic, cv::NORM_L1) / double(ia.total()), 10.0);
        }
    }
    EXPECT_GT(cv::norm(a.hand_pose(150).palm_mm - other.hand_pose(150).palm_mm), 10.0);
}

TEST(SimScene, DeterministicPerSeedAndDifferentAcrossSeeds)
{
    expect_seeded(config(Preset::Heavy, Motion::Mixed, 7), 8);
}

TEST(SimScene, NoiseIsSeededPerFrameAndEye)
{
    SceneConfig c = config(Preset::Clean, Motion::Static, 4);
    c.noise_sigma = 3.0;
    const Scene noisy(c);
    c.noise_sigma = 0.0;
    const Scene clean(c);
    cv::Mat n1, n2, q1;
    // Static after the wave: frames 60 and 61 show the same scene, with different noise.
    noisy.render(60, Eye::Left, {}, n1);
    noisy.render(61, Eye::Left, {}, n2);
    clean.render(60, Eye::Left, {}, q1);
    cv::Mat diff;
    cv::absdiff(n1, q1, diff);
    const double sigma = cv::norm(n1, q1, cv::NORM_L2) / std::sqrt(double(n1.total() * 3));
    EXPECT_NEAR(sigma, 3.0, 0.5);
    EXPECT_GT(cv::norm(n1, n2, cv::NORM_L1), 0.0);
}

TEST(SimScene, RendersIntoTheCallersBuffer)
{
    const Scene scene(config(Preset::Light, Motion::Translate, 1));
    cv::Mat img;
    scene.render(0, Eye::Left, {}, img);
    const uchar* data = img.data;
    scene.render(1, Eye::Right, {}, img);
    EXPECT_EQ(img.data, data);
    EXPECT_EQ(img.type(), CV_8UC3);
    EXPECT_EQ(img.size(), cv::Size(640, 480));
}

// Clutter presets land near the thesis's skin-pixel fractions, measured as it did.
TEST(SimScene, PresetSkinFractionsMatchTheThesis)
{
    for (std::uint64_t seed : {1, 2, 3}) {
        const double clean = Scene(config(Preset::Clean, Motion::Mixed, seed)).measured_skin_fraction();
        const double light = Scene(config(Preset::Light, Motion::Mixed, seed)).measured_skin_fraction();
        const double heavy = Scene(config(Preset::Heavy, Motion::Mixed, seed)).measured_skin_fraction();
        const double face = Scene(config(Preset::FacePass, Motion::Mixed, seed)).measured_skin_fraction();
        EXPECT_LT(clean, 0.003) << "seed " << seed;
        EXPECT_GT(light, 0.025) << "seed " << seed;
        EXPECT_LT(light, 0.05) << "seed " << seed;
        EXPECT_GT(heavy, 0.07) << "seed " << seed;
        EXPECT_LT(heavy, 0.12) << "seed " << seed;
        EXPECT_GT(face, 0.03) << "seed " << seed;
        EXPECT_LT(face, 0.07) << "seed " << seed;
    }
}

TEST(SimScene, FacePassPutsAFaceOnTheHandsPath)
{
    // Some frame of the sequence has the hand over skin-coloured background that the light
    // preset of the same seed does not have: the face.
    const Scene face(config(Preset::FacePass, Motion::Mixed, 5));
    const Scene light(config(Preset::Light, Motion::Mixed, 5));
    double most = 0.0;
    for (int frame = 30; frame < 300; frame += 15)
        most = std::max(most, face.measured_skin_fraction(frame) - light.measured_skin_fraction(frame));
    EXPECT_GT(most, 0.003);
}

// face-pass: the hand waves (and is acquired) beside the face, not on it, and crosses it
// later. The face's pixels are those that differ from the light preset of the same seed
// (same room, noise and hand) and are skin-coloured for a model fitted to the hand.
TEST(SimScene, FacePassStartsBesideTheFaceAndCrossesIt)
{
    for (std::uint64_t seed : {1, 2, 3}) {
        const Scene face(config(Preset::FacePass, Motion::Mixed, seed));
        const Scene light(config(Preset::Light, Motion::Mixed, seed));
        cv::Mat a;
        EyeTruth t;
        auto face_skin = [&](int frame) { return added_skin(face, light, frame, a, t); };
        const cv::Mat1b face_at_rest = face_skin(0);
        const int face_area = cv::countNonZero(face_at_rest);
        ASSERT_GT(face_area, 500) << "seed " << seed;
        for (int frame = 0; frame <= 36; frame += 4) {  // the wave
            face_skin(frame);
            cv::Mat1b near;
            cv::dilate(t.mask, near, cv::getStructuringElement(cv::MORPH_ELLIPSE, {7, 7}));
            cv::bitwise_and(near, face_at_rest, near);
            EXPECT_LT(cv::countNonZero(near), 0.02 * face_area) << "seed " << seed << " frame " << frame;
        }
        double most = 0.0;  // the crossing: the hand covers much of the face
        for (int frame = 60; frame < 200; frame += 5) {
            face.render(frame, Eye::Left, {}, a, &t);
            cv::Mat1b over;
            cv::bitwise_and(t.mask, face_at_rest, over);
            most = std::max(most, double(cv::countNonZero(over)) / face_area);
        }
        EXPECT_GT(most, 0.3) << "seed " << seed;
    }
}

// The truth carries the face's skin (face, ears, neck, nose) for face-pass, and nothing for
// the other presets: it must match the skin-coloured pixels the person adds to the room.
TEST(SimScene, FacePassTruthHoldsTheFacesSkin)
{
    for (std::uint64_t seed : {1, 4}) {
        const Scene face(config(Preset::FacePass, Motion::Mixed, seed));
        const Scene light(config(Preset::Light, Motion::Mixed, seed));
        cv::Mat a, b;
        EyeTruth t, u;
        light.render(0, Eye::Left, {}, b, &u);
        EXPECT_TRUE(u.face.empty());
        cv::Mat1b added = added_skin(face, light, 0, a, t);
        ASSERT_EQ(t.face.size(), a.size());
        cv::Mat1b hand;  // the hand and its soft edge are drawn over both scenes alike
        cv::dilate(t.mask, hand, cv::getStructuringElement(cv::MORPH_ELLIPSE, {7, 7}));
        cv::Mat1b truth_face = t.face.clone();
        added.setTo(0, hand);
        truth_face.setTo(0, hand);
        const double inter = cv::countNonZero(added & truth_face);
        const double uni = cv::countNonZero(added | truth_face);
        ASSERT_GT(uni, 500.0) << "seed " << seed;
        EXPECT_GT(inter / uni, 0.9) << "seed " << seed;
    }
}

TEST(SimScene, HandIsVisibleAndOfPlausibleSize)
{
    for (Motion motion : {Motion::Translate, Motion::Scale, Motion::Mixed})
        for (std::uint64_t seed : {1, 2, 3}) {
            const Scene scene(config(Preset::Light, motion, seed));
            int visible = 0, total = 0;
            for (int frame = 0; frame < 900; frame += 30)
                for (Eye eye : {Eye::Left, Eye::Right}) {
                    cv::Mat img;
                    EyeTruth t;
                    scene.render(frame, eye, {}, img, &t);
                    ++total;
                    if (!t.visible) continue;
                    ++visible;
                    const int area = cv::countNonZero(t.mask);
                    EXPECT_GT(area, 1500);
                    EXPECT_LT(area, 25000);
                    EXPECT_GT(std::max(t.bbox.width, t.bbox.height), 60);
                    EXPECT_LT(std::max(t.bbox.width, t.bbox.height), 260);
                }
            EXPECT_GE(visible, total * 9 / 10) << to_string(motion) << " seed " << seed;
        }
}

TEST(SimScene, HandIsSkinColouredAndSleeveIsNot)
{
    for (std::uint64_t seed : {1, 2, 3, 4, 5, 6}) {
        SceneConfig c = config(Preset::Clean, Motion::Static, seed);
        c.noise_sigma = 0.0;
        const Scene scene(c);
        cv::Mat img;
        EyeTruth t;
        scene.render(60, Eye::Left, {}, img, &t);
        const cv::Scalar m = cv::mean(img, t.mask);
        const double s = m[0] + m[1] + m[2];
        EXPECT_GT(m[2], m[1]);
        EXPECT_GT(m[1], m[0]);
        EXPECT_GT(m[2] / s, 0.38);
        EXPECT_LT(m[2] / s, 0.52);
        EXPECT_GT(m[1] / s, 0.28);
        EXPECT_LT(m[1] / s, 0.35);

        // Half way along the forearm, the sleeve is not what a skin model of the hand accepts.
        const HandTruth t3 = scene.hand_truth(scene.hand_pose(60));
        const gc::StereoCalibration cal = scene.calibration();
        const gc::RigidTransform to_left = gc::camera_to_head(cal.head, {}, Eye::Left).inverse();
        const cv::Point2d mid = project(cal.M1, to_left.apply(0.5 * (t3.palm_mm + t3.elbow_mm)));
        const cv::Rect patch =
            cv::Rect(cvRound(mid.x) - 2, cvRound(mid.y) - 2, 5, 5) & cv::Rect(0, 0, img.cols, img.rows);
        ASSERT_FALSE(patch.empty()) << "seed " << seed;
        const gc::SkinModel skin = gc::SkinModel::fit(img, t.mask);
        EXPECT_EQ(cv::countNonZero(skin.segment(img)(patch)), 0) << "seed " << seed;
    }
}

TEST(SimMotion, SpeedsArePlausibleAndTheWaveComesFirst)
{
    for (Motion motion : {Motion::Static, Motion::Translate, Motion::Rotate, Motion::Scale, Motion::Yaw, Motion::Mixed,
                          Motion::LeaveReturn})
        for (std::uint64_t seed : {1, 2, 3}) {
            const Scene scene(config(Preset::Clean, motion, seed));
            const double dt = 1.0 / scene.config().fps;
            double peak = 0.0, wave = 0.0;
            HandTruth prev = scene.hand_truth(scene.hand_pose(0));
            for (int frame = 1; frame < 900; ++frame) {
                const HandTruth cur = scene.hand_truth(scene.hand_pose(frame));
                const double v =
                    std::max(cv::norm(cur.fingertip_mm - prev.fingertip_mm), cv::norm(cur.palm_mm - prev.palm_mm)) / dt;
                if (frame <= 36)
                    wave = std::max(wave, v);  // the wave: 1.2 s
                else if (motion != Motion::LeaveReturn || frame > 270)
                    peak = std::max(peak, v);
                prev = cur;
            }
            EXPECT_GT(wave, 100.0) << to_string(motion) << " seed " << seed;
            EXPECT_LT(wave, 550.0) << to_string(motion) << " seed " << seed;
            EXPECT_LT(peak, 550.0) << to_string(motion) << " seed " << seed;
            if (motion == Motion::Static)
                EXPECT_EQ(peak, 0.0);
            else
                EXPECT_GT(peak, 20.0) << to_string(motion) << " seed " << seed;
        }
}

TEST(SimMotion, EachMotionMovesItsOwnDegreesOfFreedom)
{
    struct Range {
        double lo = 1e9, hi = -1e9;
        void add(double v) { lo = std::min(lo, v), hi = std::max(hi, v); }
        double span() const { return hi - lo; }
    };
    for (Motion motion : {Motion::Translate, Motion::Rotate, Motion::Scale, Motion::Yaw}) {
        const Scene scene(config(Preset::Clean, motion, 11));
        Range x, z, roll, yaw;
        for (int frame = 45; frame < 900; ++frame) {
            const HandPose p = scene.hand_pose(frame);
            x.add(p.palm_mm[0]), z.add(p.palm_mm[2]), roll.add(p.roll_deg), yaw.add(p.yaw_deg);
        }
        const std::string name(to_string(motion));
        EXPECT_EQ(x.span() > 50.0, motion == Motion::Translate) << name;
        EXPECT_EQ(z.span() > 100.0, motion == Motion::Scale) << name;
        EXPECT_EQ(roll.span() > 20.0, motion == Motion::Rotate) << name;
        EXPECT_EQ(yaw.span() > 20.0, motion == Motion::Yaw) << name;
    }
}

TEST(SimMotion, LeaveReturnLeavesBothViewsAndComesBack)
{
    const Scene scene(config(Preset::Clean, Motion::LeaveReturn, 2));
    cv::Mat img;
    EyeTruth l, r;
    int gone = 0;
    for (int frame = 0; frame < 600; frame += 10) {
        scene.render(frame, Eye::Left, {}, img, &l);
        scene.render(frame, Eye::Right, {}, img, &r);
        if (cv::countNonZero(l.mask) == 0 && cv::countNonZero(r.mask) == 0) ++gone;
    }
    EXPECT_GE(gone, 3);
    scene.render(0, Eye::Left, {}, img, &l);
    EXPECT_TRUE(l.visible);
    scene.render(600, Eye::Left, {}, img, &l);
    EXPECT_TRUE(l.visible);
    EXPECT_THROW(scene.measured_skin_fraction(200), std::runtime_error);
}

// Panning moves the room the way the shared kinematics say: pan > 0 turns right, so the
// far wall slides left by about f tan(pan).
TEST(SimScene, PanningMovesTheBackgroundLikeARealCamera)
{
    SceneConfig c = config(Preset::Heavy, Motion::Static, 6);
    c.noise_sigma = 0.0;
    const Scene scene(c);
    HandPose away;  // keep the hand out of the way
    away.palm_mm = {5000.0, 0.0, 1000.0};
    cv::Mat a, b, ga, gb;
    scene.render_pose(away, 0, Eye::Left, {}, a);
    scene.render_pose(away, 0, Eye::Left, HeadPose{3.0, 0.0, 0.0, 0.0}, b);
    cv::cvtColor(a, ga, cv::COLOR_BGR2GRAY);
    cv::cvtColor(b, gb, cv::COLOR_BGR2GRAY);
    ga.convertTo(ga, CV_64F);
    gb.convertTo(gb, CV_64F);
    const cv::Point2d shift = cv::phaseCorrelate(ga, gb);
    const double f = scene.calibration().M1(0, 0);
    EXPECT_NEAR(shift.x, -f * std::tan(3.0 * std::numbers::pi / 180.0), 1.5);
    EXPECT_NEAR(shift.y, 0.0, 1.0);
}

TEST(SimScene, LightingChangeVariesBrightness)
{
    SceneConfig c = config(Preset::Light, Motion::Static, 3);
    c.noise_sigma = 0.0;
    const Scene steady(c);
    c.lighting_change = true;
    const Scene changing(c);
    cv::Mat img;
    double lo = 1e9, hi = 0, steady_lo = 1e9, steady_hi = 0;
    for (int frame = 60; frame < 400; frame += 20) {
        changing.render(frame, Eye::Left, {}, img);
        const double m = cv::mean(img)[1];
        lo = std::min(lo, m), hi = std::max(hi, m);
        steady.render(frame, Eye::Left, {}, img);
        const double s = cv::mean(img)[1];
        steady_lo = std::min(steady_lo, s), steady_hi = std::max(steady_hi, s);
    }
    EXPECT_GT(hi / lo, 1.08);
    EXPECT_LT(steady_hi / steady_lo, 1.01);
}

TEST(SimScene, YawForeshortensTheHand)
{
    const Scene scene(config(Preset::Clean, Motion::Static, 1));
    HandPose pose;
    pose.palm_mm = {-60.0, 0.0, 1000.0};
    pose.roll_deg = 0.0;
    cv::Mat img;
    EyeTruth face_on, turned;
    scene.render_pose(pose, 0, Eye::Left, {}, img, &face_on);
    pose.yaw_deg = 60.0;
    scene.render_pose(pose, 0, Eye::Left, {}, img, &turned);
    const double ratio = double(cv::countNonZero(turned.mask)) / cv::countNonZero(face_on.mask);
    EXPECT_NEAR(ratio, 0.5, 0.12);  // cos 60 deg, with some perspective
}

// FNV-1a over the bytes of the image, the hand mask and the face mask of one frame.
std::uint64_t frame_hash(const cv::Mat& img, const EyeTruth& t)
{
    std::uint64_t h = 1469598103934665603ull;
    auto add = [&h](const cv::Mat& m) {
        if (m.empty()) return;
        const cv::Mat c = m.isContinuous() ? m : m.clone();
        const auto* p = c.ptr<std::uint8_t>();
        for (std::size_t i = 0; i < c.total() * c.elemSize(); ++i) h = (h ^ p[i]) * 1099511628211ull;
    };
    add(img);
    add(t.mask);
    add(t.face);
    return h;
}

// The presets of before the scene variety render the very same frames and truth by default:
// many tests and benchmark figures depend on them. The hashes were taken from the renderer
// before the variety existed (OpenCV 4.6 of Debian 12; another OpenCV may round its warps
// differently).
TEST(SimScene, ExistingPresetsRenderAsBefore)
{
    struct Case {
        Preset preset;
        Motion motion;
        std::uint64_t seed;
        bool lighting;
        std::uint64_t expected;
    };
    const Case cases[] = {
        {Preset::Clean, Motion::Mixed, 1, false, 17929683889105910823ull},
        {Preset::Light, Motion::Yaw, 2, false, 2990204891979785252ull},
        {Preset::Heavy, Motion::Mixed, 7, true, 11518751136972703918ull},
        {Preset::FacePass, Motion::Mixed, 3, false, 7102670778598867120ull},
        {Preset::FacePass, Motion::LeaveReturn, 5, true, 8911110177374500181ull},
    };
    for (const Case& k : cases) {
        SceneConfig c = config(k.preset, k.motion, k.seed);
        c.lighting_change = k.lighting;
        const Scene scene(c);
        std::uint64_t h = 0;
        cv::Mat img;
        EyeTruth t;
        for (int frame : {0, 45, 130})
            for (Eye eye : {Eye::Left, Eye::Right}) {
                scene.render(frame, eye, frame == 130 ? HeadPose{2.0, -1.5, 1.0, -0.5} : HeadPose{}, img, &t);
                h = h * 31 + frame_hash(img, t);
            }
        EXPECT_EQ(h, k.expected) << to_string(k.preset) << " " << to_string(k.motion) << " seed " << k.seed;
    }
}

SceneConfig wide(Preset preset, Motion motion, std::uint64_t seed)
{
    SceneConfig c = config(preset, motion, seed);
    c.variety = Variety::Wide;
    return c;
}

TEST(SimVariety, SameSeedSameSceneOtherSeedOtherScene)
{
    expect_seeded(wide(Preset::Varied, Motion::Mixed, 5), 6);
    expect_seeded(wide(Preset::FacePass, Motion::Mixed, 3), 4);
    // The variety is drawn from the seed on top of the preset: heavy with and without it
    // differ, in the hand as in the rest.
    cv::Mat plain, varied;
    EyeTruth tp, tv;
    Scene(config(Preset::Heavy, Motion::Mixed, 5)).render(40, Eye::Left, {}, plain, &tp);
    Scene(wide(Preset::Heavy, Motion::Mixed, 5)).render(40, Eye::Left, {}, varied, &tv);
    EXPECT_GT(cv::norm(plain, varied, cv::NORM_L1) / double(plain.total()), 5.0);
    EXPECT_GT(cv::norm(tp.mask, tv.mask, cv::NORM_L1), 0.0);
}

// Whatever the seed draws (hand shape, distance, blur, compression), the truth is exact: the
// 3D points project onto the truth pixels, the palm is on the mask and the fingertip is the
// mask's extreme point along the pointing direction.
TEST(SimVariety, TruthStaysExact)
{
    int checked = 0;
    for (Preset preset : {Preset::Varied, Preset::Heavy, Preset::FacePass})
        for (std::uint64_t seed = 1; seed <= 6; ++seed) {
            const Scene scene(wide(preset, Motion::Mixed, seed));
            const gc::StereoCalibration cal = scene.calibration();
            for (int frame : {10, 95, 170})
                for (Eye eye : {Eye::Left, Eye::Right}) {
                    cv::Mat img;
                    EyeTruth t;
                    scene.render(frame, eye, {}, img, &t);
                    if (!t.visible) continue;
                    ++checked;
                    const HandTruth t3 = scene.hand_truth(scene.hand_pose(frame));
                    const gc::RigidTransform to_eye = gc::camera_to_head(cal.head, {}, eye).inverse();
                    const cv::Point2d palm = project(cal.M1, to_eye.apply(t3.palm_mm));
                    EXPECT_LT(distance(palm, t.palm_px), 0.5);
                    EXPECT_LT(distance(project(cal.M1, to_eye.apply(t3.fingertip_mm)), t.fingertip_px), 0.5);
                    EXPECT_EQ(t.mask(cv::Point(cvRound(palm.x), cvRound(palm.y))), 255);
                    const double a = t.pointing_deg * std::numbers::pi / 180.0;
                    const cv::Point2d dir(std::cos(a), -std::sin(a));
                    EXPECT_LT(distance(extreme_point(t.mask, palm, dir), t.fingertip_px), 2.5)
                        << to_string(preset) << " seed " << seed << " frame " << frame << " eye " << int(eye);
                    EXPECT_EQ(t.bbox, cv::boundingRect(t.mask));
                }
        }
    EXPECT_GT(checked, 80);
}

// Seeds really differ: the hand's skin from dark to light, its finger from short to long,
// the sensor from quiet to noisy, the forearm sleeved or bare.
TEST(SimVariety, SeedsSpanSkinHandsSensorsAndSleeves)
{
    double darkest = 255.0, lightest = 0.0, shortest = 1e9, longest = 0.0, quietest = 1e9, noisiest = 0.0;
    int bare = 0, sleeved = 0;
    for (std::uint64_t seed = 1; seed <= 24; ++seed) {
        const Scene scene(wide(Preset::Clean, Motion::Static, seed));
        cv::Mat a, b, grey;
        EyeTruth t;
        scene.render(60, Eye::Left, {}, a, &t);
        scene.render(61, Eye::Left, {}, b);
        ASSERT_TRUE(t.visible) << "seed " << seed;
        cv::Mat1b core;  // the hand inside its soft edge
        cv::erode(t.mask, core, cv::getStructuringElement(cv::MORPH_ELLIPSE, {5, 5}));
        cv::cvtColor(a, grey, cv::COLOR_BGR2GRAY);
        const double level = cv::mean(grey, core)[0];
        darkest = std::min(darkest, level), lightest = std::max(lightest, level);

        const HandTruth t3 = scene.hand_truth(scene.hand_pose(60));
        const double finger = cv::norm(t3.fingertip_mm - t3.palm_mm);
        shortest = std::min(shortest, finger), longest = std::max(longest, finger);

        // Static after the wave: frames 60 and 61 differ by their noise alone (and a
        // slow exposure drift), on a background without the hand and arm.
        cv::Mat1b background = t.mask.clone();
        cv::dilate(background, background, cv::getStructuringElement(cv::MORPH_RECT, {101, 101}));
        cv::Mat diff;
        cv::subtract(a, b, diff, cv::noArray(), CV_32F);
        cv::Scalar mean, sd;
        cv::Mat1b outside;
        cv::bitwise_not(background, outside);
        cv::meanStdDev(diff, mean, sd, outside);
        const double sigma = (sd[0] + sd[1] + sd[2]) / 3.0 / std::sqrt(2.0);
        quietest = std::min(quietest, sigma), noisiest = std::max(noisiest, sigma);

        // Half way along the forearm: skin (bare) or not (a sleeve), by a model of the hand.
        const gc::StereoCalibration cal = scene.calibration();
        const gc::RigidTransform to_left = gc::camera_to_head(cal.head, {}, Eye::Left).inverse();
        const cv::Point2d mid = project(cal.M1, to_left.apply(0.5 * (t3.palm_mm + t3.elbow_mm)));
        const cv::Rect patch = cv::Rect(cvRound(mid.x) - 2, cvRound(mid.y) - 2, 5, 5) & cv::Rect(0, 0, a.cols, a.rows);
        ASSERT_FALSE(patch.empty());
        const int skin = cv::countNonZero(gc::SkinModel::fit(a, t.mask).segment(a)(patch));
        bare += skin >= 20;
        sleeved += skin == 0;
    }
    EXPECT_LT(darkest, 70.0);
    EXPECT_GT(lightest, 160.0);
    EXPECT_GT(longest - shortest, 15.0);
    EXPECT_LT(quietest, 1.2);
    EXPECT_GT(noisiest, 3.0);
    EXPECT_GE(bare, 3);
    EXPECT_GE(sleeved, 8);
}

// face-pass with the variety (people of other sizes and tones, sometimes two, the hand at
// another distance) still starts beside the face and crosses it later.
TEST(SimVariety, FacePassStillCrossesTheFace)
{
    for (std::uint64_t seed : {1, 2, 3}) {
        const Scene scene(wide(Preset::FacePass, Motion::Mixed, seed));
        int during_wave = 0, crossing = 0;
        cv::Mat img;
        EyeTruth t;
        for (int frame = 0; frame < 200; frame += 4) {
            scene.render(frame, Eye::Left, {}, img, &t);
            ASSERT_FALSE(t.face.empty());
            const int hand = cv::countNonZero(t.mask);
            const bool crosses = hand > 0 && cv::countNonZero(t.mask & t.face) >= 0.05 * hand;
            (frame <= 36 ? during_wave : crossing) += crosses;
        }
        EXPECT_EQ(during_wave, 0) << "seed " << seed;
        EXPECT_GE(crossing, 5) << "seed " << seed;
    }
}

// A hand moving while the shutter is open smears past its outline (rendering the same pose
// as a still hand shows the difference); without the variety there is no smear.
TEST(SimVariety, MovingHandSmears)
{
    int smeared = 0;
    for (Variety variety : {Variety::None, Variety::Wide}) {
        SceneConfig c = config(Preset::Clean, Motion::Mixed, 23);
        c.variety = variety;
        const Scene scene(c);
        cv::Mat moving, still, diff;
        EyeTruth t;
        scene.render(10, Eye::Left, {}, moving, &t);  // the wave
        scene.render_pose(scene.hand_pose(10), 10, Eye::Left, {}, still);
        cv::absdiff(moving, still, diff);
        cv::Mat1b changed;
        cv::cvtColor(diff, changed, cv::COLOR_BGR2GRAY);
        changed = changed > 10;
        changed.setTo(0, t.mask);
        if (variety == Variety::None)
            EXPECT_EQ(cv::norm(diff, cv::NORM_L1), 0.0);
        else
            smeared = cv::countNonZero(changed);
    }
    EXPECT_GT(smeared, 50);
}

// The varied preset's rooms run from almost no skin-coloured background to a great deal of
// it (skin-coloured walls), and hold no one, one or two people.
TEST(SimVariety, VariedRoomsSpanClutterAndPeople)
{
    double least = 1.0, most = 0.0;
    int without = 0, with_two = 0;
    for (std::uint64_t seed = 1; seed <= 12; ++seed) {
        const Scene scene(wide(Preset::Varied, Motion::Mixed, seed));
        const double fraction = scene.measured_skin_fraction();
        least = std::min(least, fraction), most = std::max(most, fraction);
        cv::Mat img;
        EyeTruth t;
        scene.render_pose(HandPose{{5000.0, 0.0, 1000.0}}, 0, Eye::Left, {}, img, &t);  // hand out of the way
        if (t.face.empty()) {
            ++without;
            continue;
        }
        std::vector<std::vector<cv::Point>> faces;
        cv::findContours(t.face.clone(), faces, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
        int big = 0;
        for (const auto& f : faces) big += cv::contourArea(f) > 100.0;
        with_two += big >= 2;
    }
    EXPECT_LT(least, 0.05);
    EXPECT_GT(most, 0.2);
    EXPECT_GE(without, 1);
    EXPECT_GE(with_two, 1);
}

}  // namespace
