// The learned hand models on the real stereo pair: the palm detector finds the hand, the
// landmark model puts the fingertip where MediaPipe does, frames without a hand give none,
// and broken model files are refused with their path.
#include "detect/dnn_input.hpp"
#include "detect/hand_finder.hpp"
#include "detect/hand_landmarks.hpp"
#include "detect/model_files.hpp"
#include "detect/palm_detector.hpp"

#include "real_pair.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <opencv2/imgproc.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using gc_test::ReferenceHand;

constexpr float kMinPalmScore = 0.5f;
constexpr float kMinPresence = 0.5f;
// Frames 25, 50, ... 250 of both views: pointing, then the open hand.
constexpr int kSpotFrameStep = 25;
constexpr int kLastSpotFrame = 250;
// cam0 frames where the hand has not yet come into view.
constexpr int kEmptyFrames = 6;
// Stretches followed frame to frame: pointing, and pointing turning into the open hand.
struct Stretch {
    int view, first, last;
};
constexpr Stretch kStretches[] = {{0, 20, 80}, {1, 190, 250}};

cv::Point2f palm_centre(const std::array<cv::Point2f, 21>& hand)
{
    return (hand[0] + hand[5] + hand[9] + hand[13] + hand[17]) / 5.0f;
}

bool crop_contains(const gc::HandCrop& crop, cv::Point2f p)
{
    cv::Matx23f to_crop;
    cv::invertAffineTransform(gc::crop_to_frame(crop, 1), to_crop);
    const cv::Vec2f q = to_crop * cv::Vec3f(p.x, p.y, 1.0f);
    return q[0] >= 0.0f && q[0] <= 1.0f && q[1] >= 0.0f && q[1] <= 1.0f;
}

// Both views decoded once, the frames the tests use kept, with the references and models.
class RealPair : public ::testing::Test {
protected:
    static void SetUpTestSuite()
    {
        std::set<int> keep;
        for (int i = 0; i <= kLastSpotFrame; i += kSpotFrameStep) keep.insert(i);
        for (int i = 0; i < kEmptyFrames; ++i) keep.insert(i);
        for (const Stretch& s : kStretches)
            for (int i = s.first; i <= s.last; ++i) keep.insert(i);
        for (int view = 0; view < 2; ++view) {
            views_[view] = gc_test::decode_view(view, keep);
            references_[view] = gc_test::load_reference(view);
        }
        palm_ = std::make_unique<gc::PalmDetector>(gc::find_model(gc::kPalmModelFile));
        landmarks_ = std::make_unique<gc::LandmarkModel>(gc::find_model(gc::kLandmarkModelFile));
    }
    static void TearDownTestSuite()
    {
        palm_.reset();
        landmarks_.reset();
        views_ = {};
        references_ = {};
    }

    static const cv::Mat& frame(int view, int i) { return views_[view].frames.at(i); }
    static const ReferenceHand& reference(int view, int i) { return references_[view].at(i); }

    static inline std::array<gc_test::DecodedView, 2> views_;
    static inline std::array<std::vector<ReferenceHand>, 2> references_;
    static inline std::unique_ptr<gc::PalmDetector> palm_;
    static inline std::unique_ptr<gc::LandmarkModel> landmarks_;
};

TEST_F(RealPair, BothViewsDecodeToTheReferencesFrames)
{
    for (int view = 0; view < 2; ++view) {
        EXPECT_EQ(views_[view].frame_count, gc_test::kRealPairFrames) << "view " << view;
        EXPECT_EQ(int(references_[view].size()), gc_test::kRealPairFrames) << "view " << view;
    }
}

