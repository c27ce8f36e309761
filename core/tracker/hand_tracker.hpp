// One eye's CONDENSATION hand tracker: acquisition by a learned palm detector (or, in the
// thesis's mode, by motion + skin), then factored sampling over (x, y, rotation, scale) with
// a skin-edge measurement along the contour normals, checked now and then by a learned
// landmark model that also gives the hand's key points and gesture.
#pragma once

#include "common/types.hpp"

#include <opencv2/core.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace gc {

// How a hand is found and checked. Learned: the palm detector finds it anywhere and the
// landmark model confirms it, gives its key points and gesture, and re-seeds the contour.
// Motion: the thesis's detection of a waving skin-coloured blob, nothing learned.
enum class HandDetector { Learned, Motion };

struct TrackerParams {
    int particles = 1000;     // N, the sample-set size (>= 1)
    std::uint64_t seed = 1;   // same seed + same frames = same output
    double lost_ratio = 0.6;  // lost when every likelihood < lost_ratio * P_init
    int lost_frames = 3;      // ... for this many consecutive frames
    bool adapt_skin = true;   // update the skin mean from inside the tracked contour
    // Learn the static scene: captures leave out its skin, and in front of skin the hand is
    // told from the scene behind it.
    bool use_static_scene = true;
    HandDetector detector = HandDetector::Learned;
    std::string model_dir;       // learned models' folder; empty: found without configuration
    int max_model_interval = 8;  // frames between landmark checks while the contour agrees
    // PointingTracker: frames wider than this are tracked scaled down to it (aspect kept),
    // their results given in the frame's pixels; 0 tracks every frame at its own size.
    int tracking_width = 0;
};

// A weighted hypothesis, exposed for drawing the marginal distributions.
struct Particle {
    HandState state;
    double weight = 0.0;
};

class HandTracker {
public:
    // Throws std::runtime_error when the learned models cannot be loaded.
    explicit HandTracker(const TrackerParams& params = {});
    ~HandTracker();
    HandTracker(HandTracker&&) noexcept;
    HandTracker& operator=(HandTracker&&) noexcept;

    // Processes one frame (CV_8UC3, BGR, any size >= 32x32; the size must stay the same
    // until reset()). `camera_motion` is C_t: the image motion the head caused since the
    // previous frame. Throws std::invalid_argument on an empty or wrongly typed frame.
    const EyeEstimate& process(const cv::Mat& bgr, const ImageMotion& camera_motion = {});

    // Forgets the hand: the next frame starts acquisition again.
    void reset();

    const EyeEstimate& estimate() const;
    std::span<const Particle> particles() const;
    const TrackerParams& params() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace gc
