// The head link against the simulated head served in-process on loopback: commands reach the
// head in each steering mode, the link survives the head going away, and no call waits on it.
#include "headctl/steering/head_link.hpp"
#include "running_head.hpp"

#include "stereo/calibration.hpp"
#include "stereo/head_geometry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <numbers>
#include <thread>
#include <vector>

namespace gc {
namespace {

using namespace std::chrono_literals;
using headctl::ConnectionState;
using headctl::HeadAtCapture;
using headctl::HeadLink;
using headctl::HeadLinkConfig;
using headctl::steer_mode_from_string;
using headctl::SteerMode;
using loopback::eventually;
using loopback::loopback_head;
using loopback::RunningHead;

const StereoCalibration& calibration()
{
    static const StereoCalibration c = default_calibration({640, 480});
    return c;
}

HeadLinkConfig link_config(const std::string& uri, SteerMode mode)
{
    HeadLinkConfig c;
    c.uri = uri;
    c.steer = mode;
    return c;
}

// A frame in which the left eye tracks the hand at pixel (x, y).
FrameResult left_hand_at(double x, double y)
{
    FrameResult r;
    r.stereo = true;
    r.state = TrackState::Tracking;
    r.left.state = TrackState::Tracking;
    r.left.mean.x = x;
    r.left.mean.y = y;
    r.right = r.left;
    return r;
}

HeadPose latest_pose(const HeadLink& link)
{
    const auto s = link.client().latest();
    return s ? s->state.pose : HeadPose{};
}

// A hand at `palm_head` (head frame, mm) seen by the left eye at the pose at capture;
// nothing when it is out of that view.
FrameResult hand_seen_at(const HeadAtCapture& at, const cv::Vec3d& palm_head)
{
    const HeadPose pose = at.pose.value_or(HeadPose{});
    const cv::Vec3d c = camera_to_head(calibration().head, pose, Eye::Left).inverse().apply(palm_head);
    if (c[2] <= 0.0 || std::abs(c[0] / c[2]) > 0.55) return FrameResult{};
    const cv::Matx33d& K = calibration().M1;
    FrameResult r = left_hand_at(K(0, 0) * c[0] / c[2] + K(0, 2), K(1, 1) * c[1] / c[2] + K(1, 2));
    r.pointing.palm_head_mm = palm_head;
    r.pointing.palm_mm = c;
    return r;
}

// The same hand pointing up, with its 3D position known.
FrameResult pointing_up_at(const HeadAtCapture& at, const cv::Vec3d& palm_head)
{
    FrameResult r = hand_seen_at(at, palm_head);
    if (!r.left.valid()) return r;
    r.pointing.valid = true;
    r.pointing.fingertip_head_mm = palm_head + cv::Vec3d(0.0, -80.0, 0.0);
    r.pointing.direction_head = {0.0, -1.0, 0.0};
    return r;
}

// What `headctl move AXIS=VALUE` does while the link runs: another client's absolute move.
// The client is returned so that it lives until the move is sent.
std::unique_ptr<headctl::HeadClient> move_from_outside(const std::string& uri, headctl::Axis axis, double value)
{
    headctl::HeadClientConfig config;
    config.uri = uri;
    auto client = std::make_unique<headctl::HeadClient>(config);
    headctl::HeadCommand move{headctl::CommandKind::Absolute, {}};
    move.values.set(axis, value);
    client->submit(move);
    return client;
}

// Runs the link at 30 frames per second for `duration`, feeding it `frame(pose at capture)`.
template <class Frame>
void run_frames(HeadLink& link, std::chrono::milliseconds duration, Frame frame)
{
    const auto end = std::chrono::steady_clock::now() + duration;
    while (std::chrono::steady_clock::now() < end) {
        const HeadAtCapture at = link.begin_frame(link.now());
        link.end_frame(frame(at));
        std::this_thread::sleep_for(33ms);
    }
}

TEST(HeadLink, FixateTurnsTheHeadTowardsAHandRightOfCentre)
{
    RunningHead head(loopback_head());
    HeadLink link(link_config(head.uri(), SteerMode::Fixate), calibration());
    ASSERT_TRUE(eventually([&] { return link.state() == ConnectionState::Connected; }, 2000ms));
    ASSERT_TRUE(eventually([&] { return link.client().latest().has_value(); }, 2000ms));

    // The hand stays 10 degrees right of the optical axis and up: the head must pan right
    // and tilt up, and keep going while the hand stays off-centre.
    const double f = calibration().M1(0, 0);
    const double cx = calibration().M1(0, 2), cy = calibration().M1(1, 2);
    const double dx = f * std::tan(10.0 * std::numbers::pi / 180.0);
    run_frames(link, 600ms, [&](const HeadAtCapture&) { return left_hand_at(cx + dx, cy - 0.5 * dx); });
    const HeadPose p = latest_pose(link);
    EXPECT_GT(p.pan_deg, 2.0);
    EXPECT_GT(p.tilt_deg, 1.0);
    EXPECT_GT(link.client().stats().commands_sent, 5u);
}

TEST(HeadLink, FixateReturnsToTheHomePresetOnceTheHandIsLost)
{
    RunningHead head(loopback_head());
    // Someone sets up the watch position with headctl beforehand: pan -15, zoom 3, preset 5.
    headctl::HeadClientConfig driver_config;
    driver_config.uri = head.uri();
    headctl::HeadClient driver(driver_config);
    headctl::HeadCommand watch{headctl::CommandKind::Absolute, {}};
    watch.values.set(headctl::Axis::Pan, -15.0);
    watch.values.set(headctl::Axis::Zoom, 3.0);
    driver.submit(watch);
    const auto at_watch = [&] {
        const auto s = driver.latest();
        return s && std::abs(s->state.pose.pan_deg + 15.0) < 1e-6 && s->state.pose.zoom == 3.0;
    };
    ASSERT_TRUE(eventually(at_watch, 3000ms));
    driver.submit(headctl::preset_command(headctl::CommandKind::SavePreset, 5));
    ASSERT_TRUE(eventually([&] { return driver.stats().commands_sent >= 2; }, 2000ms));
    driver.submit(headctl::HeadCommand{headctl::CommandKind::Home, {}});
    ASSERT_TRUE(eventually(
        [&] {
            const auto s = driver.latest();
            return s && s->state.pose.pan_deg == 0.0 && s->state.pose.zoom == 1.0;
        },
        3000ms));

    HeadLinkConfig config = link_config(head.uri(), SteerMode::Fixate);
    config.fixate.hold_s = 0.3;
    config.fixate.home_preset = 5;
    HeadLink link(config, calibration());
    ASSERT_TRUE(eventually([&] { return link.client().latest().has_value(); }, 2000ms));
    const double dx = calibration().M1(0, 0) * std::tan(10.0 * std::numbers::pi / 180.0);
    run_frames(link, 400ms, [&](const HeadAtCapture&) { return left_hand_at(calibration().M1(0, 2) + dx, 240.0); });
    EXPECT_GT(latest_pose(link).pan_deg, 0.5);  // it followed the hand
    run_frames(link, 1500ms, [&](const HeadAtCapture&) { return FrameResult{}; });
    EXPECT_TRUE(eventually(at_watch, 3000ms)) << latest_pose(link).pan_deg;
}

TEST(HeadLink, FixateWidensTheViewWhileTheHandIsLostAndResumesWhenItIsBack)
{
    RunningHead head(loopback_head());
    HeadLinkConfig config = link_config(head.uri(), SteerMode::Fixate);
    config.fixate.widen_after_s = 0.3;
    config.fixate.widen_rate = 4.0;
    config.fixate.hold_s = 30.0;
    HeadLink link(config, calibration());
    ASSERT_TRUE(eventually([&] { return link.client().limits().has_value(); }, 2000ms));
    const auto driver = move_from_outside(head.uri(), headctl::Axis::Zoom, 6.0);
    ASSERT_TRUE(eventually([&] { return latest_pose(link).zoom == 6.0; }, 3000ms));

    const FrameResult centred = left_hand_at(calibration().M1(0, 2), calibration().M1(1, 2));
    run_frames(link, 300ms, [&](const HeadAtCapture&) { return centred; });
    EXPECT_DOUBLE_EQ(latest_pose(link).zoom, 6.0);  // tracking leaves the lens alone
    run_frames(link, 1200ms, [&](const HeadAtCapture&) { return FrameResult{}; });
    const double widened = latest_pose(link).zoom;
    EXPECT_LT(widened, 4.0);  // about 0.9 s at 4 per second
    run_frames(link, 600ms, [&](const HeadAtCapture&) { return centred; });
    const double resumed = latest_pose(link).zoom;
    EXPECT_GT(resumed, widened - 1.0);  // stopped at once, not run on to the widest
    EXPECT_GT(resumed, 1.5);
}

// Views that reach the link later than max_view_age after capture do not steer: the same
// off-centre hand that turns the head when fresh leaves it at rest when 400 ms old.
TEST(HeadLink, ViewsTooOldToSteerFromLeaveTheHeadAtRest)
{
    RunningHead head(loopback_head());
    HeadLink link(link_config(head.uri(), SteerMode::Fixate), calibration());
    ASSERT_TRUE(eventually([&] { return link.client().latest().has_value(); }, 2000ms));
    const double dx = calibration().M1(0, 0) * std::tan(10.0 * std::numbers::pi / 180.0);
    const FrameResult off_centre = left_hand_at(calibration().M1(0, 2) + dx, calibration().M1(1, 2));
    const auto end = std::chrono::steady_clock::now() + 600ms;
    while (std::chrono::steady_clock::now() < end) {
        link.begin_frame(link.now() - std::chrono::milliseconds(400));
        link.end_frame(off_centre);
        EXPECT_TRUE(link.last_view_stale());
        EXPECT_GE(link.last_view_age_ms(), 400.0);
        std::this_thread::sleep_for(33ms);
    }
    std::this_thread::sleep_for(100ms);
    EXPECT_LT(std::abs(latest_pose(link).pan_deg), 0.01);

    run_frames(link, 300ms, [&](const HeadAtCapture&) { return off_centre; });
    EXPECT_FALSE(link.last_view_stale());
    EXPECT_LT(link.last_view_age_ms(), 250.0);
    EXPECT_GT(latest_pose(link).pan_deg, 0.5);
}

TEST(HeadLink, FixateVergesOnTheHandsDepth)
{
    RunningHead head(loopback_head());
    HeadLink link(link_config(head.uri(), SteerMode::Fixate), calibration());
    ASSERT_TRUE(eventually([&] { return link.client().latest().has_value(); }, 2000ms));
    // A static hand 600 mm straight ahead of the head, seen where the left eye's pose at
    // capture puts it, with its 3D position known.
    const cv::Vec3d palm_head(0.0, 0.0, 600.0);
    // Long enough for the eyes to verge and the neck to settle after them, also under ASan.
    run_frames(link, 4000ms, [&](const HeadAtCapture& at) { return pointing_up_at(at, palm_head); });
    const HeadPose p = latest_pose(link);
    const double expected = std::atan2(60.0, 600.0) * 180.0 / std::numbers::pi;  // 5.7 degrees
    EXPECT_NEAR(p.verge_left_deg, expected, 0.6);
    EXPECT_NEAR(p.verge_right_deg, -expected, 0.6);
    // The hand is straight ahead: the neck ends within the controller's release band (2 deg;
    // it stops anywhere inside the 1 deg dead band of the left eye's offset).
    EXPECT_NEAR(p.pan_deg, 0.0, 2.0);
    EXPECT_NEAR(p.tilt_deg, 0.0, 2.0);
}

// A still hand whose fingertip is 800 mm ahead of the head, pointing along `direction`, seen
// where the pose at capture puts it in the left view; nothing when it is out of view.
FrameResult pointing_along(const HeadAtCapture& at, const cv::Vec3d& direction)
{
    FrameResult r = hand_seen_at(at, {-80.0, 0.0, 800.0});
    if (!r.left.valid()) return r;
    r.pointing.valid = true;
    r.pointing.fingertip_head_mm = {0.0, 0.0, 800.0};
    r.pointing.direction_head = cv::normalize(direction);
    return r;
}

struct Recorded {
    std::vector<headctl::SteeringEvent> events;
    void attach(HeadLinkConfig& c)
    {
        c.on_steering = [this](headctl::SteeringEvent e, const std::string& detail) {
            std::printf("  %s: %s\n", std::string(headctl::to_string(e)).c_str(), detail.c_str());
            events.push_back(e);
        };
    }
    long count(headctl::SteeringEvent e) const { return std::count(events.begin(), events.end(), e); }
};

TEST(HeadLink, PointLooksAtAHeldPointingForTheLookTimeAndComesBack)
{
    RunningHead head(loopback_head());
    HeadLinkConfig config = link_config(head.uri(), SteerMode::Point);
    config.target.distance_mm = 1000.0;
    config.times.dwell_s = 1.0;
    config.times.look_s = 1.5;
    Recorded recorded;
    recorded.attach(config);
    HeadLink link(config, calibration());
    ASSERT_TRUE(eventually([&] { return link.client().latest().has_value(); }, 2000ms));

    // The hand points to the right and a little up, and holds it.
    const cv::Vec3d direction = cv::normalize(cv::Vec3d(1.0, -0.2, 0.0));
    const auto held = [&](const HeadAtCapture& at) { return pointing_along(at, direction); };
    const cv::Vec3d target = cv::Vec3d(0.0, 0.0, 800.0) + 1000.0 * direction;
    const double pan = std::atan2(target[0], target[2]) * 180.0 / std::numbers::pi;
    run_frames(link, 800ms, held);
    const HeadPose before = latest_pose(link);  // keeping the hand in view
    EXPECT_LT(std::abs(before.pan_deg), 10.0) << "it turned before the dwell was over";
    // Dwell (1 s) and the turn: the head looks at the target for the look time.
    run_frames(link, 1000ms, held);
    HeadPose p = latest_pose(link);
    EXPECT_NEAR(p.pan_deg, pan, 0.5);
    EXPECT_GT(p.tilt_deg, 3.0);                      // up
    EXPECT_GT(p.verge_left_deg, p.verge_right_deg);  // converging on the target
    EXPECT_EQ(link.point_phase(), headctl::PointPhase::Looking);
    // Then back to the pose it left, where the hand was; the pointing, still held, is not
    // looked at again.
    run_frames(link, 3000ms, held);
    p = latest_pose(link);
    EXPECT_NEAR(p.pan_deg, before.pan_deg, 1.5);
    EXPECT_NEAR(p.tilt_deg, before.tilt_deg, 1.5);
    EXPECT_EQ(link.point_phase(), headctl::PointPhase::Following);
    EXPECT_EQ(recorded.count(headctl::SteeringEvent::Look), 1);
    EXPECT_EQ(recorded.count(headctl::SteeringEvent::Return), 1);
    EXPECT_EQ(recorded.count(headctl::SteeringEvent::Follow), 1);
}

// A side wall 500 mm to the right (set while running, as the element does): the head looks
// where the ray meets it, not target-distance along the ray (which would be 19 deg farther).
TEST(HeadLink, PointLooksWhereTheRayMeetsTheTargetPlane)
{
    RunningHead head(loopback_head());
    HeadLinkConfig config = link_config(head.uri(), SteerMode::Point);
    config.times.dwell_s = 1.0;
    HeadLink link(config, calibration());
    link.set_steering(SteerMode::Point, {1000.0, plane_from_coefficients(1.0, 0.0, 0.0, -500.0)});
    ASSERT_TRUE(eventually([&] { return link.client().latest().has_value(); }, 2000ms));
    const cv::Vec3d direction = cv::normalize(cv::Vec3d(1.0, -0.2, 0.0));
    const auto held = [&](const HeadAtCapture& at) { return pointing_along(at, direction); };
    run_frames(link, 1800ms, held);
    const double on_wall_pan = std::atan2(500.0, 800.0) * 180.0 / std::numbers::pi;
    EXPECT_NEAR(latest_pose(link).pan_deg, on_wall_pan, 0.5);
    EXPECT_EQ(link.point_phase(), headctl::PointPhase::Looking);
}

TEST(HeadLink, PointMovesNothingForATalkingHand)
{
    RunningHead head(loopback_head());
    HeadLinkConfig config = link_config(head.uri(), SteerMode::Point);
    config.target.distance_mm = 1000.0;
    Recorded recorded;
    recorded.attach(config);
    HeadLink link(config, calibration());
    ASSERT_TRUE(eventually([&] { return link.client().latest().has_value(); }, 2000ms));
    // A hand in the middle of the view whose pointing swings 15 deg every half second (each
    // direction held long enough for the old re-aim on five steady frames), then is lowered.
    int frame = 0;
    run_frames(link, 3000ms, [&](const HeadAtCapture& at) {
        const bool left = (frame++ / 15) % 2 == 0;
        return pointing_along(at, left ? cv::Vec3d(0.3, -0.2, 1.0) : cv::Vec3d(0.6, -0.2, 1.0));
    });
    run_frames(link, 1000ms, [&](const HeadAtCapture& at) {
        FrameResult r = pointing_along(at, {0.0, 1.0, 0.0});
        r.pointing = {};  // lowered: no pointing
        return r;
    });
    EXPECT_EQ(recorded.count(headctl::SteeringEvent::Look), 0);
    // The fixate law only keeps the hand in the left view (it is 8 deg right of that eye's axis).
    EXPECT_LT(std::abs(latest_pose(link).pan_deg), 10.0);
    EXPECT_LT(std::abs(latest_pose(link).tilt_deg), 2.0);
}

// A fixate link whose steering pauses 1.5 s after someone else moves the head.
struct PausingLink {
    RunningHead head{loopback_head()};
    Recorded recorded;
    HeadLink link{config(), calibration()};