// On spot frames of both views the best palm covers the reference palm, its crop holds
// the palm and the fingertip (the wrist lies at the crop's lower edge, sometimes just
// outside), and the landmark model run on that crop finds the hand
// with the index fingertip within 15 px of MediaPipe's.
TEST_F(RealPair, PalmThenLandmarksFindTheFingertip)
{
    for (int view = 0; view < 2; ++view) {
        for (int i = kSpotFrameStep; i <= kLastSpotFrame; i += kSpotFrameStep) {
            SCOPED_TRACE("view " + std::to_string(view) + " frame " + std::to_string(i));
            const ReferenceHand& ref = reference(view, i);
            ASSERT_TRUE(ref.has_value());
            const std::vector<gc::PalmDetection> palms = palm_->detect(frame(view, i), kMinPalmScore);
            ASSERT_FALSE(palms.empty());
            EXPECT_TRUE(palms[0].box.contains(palm_centre(*ref))) << palms[0].box;
            const gc::HandCrop crop = gc::crop_from_palm(palms[0]);
            EXPECT_TRUE(crop_contains(crop, (*ref)[8]));
            EXPECT_TRUE(crop_contains(crop, palm_centre(*ref)));
            const gc::HandKeyPoints hand = landmarks_->run(frame(view, i), crop);
            EXPECT_GE(hand.presence, kMinPresence);
            EXPECT_LE(cv::norm(hand.point(gc::HandPoint::IndexTip) - (*ref)[8]), 15.0);
        }
    }
}

// The hand followed from one palm detection by the landmark model alone, each crop from
// the previous frame's points: the fingertip stays within 30 px of MediaPipe's on nearly
// every frame, also while the pointing hand opens.
TEST_F(RealPair, LandmarksFollowTheHandFrameToFrame)
{
    for (const Stretch& s : kStretches) {
        SCOPED_TRACE("view " + std::to_string(s.view) + " frames " + std::to_string(s.first) + "-" +
                     std::to_string(s.last));
        const std::vector<gc::PalmDetection> palms = palm_->detect(frame(s.view, s.first), kMinPalmScore);
        ASSERT_FALSE(palms.empty());
        gc::HandCrop crop = gc::crop_from_palm(palms[0]);
        int frames = 0, near = 0;
        for (int i = s.first; i <= s.last; ++i, ++frames) {
            const gc::HandKeyPoints hand = landmarks_->run(frame(s.view, i), crop);
            ASSERT_GE(hand.presence, kMinPresence) << "hand lost at frame " << i;
            near += cv::norm(hand.point(gc::HandPoint::IndexTip) - (*reference(s.view, i))[8]) <= 30.0;
            crop = gc::crop_from_landmarks(hand);
        }
        EXPECT_GE(near, 0.95 * frames) << near << " of " << frames << " frames within 30 px";
    }
}

// The finder looks at each hand it finds again through the crop its key points give, and
// turns away a hand whose key points do not settle: the real hand settles on every spot
// frame of both views, fingertip within 15 px of MediaPipe's.
TEST_F(RealPair, TheFinderFindsTheRealHandOnEverySpotFrame)
{
    gc::HandFinder finder;
    for (int view = 0; view < 2; ++view) {
        for (int i = kSpotFrameStep; i <= kLastSpotFrame; i += kSpotFrameStep) {
            SCOPED_TRACE("view " + std::to_string(view) + " frame " + std::to_string(i));
            const std::optional<gc::FoundHand> hand = finder.find(frame(view, i));
            ASSERT_TRUE(hand.has_value());
            EXPECT_LE(cv::norm(hand->points[8] - (*reference(view, i))[8]), 15.0);
        }
    }
}

// Key points carried through a wild camera motion may collapse into one point or leave the
// finite numbers; following them finds no hand instead of ending the tracker with an error.
TEST_F(RealPair, FollowingCollapsedOrNonFiniteKeyPointsFindsNoHand)
{
    gc::HandFinder finder;
    const cv::Mat& bgr = frame(0, 200);
    std::array<cv::Point2f, 21> points;
    points.fill(cv::Point2f(320.0f, 240.0f));
    EXPECT_FALSE(finder.follow(bgr, points).has_value());
    points = *reference(0, 200);
    points[0].x = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(finder.follow(bgr, points).has_value());
    EXPECT_TRUE(finder.follow(bgr, *reference(0, 200)).has_value());
}

TEST_F(RealPair, NoPalmBeforeTheHandComesIntoView)
{
    for (int i = 0; i < kEmptyFrames; ++i) {
        ASSERT_FALSE(reference(0, i).has_value()) << "frame " << i;
        EXPECT_TRUE(palm_->detect(frame(0, i), kMinPalmScore).empty()) << "frame " << i;
    }
}

