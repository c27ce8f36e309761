// What the camera sees when nothing moves: a per-pixel running median of the frames, learnt
// everywhere but where the tracked hand is. Skin that matches it is skin of the scene (a
// face, a skin-coloured object), not the moving hand, and the detector leaves it out, so
// that a capture touching it is cut off at its outline.
//
// The median is approximated by stepping each channel one level towards the frame on every
// frame the pixel learns from (so it takes |change| of them to follow a change): a hand
// passing over a pixel, or waving over it half the time, does not move it. A pixel counts as the scene's when its
// median is trusted (the frame has matched it more often than not, by a margin: the first
// frame's median holds whatever was there, the hand included), the frame matches it now,
// and so do all its neighbours: sensor noise and the hand's texture passing over a similar
// colour do not punch holes in the hand.
#pragma once

#include <opencv2/core.hpp>

namespace gc {

struct StaticBackgroundParams {
    // Largest per-channel difference, in grey levels, between a frame pixel and the
    // median for it to be the scene's: about 4 sigma of a typical sensor's noise.
    int tolerance = 8;
    // Trust a pixel's median needs to be the scene's: matches minus misses, counted from
    // zero (never below it) and capped at 255, over the frames the pixel learnt from (every
    // second one: learn() steps every other row, the two halves in turn).
    int trusted_after = 8;
};

class StaticBackground {
public:
    // Throws std::invalid_argument unless 0 < tolerance < 256 and 0 < trusted_after < 256.
    explicit StaticBackground(const StaticBackgroundParams& params = {});

    // Steps the median towards `bgr` (CV_8UC3), on every other row (the other half on the
    // next call), everywhere but in `keep_out`, where it is held: all of it, or where
    // given, only where `keep_out_mask` (keep_out's size) is non-zero. Trust is counted
    // everywhere, against the held median too. The first frame after construction or
    // reset() becomes the median, untrusted; a frame of another size starts it again.
    // Throws std::invalid_argument on a wrong frame type or mask size.
    void learn(const cv::Mat& bgr, const cv::Rect& keep_out = {}, const cv::Mat1b& keep_out_mask = {});
    // Forgets the median (the camera moved: the scene is elsewhere in the image).
    void reset();
    bool empty() const { return median_.empty(); }

    // What the frame shows at one pixel, against the learnt scene.
    enum class Look {
        Unknown,     // no trusted median there (or no median, or another frame size)
        Scene,       // the scene: the pixel and its neighbours match their trusted medians
        Foreground,  // something in front of it: the pixel differs from its trusted median
        Unsure,      // trusted and matching, but a neighbour is not (noise, a chance match)
    };
    // As find_static() would say at `p`, and more: Unknown where it would say 0 for want
    // of a trusted median, Foreground where the median is trusted and the pixel differs.
    // `p` must lie in the frame.
    Look look(const cv::Mat& bgr, cv::Point p) const;

    // Where the frame `bgr` shows the static scene, over `roi`: a map of the frame's size,
    // 255 there and 0 elsewhere (valid until the next call). Empty before the first
    // learn() or when the frame's size or type differs. Reuses its buffers: no allocation
    // once they have the frame's size.
    const cv::Mat1b& find_static(const cv::Mat& bgr, const cv::Rect& roi);

private:
    StaticBackgroundParams p_;
    cv::Mat3b median_;
    cv::Mat3b trust_;            // per channel: matches minus misses, saturating at 0 and 255
    int row_parity_ = 0;         // the rows learn() steps next: even (0) or odd (1)
    cv::Mat1b matches_, scene_;  // per pixel: matches the median; and so do its neighbours
    cv::Rect scene_area_;        // where scene_ was last filled (0 elsewhere)
    cv::Mat1b none_;             // stays empty: the map returned where nothing is known
};

}  // namespace gc
