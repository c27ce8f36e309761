// The director camera: a picked target turns and zooms headsim's head (over GCHP, VISCA and
// ONVIF) so the target sits in the middle of its picture at the region's width; a release
// sends it home or to its preset; the same target sends nothing new; someone else moving it
// pauses it; a dead camera never makes show() wait.
#include "test_support.hpp"

#include "headctl/steering/director_camera.hpp"

#include <cmath>
#include <thread>
#include <vector>

namespace gc::headctl::testing {
namespace {

using loopback::eventually;

// 1 m to the left of the stereo head, 200 mm above it, facing ahead.
DirectorMount test_mount()
{
    DirectorMount m;
    m.head_to_base.t = {1000.0, 200.0, 0.0};
    return m;
}

DirectorCameraConfig config_for(const std::string& uri)
{
    DirectorCameraConfig c;
    c.uri = uri;
    c.mount = test_mount();
    c.region_mm = 500.0;
    return c;
}

// The head's pose as a GCHP client of its own reads it, once it stands still near `want`.
bool reaches(HeadClient& observer, const HeadPose& want, double zoom_tolerance)
{
    return eventually(
        [&] {
            const auto s = observer.latest();
            if (!s) return false;
            const HeadPose& p = s->state.pose;
            return std::abs(p.pan_deg - want.pan_deg) < 0.3 && std::abs(p.tilt_deg - want.tilt_deg) < 0.3 &&
                   std::abs(p.zoom - want.zoom) < zoom_tolerance * want.zoom;
        },
        5000ms);
}

HeadClientConfig observer_config(const std::string& uri)
{
    HeadClientConfig c;
    c.uri = uri;
    c.status_interval = 10ms;
    return c;
}

TEST(DirectorCamera, FramesAPickedTargetAndGoesHomeOnRelease)
{
    const cv::Vec3d target(-2000.0, -700.0, 2000.0);  // left of the director, above it, ahead
    for (const std::string scheme : {"gchp", "visca-udp", "onvif"}) {
        SCOPED_TRACE(scheme);
        RunningSimHead head;
        const std::string uri = scheme == "gchp"    ? head.gchp_uri()
                                : scheme == "onvif" ? head.onvif_uri()
                                                    : head.visca_uri();
        HeadClient observer(observer_config(head.gchp_uri()));
        DirectorCamera director(config_for(uri));
        ASSERT_TRUE(eventually([&] { return director.client().state() == ConnectionState::Connected; }, 5000ms));
        director.show(target);
        const auto aim = director.aim();
        ASSERT_TRUE(aim);
        EXPECT_LT(aim->pan_deg, -20.0);
        EXPECT_GT(aim->tilt_deg, 5.0);
        EXPECT_GT(aim->zoom, 4.0);
        // VISCA carries the zoom in 0x4000 steps over the lens's range.
        EXPECT_TRUE(reaches(observer, *aim, 0.02));
        const auto placed = place_in_director(test_mount(), observer.latest()->state.pose, target, 500.0);
        ASSERT_TRUE(placed);
        EXPECT_NEAR(placed->centre.x, 0.5, 0.02);
        EXPECT_NEAR(placed->centre.y, 0.5, 0.03);
        EXPECT_NEAR(placed->fill, 1.0, 0.02);

        director.show(std::nullopt);
        EXPECT_FALSE(director.aim());
        EXPECT_TRUE(reaches(observer, HeadPose{}, 0.001));
    }
}

TEST(DirectorCamera, TheSameTargetSendsNothingAndAReleaseGoesToThePreset)
{
    RunningServer server;
    HeadClient observer(observer_config(server.uri()));
    // An overview saved as preset 7 where the head stands then, and the head sent home.
    HeadPose overview;
    overview.pan_deg = 12.0;
    overview.zoom = 1.5;
    server.server().with_model([&](HeadModel& model, double now_s) {
        AxisValues there;
        there.set(Axis::Pan, overview.pan_deg);
        there.set(Axis::Zoom, overview.zoom);
        model.move_absolute(there, now_s);
    });
    ASSERT_TRUE(reaches(observer, overview, 0.001));
    server.server().with_model([](HeadModel& model, double now_s) {
        model.save_preset(7, now_s);
        model.home(now_s);
    });
    ASSERT_TRUE(reaches(observer, HeadPose{}, 0.001));

    DirectorCameraConfig config = config_for(server.uri());
    config.home_preset = 7;
    std::vector<HeadCommand> sent;
    config.on_command = [&](const HeadCommand& c) { sent.push_back(c); };
    DirectorCamera director(config);
    ASSERT_TRUE(eventually([&] { return director.client().state() == ConnectionState::Connected; }, 5000ms));
    const cv::Vec3d target(800.0, 0.0, 3000.0);
    for (int i = 0; i < 10; ++i) director.show(target);
    director.show(target + cv::Vec3d(0.5, 0.0, 0.0));  // within a millimetre: the same target
    ASSERT_EQ(sent.size(), 1u);
    EXPECT_EQ(sent[0].kind, CommandKind::Absolute);
    ASSERT_TRUE(reaches(observer, *director.aim(), 0.001));
    director.show(std::nullopt);
    director.show(std::nullopt);
    ASSERT_EQ(sent.size(), 2u);
    EXPECT_EQ(sent[1], preset_command(CommandKind::RecallPreset, 7));
    EXPECT_TRUE(reaches(observer, overview, 0.001));
}

// Calls show(target) at 30 frames per second for `duration`, as the element does, and
// returns the events it gave.
std::vector<DirectorEvent> frames(DirectorCamera& director, const std::optional<cv::Vec3d>& target,
                                  std::chrono::milliseconds duration)
{
    std::vector<DirectorEvent> events;
    const auto end = std::chrono::steady_clock::now() + duration;
    while (std::chrono::steady_clock::now() < end) {
        if (const auto e = director.show(target)) events.push_back(*e);
        std::this_thread::sleep_for(33ms);
    }
    return events;
}

TEST(DirectorCamera, SomeoneElseMovingItPausesItThenAHeldTargetIsFramedAgain)
{
    RunningServer server;
    DirectorCameraConfig config = config_for(server.uri());
    config.manual_pause_s = 1.0;
    DirectorCamera director(config);
    ASSERT_TRUE(eventually([&] { return director.client().state() == ConnectionState::Connected; }, 5000ms));
    const cv::Vec3d target(800.0, 0.0, 3000.0);
    EXPECT_EQ(frames(director, target, 1500ms), std::vector<DirectorEvent>{DirectorEvent::Frame});
    const HeadPose aim = *director.aim();

    // A person turns it 20 degrees further (headctl, its remote) while the target is held.
    server.server().with_model([&](HeadModel& model, double now_s) {
        AxisValues elsewhere;
        elsewhere.set(Axis::Pan, aim.pan_deg + 20.0);
        model.move_absolute(elsewhere, now_s);
    });
    EXPECT_EQ(frames(director, target, 600ms), std::vector<DirectorEvent>{DirectorEvent::ManualPause});
    EXPECT_TRUE(director.paused());
    // Released while paused: it stays where the person put it, and the pause runs a second
    // from the last move seen.
    EXPECT_EQ(frames(director, std::nullopt, 1800ms), std::vector<DirectorEvent>{DirectorEvent::Resume});
    EXPECT_FALSE(director.paused());
    HeadClient observer(observer_config(server.uri()));
    HeadPose moved = aim;
    moved.pan_deg += 20.0;
    EXPECT_TRUE(reaches(observer, moved, 0.001));
    // A target held after the pause is framed anew.
    EXPECT_EQ(frames(director, target, 200ms), std::vector<DirectorEvent>{DirectorEvent::Frame});
    EXPECT_TRUE(reaches(observer, aim, 0.001));
}

TEST(DirectorCamera, ACameraThatStallsOrGoesAwayNeverMakesTheCallerWait)
{
    const StuckListener stuck;
    const auto alternate = [](DirectorCamera& director, int i) {
        director.show(i % 20 < 10 ? std::optional<cv::Vec3d>(cv::Vec3d(100.0 * (i / 20), 0.0, 2000.0)) : std::nullopt);
    };
    {
        DirectorCamera director(config_for(stuck.uri()));
        EXPECT_LT(longest_call_us(200, [&](int i) { alternate(director, i); }), 100000.0);
        EXPECT_FALSE(director.aim());  // it never answered: nothing was aimed
    }
    // A camera that answered, then went away: targets and releases go to its client, which
    // keeps trying on its own thread.
    auto server = std::make_unique<RunningServer>();
    DirectorCamera director(config_for(server->uri()));
    ASSERT_TRUE(eventually([&] { return director.client().state() == ConnectionState::Connected; }, 5000ms));
    server.reset();
    EXPECT_LT(longest_call_us(200, [&](int i) { alternate(director, i); }), 100000.0);
}

TEST(DirectorCamera, RefusesABadConfiguration)
{
    DirectorCameraConfig c = config_for("tcp://127.0.0.1:5050");
    c.region_mm = 0.0;
    EXPECT_THROW(DirectorCamera{c}, std::invalid_argument);
    c = config_for("tcp://127.0.0.1:5050");
    c.home_preset = kMaxPreset + 1;
    EXPECT_THROW(DirectorCamera{c}, std::invalid_argument);
    c = config_for("tcp://127.0.0.1:5050");
    c.manual_pause_s = -1.0;
    EXPECT_THROW(DirectorCamera{c}, std::invalid_argument);
    c = config_for("ftp://camera");
    EXPECT_THROW(DirectorCamera{c}, std::invalid_argument);
    DirectorCamera director(config_for("tcp://127.0.0.1:1"));
    EXPECT_THROW(director.set_region(-1.0), std::invalid_argument);
    EXPECT_THROW(director.set_manual_pause(std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace gc::headctl::testing
