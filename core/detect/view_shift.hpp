// Whether the whole view moved since the previous frame, with nobody saying so: a PTZ head
// moved by someone else, a bumped tripod. Phase correlation of two small grey copies of
// consecutive frames gives the scene's shift; a hand moving in front of a still scene
// covers too little of the frame to make a confident peak away from zero.
#pragma once

#include <opencv2/core.hpp>

namespace gc {

// The view's change between the previous frame and this one, in frame pixels.
struct ViewChange {
    bool shifted = false;  // the scene moved as a whole, by (dx, dy)
    bool cut = false;      // the view changed too much to say how it moved
    double dx = 0.0;
    double dy = 0.0;
};

class ViewShift {
public:
    // Compares `bgr` (CV_8UC3) with the previous frame given; the first frame, or one of
    // another size, is compared with nothing. No allocation once the size is known.
    ViewChange update(const cv::Mat& bgr);
    void reset();

private:
    bool prepare(const cv::Mat& bgr);  // false when there is no previous frame to compare with
    bool has_previous_ = false;        // a frame of this size since the start or reset()

    cv::Mat half_bgr_, small_bgr_;
    cv::Mat1b small_grey_;
    cv::Mat1f plane_, window_, level_, previous_level_;
    cv::Mat2f spectrum_, previous_spectrum_, cross_;
    cv::Mat1f correlation_;
    double scale_ = 1.0;  // frame pixels per small pixel
};

}  // namespace gc
