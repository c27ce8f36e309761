// The learned hand models behind one interface: the palm detector finds a hand anywhere in
// a frame, the landmark model gives its 21 key points (MediaPipe's order: 0 wrist, 4 thumb
// tip, 8 index tip, 5/9/13/17 the knuckles) and says whether a hand is there at all.
#pragma once

#include "detect/gesture.hpp"

#include <opencv2/core.hpp>

#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <string>

namespace gc {

struct HandFinderParams {
    std::string model_dir;        // empty: found without configuration (model_files.hpp)
    float min_palm_score = 0.4f;  // palm detector's score to try a palm (docs/adr/0028)
    float min_presence = 0.5f;    // landmark model's hand presence to accept a hand
};

// A hand the models found: its key points in frame pixels and what it does.
struct FoundHand {
    std::array<cv::Point2f, 21> points;
    float presence = 0.0f;
    Gesture gesture = Gesture::Other;
};

// The palm centre as the product reports it: the mean of the wrist and the four knuckles.
cv::Point2f palm_centre(const std::array<cv::Point2f, 21>& points);

// The mean distance from one set of key points to another, in palm sizes of `to` (wrist to
// middle knuckle, at least 1 px): how far a hand's key points moved between two looks.
double key_point_move(const std::array<cv::Point2f, 21>& from, const std::array<cv::Point2f, 21>& to);

class HandFinder {
public:
    // Loads both models; throws std::runtime_error naming the file that is missing or bad.
    explicit HandFinder(const HandFinderParams& params = {});
    ~HandFinder();
    HandFinder(HandFinder&&) noexcept;
    HandFinder& operator=(HandFinder&&) noexcept;

    // Searches the whole frame (BGR): the palms the detector rates best (up to three), each
    // with its key points; the first whose key points settle well, else the one that settled best.
    std::optional<FoundHand> find(const cv::Mat& bgr);
    // The same search in one square region of the frame, such as where something moved: the
    // palm detector sees the region larger than the whole frame, and finds hands that are
    // small or unlike those it learnt from. Nothing when the region is empty.
    std::optional<FoundHand> find_in(const cv::Mat& bgr, const cv::Rect& region);
    // The key points of a hand known to be near `around` (last key points, moved to this
    // frame): the landmark model alone, on a crop taken from them. Key points that moved
    // `look_again_beyond` palm sizes or more from `around` are looked at once more through
    // their own crop (a finger that straightened fast may lie outside the first), and the
    // second look is kept if it settles: moves them less than the first look did.
    std::optional<FoundHand> follow(const cv::Mat& bgr, const std::array<cv::Point2f, 21>& around,
                                    double look_again_beyond = std::numeric_limits<double>::infinity());
    // The key points of a hand proposed by other means (a moving skin blob): its palm centre
    // and the tip of its longest finger, in frame pixels. The landmark model alone decides.
    std::optional<FoundHand> confirm(const cv::Mat& bgr, cv::Point2f palm, cv::Point2f fingertip);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace gc
