// The frame pipeline shared by the element and the CLI: input validation, the overall state,
// the 3D step's wiring, and the JSON line's schema, rounding and robustness.
#include "sim/scene.hpp"
#include "stereo/calibration.hpp"
#include "tools/json_reader.hpp"
#include "tracker/pointing_tracker.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <locale>
#include <set>
#include <string>

namespace {

using gc::tools::JsonReader;
using gc::tools::JsonValue;

std::set<std::string> keys_of(const JsonValue& v)
{
    std::set<std::string> keys;
    for (const auto& [k, _] : v.object()) keys.insert(k);
    return keys;
}

const std::set<std::string> kEyeKeys{"x",    "y",       "rotation_deg", "scale",        "confidence",
                                     "bbox", "contour", "fingertip",    "pointing_deg", "gesture"};

gc::EyeEstimate sample_eye()
{
    gc::EyeEstimate e;
    e.state = gc::TrackState::Tracking;
    e.mean = {123.456789, 45.678912, 0.5, 1.23456};
    e.best = e.mean;
    e.confidence = 0.87654;
    e.bbox = cv::Rect(100, 20, 50, 60);
    e.contour = {{100.004f, 20.0f}, {150.0f, 20.126f}, {150.0f, 80.0f}, {100.0f, 80.0f}};
    e.fingertip = {149.996f, 50.5f};
    e.palm = {120.0f, 50.0f};
    e.pointing_deg = -12.3456;
    return e;
}

// Runs `f`, expects exception E, and returns its message.
template <typename E, typename F>
std::string message_of(F&& f)
{
    try {
        f();
    } catch (const E& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "unexpected exception type: " << e.what();
        return {};
    }
    ADD_FAILURE() << "no exception thrown";
    return {};
}

TEST(JsonLine, MonoHasTheSchemaOfDesignWithoutRightOrPointing)
{
    gc::FrameResult r;
    r.frame = 7;
    r.pts_ns = 233333333;
    r.state = gc::TrackState::Tracking;
    r.stereo = false;
    r.left = sample_eye();
    const JsonValue v = JsonReader::parse(gc::to_json_line(r));
    EXPECT_EQ(keys_of(v), (std::set<std::string>{"frame", "pts_ns", "state", "left"}));
    EXPECT_EQ(v["frame"].number(), 7);
    EXPECT_EQ(v["pts_ns"].number(), 233333333);
    EXPECT_EQ(v["state"].string(), "tracking");
    const JsonValue& left = v["left"];
    EXPECT_EQ(keys_of(left), kEyeKeys);
    EXPECT_DOUBLE_EQ(left["x"].number(), 123.46);  // 0.01 px
    EXPECT_DOUBLE_EQ(left["y"].number(), 45.68);
    EXPECT_DOUBLE_EQ(left["rotation_deg"].number(), 28.65);  // 0.5 rad, 0.01 deg
    EXPECT_DOUBLE_EQ(left["scale"].number(), 1.235);
    EXPECT_DOUBLE_EQ(left["confidence"].number(), 0.877);
    EXPECT_DOUBLE_EQ(left["pointing_deg"].number(), -12.35);
    ASSERT_EQ(left["bbox"].array().size(), 4u);
    EXPECT_EQ(left["bbox"][2].number(), 50);
    ASSERT_EQ(left["contour"].array().size(), 4u);
    EXPECT_DOUBLE_EQ(left["contour"][0][0].number(), 100.0);
    EXPECT_DOUBLE_EQ(left["contour"][1][1].number(), 20.13);
    EXPECT_DOUBLE_EQ(left["fingertip"][0].number(), 150.0);
}

TEST(JsonLine, StereoEyeWithoutEstimateAndInvalidPointingAreNull)
{
    gc::FrameResult r;
    r.stereo = true;
    r.state = gc::TrackState::Acquiring;
    r.left = sample_eye();
    r.right = gc::EyeEstimate{};  // acquiring, nothing found yet
    r.pts_ns = -1;
    const std::string line = gc::to_json_line(r);
    EXPECT_EQ(line.find('\n'), std::string::npos);
    const JsonValue v = JsonReader::parse(line);
    EXPECT_EQ(keys_of(v), (std::set<std::string>{"frame", "pts_ns", "state", "left", "right", "pointing"}));
    EXPECT_TRUE(v["pts_ns"].is_null());
    EXPECT_EQ(v["state"].string(), "acquiring");
    EXPECT_TRUE(v["left"].is_object());
    EXPECT_TRUE(v["right"].is_null());
    EXPECT_TRUE(v["pointing"].is_null());
}

TEST(JsonLine, ValidPointingIsWrittenInMillimetresAndDegrees)
{
    gc::FrameResult r;
    r.stereo = true;
    r.state = gc::TrackState::Tracking;
    r.left = sample_eye();
    r.right = sample_eye();
    r.pointing.valid = true;
    r.pointing.fingertip_mm = {10.04, -20.06, 1000.25};
    r.pointing.palm_mm = {-50.0, 0.0, 1100.0};
    r.pointing.direction = cv::normalize(r.pointing.fingertip_mm - r.pointing.palm_mm);
    gc::direction_angles(r.pointing.direction, r.pointing.azimuth_deg, r.pointing.elevation_deg);
    const JsonValue v = JsonReader::parse(gc::to_json_line(r));
    const JsonValue& p = v["pointing"];
    EXPECT_EQ(keys_of(p),
              (std::set<std::string>{"fingertip_mm", "palm_mm", "direction", "azimuth_deg", "elevation_deg"}));
    EXPECT_DOUBLE_EQ(p["fingertip_mm"][0].number(), 10.0);  // 0.1 mm
    EXPECT_DOUBLE_EQ(p["fingertip_mm"][1].number(), -20.1);
    EXPECT_DOUBLE_EQ(p["fingertip_mm"][2].number(), 1000.3);
    double norm2 = 0.0;
    for (int i = 0; i < 3; ++i) norm2 += p["direction"][i].number() * p["direction"][i].number();
    EXPECT_NEAR(norm2, 1.0, 1e-3);
    EXPECT_NEAR(p["azimuth_deg"].number(), r.pointing.azimuth_deg, 0.006);
    EXPECT_EQ(keys_of(v["right"]), kEyeKeys);
}

TEST(JsonLine, NonFiniteNumbersBecomeNullAndNegativeZeroIsZero)
{
    gc::FrameResult r;
    r.left = sample_eye();
    r.left.mean.x = std::nan("");
    r.left.mean.y = -0.001;
    r.left.confidence = std::numeric_limits<double>::infinity();
    r.left.mean.scale = std::numeric_limits<double>::max();  // absurd but finite
    r.left.pointing_deg = -std::numeric_limits<double>::max();
    const std::string line = gc::to_json_line(r);
    EXPECT_EQ(line.find("-0,"), std::string::npos) << line;
    const JsonValue v = JsonReader::parse(line);
    EXPECT_TRUE(v["left"]["x"].is_null());
    EXPECT_EQ(v["left"]["y"].number(), 0.0);
    EXPECT_TRUE(v["left"]["confidence"].is_null());
    EXPECT_DOUBLE_EQ(v["left"]["scale"].number(), std::numeric_limits<double>::max());
    EXPECT_DOUBLE_EQ(v["left"]["pointing_deg"].number(), -std::numeric_limits<double>::max());
}

// A global locale with a decimal comma must not leak into the output.
struct CommaDecimal : std::numpunct<char> {
    char do_decimal_point() const override { return ','; }
    char do_thousands_sep() const override { return '.'; }
    std::string do_grouping() const override { return "\3"; }
};

TEST(JsonLine, IndependentOfTheGlobalLocale)
{
    gc::FrameResult r;
    r.left = sample_eye();
    const std::string reference = gc::to_json_line(r);
    const std::locale previous = std::locale::global(std::locale(std::locale::classic(), new CommaDecimal));
    const std::string under_comma = gc::to_json_line(r);
    std::locale::global(previous);
    EXPECT_EQ(reference, under_comma);
    EXPECT_NO_THROW(JsonReader::parse(under_comma));
}

TEST(PointingTracker, RejectsBadFramesWithMessagesNamingTheProblem)
{
    gc::TrackerParams params;
    params.particles = 50;
    gc::PointingTracker tracker(params);
    const cv::Mat3b frame(240, 320, cv::Vec3b(40, 40, 40));
    EXPECT_NE(message_of<std::invalid_argument>([&] { tracker.process_stereo(cv::Mat(), frame); }).find("empty"),
              std::string::npos);
    const cv::Mat1b grey(240, 320, uchar(0));
    EXPECT_NE(message_of<std::invalid_argument>([&] { tracker.process_mono(grey); }).find("CV_8UC3"),
              std::string::npos);
    const cv::Mat3b small(120, 160, cv::Vec3b(0, 0, 0));
    const std::string m = message_of<std::invalid_argument>([&] { tracker.process_stereo(frame, small); });
    EXPECT_NE(m.find("320x240"), std::string::npos) << m;
    EXPECT_NE(m.find("160x120"), std::string::npos) << m;
    EXPECT_EQ(tracker.last().frame, 0);  // nothing was processed
}

TEST(PointingTracker, CalibrationSizeMustMatchTheFrames)
{
    gc::TrackerParams params;
    params.particles = 50;
    gc::PointingTracker tracker(params, gc::default_calibration(cv::Size(640, 480)));
    const cv::Mat3b frame(240, 320, cv::Vec3b(40, 40, 40));
    const std::string m = message_of<std::invalid_argument>([&] { tracker.process_stereo(frame, frame); });
    EXPECT_NE(m.find("320x240"), std::string::npos) << m;
    EXPECT_NE(m.find("640x480"), std::string::npos) << m;
}

TEST(PointingTracker, ModeAndSizeAreFixedUntilReset)
{
    gc::TrackerParams params;
    params.particles = 50;
    gc::PointingTracker tracker(params);
    const cv::Mat3b frame(240, 320, cv::Vec3b(40, 40, 40));
    const cv::Mat3b other(200, 320, cv::Vec3b(40, 40, 40));
    tracker.process_mono(frame, 1000);
    EXPECT_THROW(tracker.process_stereo(frame, frame), std::logic_error);
    const std::string m = message_of<std::invalid_argument>([&] { tracker.process_mono(other); });
    EXPECT_NE(m.find("320x200"), std::string::npos) << m;
    tracker.process_mono(frame, 2000);
    EXPECT_EQ(tracker.last().frame, 1);
    EXPECT_EQ(tracker.last().pts_ns, 2000);
    EXPECT_FALSE(tracker.last().stereo);
    tracker.reset();
    EXPECT_NO_THROW(tracker.process_stereo(other, other));
    EXPECT_EQ(tracker.last().frame, 0);
    EXPECT_TRUE(tracker.last().stereo);
    EXPECT_EQ(tracker.last().pts_ns, -1);
}

TEST(PointingTracker, ExposesTheHypothesesOfTheEyesItTracks)
{
    gc::TrackerParams params;
    params.particles = 50;
    gc::PointingTracker tracker(params);
    EXPECT_TRUE(tracker.particles(gc::Eye::Left).empty());  // no frame yet
    const cv::Mat3b frame(240, 320, cv::Vec3b(40, 40, 40));
    tracker.process_mono(frame);
    EXPECT_EQ(tracker.particles(gc::Eye::Left).size(), 50u);
    EXPECT_TRUE(tracker.particles(gc::Eye::Right).empty());
    tracker.reset();
    EXPECT_TRUE(tracker.particles(gc::Eye::Left).empty());
    tracker.process_stereo(frame, frame);
    EXPECT_EQ(tracker.particles(gc::Eye::Left).size(), 50u);
    EXPECT_EQ(tracker.particles(gc::Eye::Right).size(), 50u);
}

gc::sim::SceneConfig translating_scene(std::uint64_t seed)
{
    gc::sim::SceneConfig config;
    config.preset = gc::sim::Preset::Clean;
    config.motion = gc::sim::Motion::Translate;
    config.seed = seed;
    return config;
}

struct StereoRun {
    int tracking = 0, pointing = 0, first_tracking = -1;
};

// One rendered scene through the stereo pipeline: tracked and pointing frames, with the
// per-frame invariants checked on the way.
StereoRun run_stereo(std::uint64_t scene_seed, int frames)
{
    const gc::sim::Scene scene(translating_scene(scene_seed));
    gc::TrackerParams params;
    params.particles = 300;
    params.seed = 5;
    gc::PointingTracker tracker(params, scene.calibration());
    cv::Mat left, right;
    gc::sim::EyeTruth truth;
    StereoRun run;
    for (int f = 0; f < frames; ++f) {
        scene.render(f, gc::Eye::Left, {}, left, &truth);
        scene.render(f, gc::Eye::Right, {}, right);
        const gc::FrameResult& r = tracker.process_stereo(left, right, f * 33'333'333LL);
        EXPECT_EQ(r.frame, f);
        EXPECT_EQ(r.pts_ns, f * 33'333'333LL);
        EXPECT_TRUE(r.stereo);
        // The overall state is the conjunction of the eyes'.
        const bool both = r.left.state == gc::TrackState::Tracking && r.right.state == gc::TrackState::Tracking;
        const bool any_lost = r.left.state == gc::TrackState::Lost || r.right.state == gc::TrackState::Lost;
        EXPECT_EQ(r.state == gc::TrackState::Tracking, both);
        EXPECT_EQ(r.state == gc::TrackState::Lost, any_lost);
        if (!both) {
            EXPECT_FALSE(r.pointing.valid) << "pointing needs both eyes, frame " << f;
            continue;
        }
        if (run.first_tracking < 0) run.first_tracking = f;
        ++run.tracking;
        run.pointing += r.pointing.valid ? 1 : 0;
        if (truth.visible) {
            EXPECT_GT((r.left.bbox & truth.bbox).area(), 0) << "frame " << f;
        }
        // The line parses whatever the state.
        EXPECT_NO_THROW(JsonReader::parse(gc::to_json_line(r)));
    }
    return run;
}

// Four rendered hands: each is acquired within a second and kept; together they point on
// at least half of the tracked frames (whether one rendered hand reads as pointing to the
// landmark model varies from scene to scene, so the share is pooled).
TEST(PipelineOnScene, StereoAcquiresTracksAndPoints)
{
    constexpr int kFrames = 60;
    int tracking = 0, pointing = 0;
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        const StereoRun run = run_stereo(seed, kFrames);
        std::printf("scene seed %d: tracked %d, pointing %d, first tracked frame %d\n", int(seed), run.tracking,
                    run.pointing, run.first_tracking);
        ASSERT_GE(run.first_tracking, 0) << "never tracked in both eyes, scene seed " << seed;
        EXPECT_LT(run.first_tracking, 30) << "scene seed " << seed;
        EXPECT_GE(run.tracking, (kFrames - run.first_tracking) * 8 / 10) << "scene seed " << seed;
        tracking += run.tracking;
        pointing += run.pointing;
    }
    EXPECT_GE(pointing, tracking / 2);
}

TEST(PipelineOnScene, MonoIsReproducibleForTheSameSeed)
{
    const gc::sim::Scene scene(translating_scene(3));
    gc::TrackerParams params;
    params.particles = 200;
    params.seed = 11;
    gc::PointingTracker a(params), b(params);
    cv::Mat frame;
    int tracking = 0;
    for (int f = 0; f < 40; ++f) {
        scene.render(f, gc::Eye::Left, {}, frame);
        const std::string la = gc::to_json_line(a.process_mono(frame, f));
        const std::string lb = gc::to_json_line(b.process_mono(frame, f));
        ASSERT_EQ(la, lb) << "frame " << f;
        const JsonValue v = JsonReader::parse(la);
        ASSERT_FALSE(v.has("right"));
        ASSERT_FALSE(v.has("pointing"));
        tracking += a.last().state == gc::TrackState::Tracking ? 1 : 0;
    }
    EXPECT_GT(tracking, 10);
}

}  // namespace
