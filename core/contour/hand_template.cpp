#include "contour/hand_template.hpp"

#include "measure/edge_search.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace gc {

namespace {

constexpr double kMinHandArea = 120.0;  // pixels; below this there is no finger to see
// An outline point this close (pixels) to a recently changed pixel moved with the hand.
constexpr int kTipMotionReach = 3;

double norm(const cv::Point2d& p) { return std::hypot(p.x, p.y); }

// Circular Gaussian smoothing of a pixel chain: removes the staircase of the raster outline
// before points are taken from it.
std::vector<cv::Point2d> smooth_ring(const std::vector<cv::Point>& ring, double sigma)
{
    const int n = static_cast<int>(ring.size());
    const int half = std::max(1, static_cast<int>(std::ceil(2.5 * sigma)));
    std::vector<double> kernel(2 * half + 1);
    for (int k = -half; k <= half; ++k) kernel[k + half] = std::exp(-0.5 * k * k / (sigma * sigma));
    const double total = std::accumulate(kernel.begin(), kernel.end(), 0.0);
    std::vector<cv::Point2d> out(n);
    for (int i = 0; i < n; ++i) {
        cv::Point2d acc(0, 0);
        for (int k = -half; k <= half; ++k) {
            const cv::Point& q = ring[((i + k) % n + n) % n];
            acc += kernel[k + half] * cv::Point2d(q.x, q.y);
        }
        out[i] = acc * (1.0 / total);
    }
    return out;
}

// Distance to the outline of each pixel inside it (holes filled), over `box` (the
// outline's bounding box) with a one-pixel margin: pixel (x, y) is at (x - box.x + 1, y - box.y + 1).
cv::Mat1f inside_distance(const std::vector<cv::Point>& outline, const cv::Rect& box)
{
    cv::Mat1b filled(box.height + 2, box.width + 2, uchar(0));
    std::vector<std::vector<cv::Point>> one{outline};
    cv::drawContours(filled, one, 0, 255, cv::FILLED, cv::LINE_8, cv::noArray(), 0, cv::Point(1 - box.x, 1 - box.y));
    cv::Mat1f dist;
    cv::distanceTransform(filled, dist, cv::DIST_L2, cv::DIST_MASK_5);
    return dist;
}

// Whether a pixel of the shape (`mask`) within kTipMotionReach of `p` changed recently
// (`motion`). Changes outside the shape do not count: there a moving sleeve or arm may
// pass the end of a static thing merged with the hand.
bool moved_near(const cv::Mat& mask, const cv::Mat1b& motion, const cv::Point& p)
{
    const cv::Rect around(p.x - kTipMotionReach, p.y - kTipMotionReach, 2 * kTipMotionReach + 1,
                          2 * kTipMotionReach + 1);
    const cv::Rect r = around & cv::Rect(0, 0, motion.cols, motion.rows);
    for (int y = r.y; y < r.br().y; ++y) {
        const uchar* m = motion.ptr<uchar>(y);
        const uchar* in = mask.ptr<uchar>(y);
        for (int x = r.x; x < r.br().x; ++x)
            if (m[x] && in[x]) return true;
    }
    return false;
}

}  // namespace