// The hand painted over with the frame's mean colour: no palm, and the landmark model at the
// hand's own crop reports no hand.
TEST_F(RealPair, BlankedHandGivesNoPalmAndNoPresence)
{
    for (int view = 0; view < 2; ++view) {
        for (int i : {100, 200}) {
            SCOPED_TRACE("view " + std::to_string(view) + " frame " + std::to_string(i));
            const std::array<cv::Point2f, 21>& ref = *reference(view, i);
            gc::HandKeyPoints hand;
            hand.points = ref;
            const gc::HandCrop crop = gc::crop_from_landmarks(hand);
            const gc::HandKeyPoints before = landmarks_->run(frame(view, i), crop);
            ASSERT_GE(before.presence, kMinPresence) << "the unblanked hand is not found";
            cv::Mat blanked = frame(view, i).clone();
            const cv::Rect hand_box = cv::boundingRect(std::vector<cv::Point2f>(ref.begin(), ref.end()));
            const int margin = 40;
            const cv::Rect cover = (hand_box + cv::Point(-margin, -margin) + cv::Size(2 * margin, 2 * margin)) &
                                   cv::Rect(0, 0, blanked.cols, blanked.rows);
            blanked(cover).setTo(cv::mean(blanked));
            EXPECT_TRUE(palm_->detect(blanked, kMinPalmScore).empty());
            EXPECT_LT(landmarks_->run(blanked, crop).presence, kMinPresence);
        }
    }
}

// A plain random texture holds no hand: no palm, and a centred crop reports none.
TEST_F(RealPair, TextureGivesNoPalmAndNoPresence)
{
    cv::Mat texture(720, 720, CV_8UC3);
    cv::RNG rng(7);
    rng.fill(texture, cv::RNG::UNIFORM, cv::Scalar::all(0), cv::Scalar::all(256));
    cv::GaussianBlur(texture, texture, cv::Size(0, 0), 3.0);
    EXPECT_TRUE(palm_->detect(texture, kMinPalmScore).empty());
    EXPECT_LT(landmarks_->run(texture, gc::HandCrop{{360.0f, 360.0f}, 300.0f, 0.0f}).presence, kMinPresence);
}

// The crop from a hand's points holds the whole hand, turned so that its wrist is below
// its middle knuckle.
TEST_F(RealPair, LandmarkCropHoldsTheHandUpright)
{
    for (int view = 0; view < 2; ++view) {
        gc::HandKeyPoints hand;
        hand.points = *reference(view, 100);
        const gc::HandCrop crop = gc::crop_from_landmarks(hand);
        for (const cv::Point2f& p : hand.points) EXPECT_TRUE(crop_contains(crop, p)) << p;
        cv::Matx23f to_crop;
        cv::invertAffineTransform(gc::crop_to_frame(crop, 1), to_crop);
        const cv::Vec2f wrist = to_crop * cv::Vec3f(hand.points[0].x, hand.points[0].y, 1.0f);
        const cv::Vec2f knuckle = to_crop * cv::Vec3f(hand.points[9].x, hand.points[9].y, 1.0f);
        EXPECT_LT(knuckle[1], wrist[1] - 0.1f);
        EXPECT_NEAR(knuckle[0], wrist[0], 1e-3f);
    }
}

TEST(HandModelFiles, BothModelsLoadFromTheSourceTree)
{
    EXPECT_NO_THROW(gc::PalmDetector{gc::find_model(gc::kPalmModelFile)});
    EXPECT_NO_THROW(gc::LandmarkModel{gc::find_model(gc::kLandmarkModelFile)});
}