    HeadLinkConfig config()
    {
        HeadLinkConfig c = link_config(head.uri(), SteerMode::Fixate);
        c.times.manual_pause_s = 1.5;
        recorded.attach(c);
        return c;
    }

    // Someone runs `headctl move pan=20` while the element steers `hand`: the move stands
    // and steering pauses. The outside client is returned to live as long as the caller's run.
    template <class Hand>
    std::unique_ptr<headctl::HeadClient> pan_from_outside(Hand hand)
    {
        auto driver = move_from_outside(head.uri(), headctl::Axis::Pan, 20.0);
        run_frames(link, 1000ms, hand);
        EXPECT_NEAR(latest_pose(link).pan_deg, 20.0, 0.1) << "the element undid the move";
        EXPECT_TRUE(link.paused());
        EXPECT_EQ(recorded.count(headctl::SteeringEvent::ManualPause), 1);
        return driver;
    }
};

TEST(HeadLink, AManualMovePausesSteeringThenItResumes)
{
    PausingLink rig;
    HeadLink& link = rig.link;
    ASSERT_TRUE(eventually([&] { return link.client().limits().has_value(); }, 2000ms));
    // A still hand 1 m straight ahead, seen where each frame's pose puts it.
    const cv::Vec3d palm_head(0.0, 0.0, 1000.0);
    const auto still_hand = [&](const HeadAtCapture& at) { return hand_seen_at(at, palm_head); };
    run_frames(link, 1500ms, still_hand);
    const HeadPose before = latest_pose(link);  // the hand in the middle of the left view
    ASSERT_LT(std::abs(before.pan_deg), 5.0);

    const auto driver = rig.pan_from_outside(still_hand);
    EXPECT_EQ(rig.recorded.count(headctl::SteeringEvent::Resume), 0);
    // The pause runs from the end of the move; then the head follows the hand again.
    run_frames(link, 2500ms, still_hand);
    EXPECT_FALSE(link.paused());
    EXPECT_EQ(rig.recorded.count(headctl::SteeringEvent::Resume), 1);
    EXPECT_NEAR(latest_pose(link).pan_deg, before.pan_deg, 2.0);
}

TEST(HeadLink, AManualPanIsSeenWhileTheEyesVerge)
{
    // The hand comes closer and goes back along the left eye's line of sight, so the eyes
    // keep verging while pan and tilt rest. Someone pans the head meanwhile: the link's
    // vergence commands must not hold pan at 0 again and so cancel the move before the watch
    // sees it.
    PausingLink rig;
    HeadLink& link = rig.link;
    ASSERT_TRUE(eventually([&] { return link.client().limits().has_value(); }, 2000ms));
    const auto start = std::chrono::steady_clock::now();
    const cv::Vec3d left_eye = camera_to_head(calibration().head, HeadPose{}, Eye::Left).apply({0.0, 0.0, 0.0});
    const auto nearing_hand = [&](const HeadAtCapture& at) {
        const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return pointing_up_at(at, left_eye + cv::Vec3d(0.0, 0.0, 700.0 + 250.0 * std::sin(2.0 * t)));
    };
    run_frames(link, 1500ms, nearing_hand);
    const HeadPose before = latest_pose(link);
    ASSERT_LT(std::abs(before.pan_deg), 5.0);

    rig.pan_from_outside(nearing_hand);
}

TEST(HeadLink, OffOnlyReadsThePose)
{
    RunningHead head(loopback_head());
    HeadLink link(link_config(head.uri(), SteerMode::Off), calibration());
    ASSERT_TRUE(eventually([&] { return link.client().latest().has_value(); }, 2000ms));
    std::optional<HeadPose> seen;
    run_frames(link, 300ms, [&](const HeadAtCapture& at) {
        seen = at.pose;
        return left_hand_at(600, 100);
    });
    EXPECT_TRUE(seen.has_value());
    EXPECT_EQ(link.client().stats().commands_submitted, 0u);
}

TEST(HeadLink, ReportsTheCameraMotionOfAMovingHead)
{
    RunningHead head(loopback_head());
    HeadLink link(link_config(head.uri(), SteerMode::Fixate), calibration());
    ASSERT_TRUE(eventually([&] { return link.client().latest().has_value(); }, 2000ms));
    // A hand far right: the head pans right, so the static scene moves left in both views.
    double sum_dx_left = 0.0, sum_dx_right = 0.0;
    std::optional<HeadPose> first, last;
    run_frames(link, 800ms, [&](const HeadAtCapture& at) {
        if (at.pose && !first) first = at.pose;
        if (at.pose) last = at.pose;
        sum_dx_left += at.left_motion.dx;
        sum_dx_right += at.right_motion.dx;
        return left_hand_at(600, 240);
    });
    ASSERT_TRUE(first && last);
    const double panned = last->pan_deg - first->pan_deg;
    ASSERT_GT(panned, 2.0);
    // About f * tan(panned) pixels to the left (the hand stays where it was last seen).
    const double expected = -calibration().M1(0, 0) * std::tan(panned * std::numbers::pi / 180.0);
    EXPECT_NEAR(sum_dx_left, expected, 0.25 * std::abs(expected));
    EXPECT_NEAR(sum_dx_right, expected, 0.25 * std::abs(expected));
}

TEST(HeadLink, ReconnectsAndNeverBlocksWhileTheHeadIsGone)
{
    std::mutex mutex;
    std::vector<ConnectionState> changes;
    auto head = std::make_unique<RunningHead>(loopback_head());
    const std::uint16_t port = head->port();
    HeadLinkConfig config = link_config(head->uri(), SteerMode::Fixate);
    config.on_state_change = [&](ConnectionState s, const std::string&) {
        std::lock_guard lock(mutex);
        changes.push_back(s);
    };
    HeadLink link(config, calibration());
    ASSERT_TRUE(eventually([&] { return link.state() == ConnectionState::Connected; }, 2000ms));

    // Frames keep coming while the head goes away and comes back; time every call.
    std::chrono::steady_clock::duration worst{0};
    auto frame = [&] {
        const auto start = std::chrono::steady_clock::now();
        link.begin_frame(link.now());
        link.end_frame(left_hand_at(500, 200));
        worst = std::max(worst, std::chrono::steady_clock::now() - start);
        std::this_thread::sleep_for(10ms);
    };
    for (int i = 0; i < 10; ++i) frame();
    head.reset();
    ASSERT_TRUE(eventually(
        [&] {
            frame();
            return link.state() != ConnectionState::Connected;
        },
        2000ms));
    const auto gone_until = std::chrono::steady_clock::now() + 700ms;
    while (std::chrono::steady_clock::now() < gone_until) frame();

    head = std::make_unique<RunningHead>(loopback_head(port));
    const auto restarted = std::chrono::steady_clock::now();
    ASSERT_TRUE(eventually(
        [&] {
            frame();
            return link.state() == ConnectionState::Connected;
        },
        2000ms));
    const auto reconnect = std::chrono::steady_clock::now() - restarted;
    for (int i = 0; i < 10; ++i) frame();

    const double worst_ms = std::chrono::duration<double, std::milli>(worst).count();
    std::printf("reconnected after %.0f ms; slowest begin_frame + end_frame: %.3f ms\n",
                std::chrono::duration<double, std::milli>(reconnect).count(), worst_ms);
    EXPECT_LT(worst_ms, 20.0);
    EXPECT_GT(link.client().stats().commands_sent, 0u);
    std::lock_guard lock(mutex);
    EXPECT_NE(std::find(changes.begin(), changes.end(), ConnectionState::Disconnected), changes.end());
    EXPECT_EQ(changes.back(), ConnectionState::Connected);
}

TEST(HeadLink, RejectsBadConfiguration)
{
    EXPECT_THROW(HeadLink(link_config("", SteerMode::Fixate), calibration()), std::invalid_argument);
    EXPECT_THROW(HeadLink(link_config("carrier-pigeon://x", SteerMode::Fixate), calibration()), std::invalid_argument);
    HeadLinkConfig c = link_config("tcp://127.0.0.1:1", SteerMode::Point);
    c.target.distance_mm = 0.0;
    try {
        HeadLink link(c, calibration());
        ADD_FAILURE() << "a zero target distance was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("target distance"), std::string::npos) << e.what();
    }
    c = link_config("tcp://127.0.0.1:1", SteerMode::Fixate);
    c.max_view_age = 0ms;
    EXPECT_THROW(HeadLink(c, calibration()), std::invalid_argument);
    c = link_config("tcp://127.0.0.1:1", SteerMode::Point);
    c.times.look_s = 0.0;
    EXPECT_THROW(HeadLink(c, calibration()), std::invalid_argument);
    c.times.look_s = 4.0;
    c.times.manual_pause_s = -1.0;
    EXPECT_THROW(HeadLink(c, calibration()), std::invalid_argument);
    EXPECT_EQ(steer_mode_from_string("fixate"), SteerMode::Fixate);
    EXPECT_EQ(steer_mode_from_string("point"), SteerMode::Point);
    EXPECT_EQ(steer_mode_from_string("off"), SteerMode::Off);
    EXPECT_FALSE(steer_mode_from_string("Fixate").has_value());
}

}  // namespace
}  // namespace gc