HandLandmarks find_hand_landmarks(const cv::Mat& mask, const cv::Mat1b& motion)
{
    if (mask.empty()) throw std::invalid_argument("hand template: empty mask");
    if (!motion.empty() && motion.size() != mask.size())
        throw std::invalid_argument("hand template: motion map size differs from mask size");
    if (mask.type() != CV_8UC1)
        throw std::invalid_argument("hand template: mask must be CV_8UC1, got " + std::to_string(mask.channels()) +
                                    " channel(s)");
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    if (contours.empty()) throw std::invalid_argument("hand template: mask has no shape");
    const auto largest = std::max_element(contours.begin(), contours.end(),
                                          [](auto& a, auto& b) { return cv::contourArea(a) < cv::contourArea(b); });
    const double area = cv::contourArea(*largest);
    if (area < kMinHandArea)
        throw std::invalid_argument("hand template: shape of " + std::to_string(int(area)) + " px is too small (need " +
                                    std::to_string(int(kMinHandArea)) + ")");
    HandLandmarks lm;
    lm.outline = std::move(*largest);

    // The palm is the thickest part: the maximum of the distance transform of the filled
    // outline (holes filled, so a shadowed spot on the palm cannot move it).
    const cv::Rect box = cv::boundingRect(lm.outline);
    const cv::Mat1f dist = inside_distance(lm.outline, box);
    double max_dist = 0.0;
    cv::Point at;
    cv::minMaxLoc(dist, nullptr, &max_dist, nullptr, &at);
    lm.palm = cv::Point2d(at.x - 1 + box.x, at.y - 1 + box.y);
    lm.palm_radius = max_dist;

    // The index fingertip: the outline point farthest from the palm, skipping points that
    // touch the image border (a forearm leaving the frame, or a hand cut off by it). With a
    // motion map, only points where the shape changed along most of the outline around
    // them (a palm radius either way) count, if any: the waving finger sweeps, while a
    // static skin-coloured thing merged with the hand does not (but for a few pixels where
    // an arm passes it), and its far end would otherwise pass for the finger.
    const int w = mask.cols, h = mask.rows;
    const int n = static_cast<int>(lm.outline.size());
    std::vector<int> moved_before;  // moved_before[i]: moved points among outline[0, i)
    if (!motion.empty()) {
        moved_before.resize(n + 1, 0);
        for (int i = 0; i < n; ++i) moved_before[i + 1] = moved_before[i] + moved_near(mask, motion, lm.outline[i]);
    }
    const int half = std::clamp(static_cast<int>(lm.palm_radius), 1, std::max(1, (n - 1) / 2));
    auto mostly_moved = [&](int i) {  // over outline[i - half, i + half], circularly
        const int lo = i - half, hi = i + half + 1;
        int moved = 0;
        if (lo < 0)
            moved = moved_before[hi] + moved_before[n] - moved_before[n + lo];
        else if (hi > n)
            moved = moved_before[n] - moved_before[lo] + moved_before[hi - n];
        else
            moved = moved_before[hi] - moved_before[lo];
        return 2 * moved > 2 * half + 1;
    };
    double best = -1.0, best_moving = -1.0;
    cv::Point2d moving_tip;
    for (int i = 0; i < n; ++i) {
        const cv::Point& p = lm.outline[i];
        if (p.x <= 0 || p.y <= 0 || p.x >= w - 1 || p.y >= h - 1) continue;
        const double d = norm(cv::Point2d(p) - lm.palm);
        if (d > best) {
            best = d;
            lm.farthest = cv::Point2d(p);
        }
        if (!moved_before.empty() && d > best_moving && mostly_moved(i)) {
            best_moving = d;
            moving_tip = cv::Point2d(p);
        }
    }
    if (best < 0.0) throw std::invalid_argument("hand template: shape lies entirely on the image border");
    lm.fingertip = best_moving >= 0.0 ? moving_tip : lm.farthest;
    return lm;
}

namespace {

// Points along the smoothed outline by arc length, the step shrinking on the finger:
// there the curve must be faithful, and more normals there weight the orientation.
std::vector<cv::Point2d> outline_points(const HandLandmarks& lm, double reach, const TemplateOptions& options)
{
    const std::vector<cv::Point2d> ring = smooth_ring(lm.outline, 1.2);
    const int n = static_cast<int>(ring.size());
    double perimeter = 0.0;
    for (int i = 0; i < n; ++i) perimeter += norm(ring[(i + 1) % n] - ring[i]);
    const double palm_step = std::max(2.0, perimeter / options.palm_points);
    const double finger_step = std::max(1.5, palm_step / options.finger_density);
    const double finger_zone = kFingerZone * reach;  // around the tip: the index finger
    auto on_finger = [&](const cv::Point2d& p) { return norm(p - lm.fingertip) < finger_zone; };

    std::vector<cv::Point2d> through;
    double travelled = 0.0, next = 0.0;
    for (int i = 0; i < n; ++i) {
        const cv::Point2d& a = ring[i];
        const cv::Point2d& b = ring[(i + 1) % n];
        const double seg = norm(b - a);
        while (next <= travelled + seg && seg > 0.0) {
            const cv::Point2d p = a + (b - a) * ((next - travelled) / seg);
            through.push_back(p);
            next += on_finger(p) ? finger_step : palm_step;
        }
        travelled += seg;
    }
    // The last point must not nearly coincide with the first one on the ring.
    while (through.size() > 4 && norm(through.back() - through.front()) < 0.5 * finger_step) through.pop_back();
    if (through.size() < 8) throw std::invalid_argument("hand template: outline too short to model");
    return through;
}

// Sub-pixel snapping to the skin boundary of the image, so the template sits where the
// measurement will look for edges (the raster outline is half a pixel inside).
void snap_to_skin_edge(std::vector<cv::Point2d>& through, const cv::Mat1b& membership, const cv::Mat& bgr,
                       double snap_range)
{
    const ClosedBSpline rough = ClosedBSpline::interpolate(through);
    for (std::size_t i = 0; i < through.size(); ++i) {
        const cv::Point2d nrm = rough.outward_normal(double(i));
        double off = 0.0;
        if (find_skin_edge_precise(membership, through[i], nrm, snap_range, 0.25, off))
            through[i] += colour_edge_offset(bgr, through[i], nrm, off) * nrm;
    }
    for (std::size_t i = 0; i + 1 < through.size();) {  // snapping may merge neighbours
        if (norm(through[i + 1] - through[i]) < 0.3)
            through.erase(through.begin() + i + 1);
        else
            ++i;
    }
}

// `count` points of the template's spline evenly in its parameter, with their outward
// normals and weights (the finger's weighted by `finger_weight`, all summing to 1).
void sample_spline(const HandTemplate& t, int count, double finger_weight, std::vector<cv::Point2f>& pts,
                   std::vector<cv::Point2f>& nrms, std::vector<float>& wts)
{
    const int knots = t.spline.size();
    pts.resize(count);
    nrms.resize(count);
    wts.resize(count);
    double total = 0.0;
    for (int k = 0; k < count; ++k) {
        const double u = double(k) * knots / count;
        const cv::Point2d p = t.spline.point(u);
        pts[k] = cv::Point2f(p);
        nrms[k] = cv::Point2f(t.spline.outward_normal(u));
        wts[k] = static_cast<float>(t.on_finger(pts[k]) ? finger_weight : 1.0);
        total += wts[k];
    }
    for (float& w : wts) w = static_cast<float>(w / total);
}

}  // namespace