// Expects `make` to throw std::runtime_error whose message names `path`.
template <typename Make>
void expect_refused_naming(const fs::path& path, Make make)
{
    try {
        make();
        ADD_FAILURE() << "no error for " << path;
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
}

fs::path scratch_dir(const std::string& name)
{
    const fs::path dir = fs::temp_directory_path() / ("gesturecam_models_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

TEST(HandModelFiles, TruncatedModelIsRefusedWithItsPath)
{
    const fs::path dir = scratch_dir("truncated");
    const fs::path source = gc::find_model(gc::kPalmModelFile);
    const fs::path cut = dir / gc::kPalmModelFile;
    {
        std::ifstream in(source, std::ios::binary);
        std::vector<char> bytes(fs::file_size(source) / 2);
        in.read(bytes.data(), std::streamsize(bytes.size()));
        std::ofstream(cut, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    }
    expect_refused_naming(cut, [&] { gc::PalmDetector{cut}; });
    fs::remove_all(dir);
}

TEST(HandModelFiles, MissingModelIsRefusedWithItsPath)
{
    const fs::path missing = scratch_dir("missing") / gc::kLandmarkModelFile;
    expect_refused_naming(missing, [&] { gc::LandmarkModel{missing}; });
    fs::remove_all(missing.parent_path());
}

TEST(HandModelFiles, TheOtherNetworkIsRefusedWithItsPath)
{
    const fs::path landmark_model = gc::find_model(gc::kLandmarkModelFile);
    expect_refused_naming(landmark_model, [&] { gc::PalmDetector{landmark_model}; });
}

// A named folder, then GESTURECAM_MODEL_DIR, is the only place looked at: a model missing
// there is reported there, not taken silently from the source tree.
TEST(HandModelFiles, NamedFolderAndEnvironmentComeFirst)
{
    const fs::path dir = scratch_dir("named");
    expect_refused_naming(dir / gc::kPalmModelFile, [&] { gc::find_model(gc::kPalmModelFile, dir); });
    fs::copy_file(gc::find_model(gc::kPalmModelFile), dir / gc::kPalmModelFile);
    EXPECT_EQ(gc::find_model(gc::kPalmModelFile, dir), dir / gc::kPalmModelFile);

    ASSERT_EQ(::setenv(gc::kModelDirEnv, dir.c_str(), 1), 0);
    EXPECT_EQ(gc::find_model(gc::kPalmModelFile), dir / gc::kPalmModelFile);
    expect_refused_naming(dir / gc::kLandmarkModelFile, [&] { gc::find_model(gc::kLandmarkModelFile); });
    ::unsetenv(gc::kModelDirEnv);
    EXPECT_NE(gc::find_model(gc::kLandmarkModelFile).parent_path(), dir);
    fs::remove_all(dir);
}

}  // namespace

// A dark crop is brought up to a normal exposure for the models, at most 3 times brighter;
// a normally exposed one, and an empty one, are left as they are.
TEST(DarkImageGain, BrightensOnlyDarkImages)
{
    cv::Mat1b grey;
    cv::Mat3b image(64, 64, cv::Vec3b(20, 20, 20));
    image(cv::Rect(0, 0, 64, 16)).setTo(cv::Vec3b(85, 85, 85));  // a quarter brighter: the 95th percentile
    EXPECT_NEAR(gc::dark_image_gain(image, grey), double(gc::kExposedBrightEnd) / 85.0, 1e-9);
    image.setTo(cv::Vec3b(10, 10, 10));
    EXPECT_DOUBLE_EQ(gc::dark_image_gain(image, grey), gc::kMaxDarkGain);
    image.setTo(cv::Vec3b(60, 60, 60));
    image(cv::Rect(0, 0, 64, 16)).setTo(cv::Vec3b(200, 200, 200));
    EXPECT_DOUBLE_EQ(gc::dark_image_gain(image, grey), 1.0);
    EXPECT_DOUBLE_EQ(gc::dark_image_gain(cv::Mat3b(), grey), 1.0);
}

// A dark room with a blown-out window in view is still a dark room: the window's white is
// left out of the exposure, whatever share of the picture it takes; a picture that is all
// window is left as it is.
TEST(DarkImageGain, LeavesBlownOutPixelsOutOfTheExposure)
{
    cv::Mat1b grey;
    cv::Mat3b image(64, 64, cv::Vec3b(20, 20, 20));
    image(cv::Rect(0, 0, 64, 16)).setTo(cv::Vec3b(85, 85, 85));
    image(cv::Rect(0, 48, 64, 16)).setTo(cv::Vec3b(255, 255, 255));  // a quarter is window
    EXPECT_NEAR(gc::dark_image_gain(image, grey), double(gc::kExposedBrightEnd) / 85.0, 1e-9);
    image(cv::Rect(0, 48, 64, 16)).setTo(cv::Vec3b(249, 249, 249));  // bright, but not blown out
    EXPECT_DOUBLE_EQ(gc::dark_image_gain(image, grey), 1.0);
    image.setTo(cv::Vec3b(255, 255, 255));
    EXPECT_DOUBLE_EQ(gc::dark_image_gain(image, grey), 1.0);
}
