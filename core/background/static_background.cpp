#include "background/static_background.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace gc {

StaticBackground::StaticBackground(const StaticBackgroundParams& params) : p_(params)
{
    if (p_.tolerance <= 0 || p_.tolerance >= 256 || p_.trusted_after <= 0 || p_.trusted_after >= 256)
        throw std::invalid_argument("StaticBackground: tolerance and trusted_after must be in 1..255");
}

void StaticBackground::reset()
{
    median_.release();
    trust_.release();
}

namespace {

// Whether a BGR pixel is within `tol` of the median on every channel.
inline bool matches(const std::uint8_t* f, const std::uint8_t* m, int tol)
{
    return std::max({std::abs(f[0] - m[0]), std::abs(f[1] - m[1]), std::abs(f[2] - m[2])}) <= tol;
}

}  // namespace

void StaticBackground::learn(const cv::Mat& bgr, const cv::Rect& keep_out, const cv::Mat1b& keep_out_mask)
{
    if (bgr.empty() || bgr.type() != CV_8UC3)
        throw std::invalid_argument("StaticBackground: expected a non-empty CV_8UC3 frame");
    if (!keep_out_mask.empty() && keep_out_mask.size() != keep_out.size())
        throw std::invalid_argument("StaticBackground: the keep-out mask must have the keep-out box's size");
    if (median_.size() != bgr.size()) {
        bgr.copyTo(median_);
        trust_ = cv::Mat3b(bgr.size(), cv::Vec3b(0, 0, 0));
        return;
    }
    const cv::Rect out = keep_out & cv::Rect(0, 0, bgr.cols, bgr.rows);
    const std::uint8_t tol = static_cast<std::uint8_t>(p_.tolerance);
    // Pixels [from, to) of a row, byte by byte (a pixel's trust is its channels' least):
    // trust counts up on a match and down on a miss, and where `step` the median moves one
    // level towards the frame. A branch-free byte loop, which vectorises (__restrict: byte
    // pointers may otherwise alias, which stops the vectoriser).
    const auto learn_run = [tol](const std::uint8_t* __restrict f, std::uint8_t* __restrict m,
                                 std::uint8_t* __restrict trust, int from, int to, bool step) {
        const std::uint8_t moves = step ? 1 : 0;
        for (int i = 3 * from; i < 3 * to; ++i) {
            const std::uint8_t a = f[i], b = m[i], t = trust[i];
            const bool match = std::uint8_t(std::max(a, b) - std::min(a, b)) <= tol;
            trust[i] = std::uint8_t(t + (match & (t != 255)) - (!match & (t != 0)));
            m[i] = std::uint8_t(b + moves * ((a > b) - (a < b)));
        }
    };
    // Every other row, the two halves in turn: each pixel learns every second frame, which
    // halves the cost (a pass over the median, the trust and the frame is memory-bound).
    for (int y = row_parity_; y < bgr.rows; y += 2) {
        const std::uint8_t* f = bgr.ptr<std::uint8_t>(y);
        std::uint8_t* m = median_.ptr<std::uint8_t>(y);
        std::uint8_t* trust = trust_.ptr<std::uint8_t>(y);
        if (out.area() == 0 || y < out.y || y >= out.y + out.height) {
            learn_run(f, m, trust, 0, bgr.cols, true);
            continue;
        }
        learn_run(f, m, trust, 0, out.x, true);
        learn_run(f, m, trust, out.x + out.width, bgr.cols, true);
        // Inside the box, the median is held where the mask is set (all of it without a
        // mask), while trust keeps counting against it: a static object the hand covers
        // is still known as the scene's.
        const std::uint8_t* mask = keep_out_mask.empty() ? nullptr : keep_out_mask.ptr<std::uint8_t>(y - keep_out.y);
        const auto held_at = [&](int x) { return !mask || mask[x - keep_out.x] != 0; };
        for (int x = out.x; x < out.x + out.width;) {
            const bool held = held_at(x);
            const int start = x;
            while (x < out.x + out.width && held_at(x) == held) ++x;
            learn_run(f, m, trust, start, x, !held);
        }
    }
    row_parity_ ^= 1;
}

StaticBackground::Look StaticBackground::look(const cv::Mat& bgr, cv::Point p) const
{
    if (median_.empty() || bgr.size() != median_.size() || bgr.type() != CV_8UC3) return Look::Unknown;
    const auto trusted = [this](int x, int y) {
        const cv::Vec3b& t = trust_(y, x);
        return std::min({t[0], t[1], t[2]}) >= p_.trusted_after;
    };
    const auto same = [&](int x, int y) {
        return matches(bgr.ptr<std::uint8_t>(y) + 3 * x, median_.ptr<std::uint8_t>(y) + 3 * x, p_.tolerance);
    };
    if (!trusted(p.x, p.y)) return Look::Unknown;
    if (!same(p.x, p.y)) return Look::Foreground;
    // The neighbours as find_static()'s erosion sees them (the border replicated).
    for (int y = std::max(p.y - 1, 0); y <= std::min(p.y + 1, bgr.rows - 1); ++y)
        for (int x = std::max(p.x - 1, 0); x <= std::min(p.x + 1, bgr.cols - 1); ++x)
            if (!trusted(x, y) || !same(x, y)) return Look::Unsure;
    return Look::Scene;
}

const cv::Mat1b& StaticBackground::find_static(const cv::Mat& bgr, const cv::Rect& roi)
{
    if (median_.empty() || bgr.size() != median_.size() || bgr.type() != CV_8UC3) return none_;
    const cv::Rect frame(0, 0, bgr.cols, bgr.rows);
    if (scene_.size() != median_.size()) {
        matches_.create(median_.size());
        scene_ = cv::Mat1b(median_.size(), uchar(0));
        scene_area_ = {};
    }
    if (scene_area_.area() > 0) scene_(scene_area_).setTo(0);
    const cv::Rect area = roi & frame;
    scene_area_ = area;
    if (area.area() == 0) return scene_;
    // The neighbour test needs the matches one pixel beyond the region.
    const cv::Rect wide = cv::Rect(area.x - 1, area.y - 1, area.width + 2, area.height + 2) & frame;
    const int tol = p_.tolerance, trusted = p_.trusted_after;
    for (int y = wide.y; y < wide.y + wide.height; ++y) {
        const std::uint8_t* f = bgr.ptr<std::uint8_t>(y) + 3 * wide.x;
        const std::uint8_t* m = median_.ptr<std::uint8_t>(y) + 3 * wide.x;
        const std::uint8_t* trust = trust_.ptr<std::uint8_t>(y) + 3 * wide.x;
        std::uint8_t* out = matches_.ptr<std::uint8_t>(y) + wide.x;
        for (int x = 0; x < wide.width; ++x, f += 3, m += 3, trust += 3)
            out[x] = std::min({trust[0], trust[1], trust[2]}) >= trusted && matches(f, m, tol) ? 255 : 0;
    }
    // Eroded within `wide` only (the matches beyond it are stale); then only `area` kept.
    cv::erode(matches_(wide), matches_(wide), cv::Mat(), cv::Point(-1, -1), 1,
              cv::BORDER_REPLICATE | cv::BORDER_ISOLATED);
    matches_(area).copyTo(scene_(area));
    return scene_;
}

}  // namespace gc