HandTemplate HandTemplate::from_mask(const cv::Mat& mask, const cv::Mat1b& membership, const TemplateOptions& options,
                                     const cv::Mat& bgr, const cv::Mat1b& motion)
{
    if (options.measurement_normals < 8 || options.outline_points < 16 || options.palm_points < 8 ||
        !(options.finger_density >= 1.0) || !(options.finger_weight > 0.0) || !(options.snap_range >= 0.0))
        throw std::invalid_argument("hand template: invalid options");
    if (!membership.empty() && membership.size() != mask.size())
        throw std::invalid_argument("hand template: membership map size differs from mask size");
    const HandLandmarks lm = find_hand_landmarks(mask, motion);
    const double reach = norm(lm.fingertip - lm.palm);
    if (reach < 1.5 * lm.palm_radius || reach < 6.0)
        throw std::invalid_argument("hand template: no finger protrudes from the palm");

    std::vector<cv::Point2d> through = outline_points(lm, reach, options);
    if (!membership.empty() && options.snap_range > 0.0)
        snap_to_skin_edge(through, membership, bgr, options.snap_range);

    HandTemplate t;
    t.origin_px = lm.palm;
    t.palm_radius = lm.palm_radius;
    for (auto& p : through) p -= lm.palm;
    t.spline = ClosedBSpline::interpolate(through);
    t.fingertip = cv::Point2f(lm.fingertip - lm.palm);
    sample_spline(t, options.measurement_normals, options.finger_weight, t.points, t.normals, t.weights);
    sample_spline(t, options.outline_points, options.finger_weight, t.outline, t.outline_normals, t.outline_weights);
    return t;
}

HandProportions hand_proportions(const cv::Mat& mask, const cv::Mat1b& motion)
{
    HandProportions out;
    HandLandmarks lm;
    try {
        lm = find_hand_landmarks(mask, motion);
    } catch (const std::invalid_argument&) {
        return out;
    }
    const cv::Rect box = cv::boundingRect(lm.outline);
    const cv::Mat1f dist = inside_distance(lm.outline, box);
    double widest = 0.0;
    for (int k = 0; k <= 8; ++k) {
        const cv::Point2d p = lm.palm + (0.55 + 0.05 * k) * (lm.fingertip - lm.palm);
        const int x = cvRound(p.x) - box.x + 1, y = cvRound(p.y) - box.y + 1;
        if (x >= 0 && y >= 0 && x < dist.cols && y < dist.rows) widest = std::max(widest, double(dist(y, x)));
    }
    const double r = std::max(1.0, lm.palm_radius);
    out.finger_width = widest / r;
    out.reach = norm(lm.fingertip - lm.palm) / r;
    out.farthest_moved = norm(lm.farthest - lm.fingertip) <= r;
    out.valid = true;
    return out;
}

}  // namespace gc
