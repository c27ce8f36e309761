// The real stereo pair of tests/data/handpose3d: its frames and MediaPipe's reference
// landmarks per view (view 0 = cam0 = left, view 1 = cam1 = right), shared by the tests of
// the learned hand models and of the gesture classifier.
#pragma once

#include "tools/real_pair.hpp"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

#include <array>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace gc_test {

inline constexpr int kRealPairFrames = 378;
// The frames where the hand points with the index finger (both views).
inline constexpr int kFirstPointingFrame = 14;
inline constexpr int kLastPointingFrame = 212;

inline bool is_pointing_frame(int i) { return i >= kFirstPointingFrame && i <= kLastPointingFrame; }

inline std::filesystem::path source_root()
{
    const char* root = std::getenv("GESTURECAM_SOURCE_ROOT");
    EXPECT_NE(root, nullptr) << "GESTURECAM_SOURCE_ROOT is not set (meson test sets it)";
    return root != nullptr ? std::filesystem::path(root) : std::filesystem::path(".");
}

inline std::filesystem::path real_pair_file(int view, const std::string& suffix)
{
    return source_root() / "tests" / "data" / "handpose3d" / ("handpose3d_cam" + std::to_string(view) + suffix);
}

// MediaPipe's 21 points of a frame, in pixels, or nothing where it found no hand.
using ReferenceHand = std::optional<std::array<cv::Point2f, 21>>;

// frames[i].landmarks of the view's reference, read as gesturecam-bench reads them.
inline std::vector<ReferenceHand> load_reference(int view)
{
    std::vector<ReferenceHand> hands;
    for (const gc::tools::ReferenceHand& read :
         gc::tools::read_reference_hands(real_pair_file(view, ".mediapipe.json").string())) {
        if (!read) {
            hands.emplace_back();
            continue;
        }
        std::array<cv::Point2f, 21> hand;
        for (int k = 0; k < 21; ++k) hand[k] = cv::Point2f(float((*read)[k].x), float((*read)[k].y));
        hands.emplace_back(hand);
    }
    return hands;
}

// Decodes a whole view with cv::VideoCapture, frame i being the i-th decoded frame, and
// keeps the frames listed.
struct DecodedView {
    int frame_count = 0;
    std::map<int, cv::Mat> frames;
};

inline DecodedView decode_view(int view, const std::set<int>& keep)
{
    cv::VideoCapture video(real_pair_file(view, ".mp4").string());
    EXPECT_TRUE(video.isOpened()) << "cannot open " << real_pair_file(view, ".mp4");
    DecodedView decoded;
    cv::Mat frame;
    while (video.read(frame)) {
        if (keep.count(decoded.frame_count) != 0) decoded.frames[decoded.frame_count] = frame.clone();
        ++decoded.frame_count;
    }
    return decoded;
}

}  // namespace gc_test
