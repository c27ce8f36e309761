// Carries the landmark model's key points from one frame to the next by pyramidal
// Lucas-Kanade optical flow, so that between the model's checks the fingers follow the
// image, not only the contour's rigid motion.
#pragma once

#include <opencv2/core.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace gc {

class KeyPointFlow {
public:
    static constexpr std::size_t kPoints = 21;
    using Points = std::array<cv::Point2f, kPoints>;

    // `bgr` becomes the frame the next carry() starts from, with `points` on it.
    void keep(const cv::Mat& bgr, const Points& points);
    // Moves the kept points into `bgr`; `moved[i]` says whether point i was followed both
    // ways (forward, then back to within a pixel of where it started). `bgr` and the points
    // where they were followed become the kept ones.
    void carry(const cv::Mat& bgr, Points& points, std::array<bool, kPoints>& moved);
    // The kept frame stays; its points are replaced (the landmark model placed them anew).
    void replace_points(const Points& points) { kept_ = points; }
    void forget() { ready_ = false; }
    bool ready() const { return ready_; }
    const Points& kept_points() const { return kept_; }

private:
    // The pyramids cover only `area_`, a region around the points: the kept frame's
    // pyramid is built again from its grey image when the points near the region's edge.
    void place_area(const cv::Size& frame);

    bool ready_ = false;
    Points kept_{};
    cv::Rect area_;
    cv::Mat1b grey_, next_grey_;
    std::vector<cv::Mat> previous_, current_;
    std::vector<cv::Point2f> from_, to_, back_;
    std::vector<std::uint8_t> status_, back_status_;
    std::vector<float> error_;
};

}  // namespace gc
