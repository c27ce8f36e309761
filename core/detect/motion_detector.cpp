#include "detect/motion_detector.hpp"

#include "contour/hand_template.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace gc {

namespace {

constexpr int kHistBins = 64;  // per normalised channel, for the moving pixels' colours
// Half width of the brightness band around the mode of the moving skin-coloured pixels, as
// a fraction of it: wide enough for the shading across a hand (sd 6-13 % of the mean).
constexpr double kModeBandFraction = 0.3;
// The largest brightness standard deviation, as a fraction of the mean, that shading
// across one hand gives: moving pixels spread wider include a static object of the hand's
// chromaticity but not its brightness (docs/adr/0003). Hand edges mixed with a dark
// background stay below it.
constexpr double kMaxShadingSpread = 0.25;
// Static-scene skin cleared within 2 px of a blob, as a fraction of its area, beyond which
// the blob was cut off that skin (a hand in front of a plain background has none).
constexpr double kStaticCutFraction = 0.01;
// Thin strands: the opening's diameter, in radii of the blob's largest inscribed circle (the
// palm's). A finger is about 0.45 of it wide (17-20 mm against a palm radius of about 40),
// so the opening keeps it with a margin and drops strands up to two thirds of its width.
constexpr double kStrandOpening = 0.3;
// The blob is left whole when the opening would keep less than this share of it (strands
// are thin and carry little area: more means the hand itself was cut) or would leave more
// than kStrandPieces pieces (a ragged blob, skin split along shading on the first frames,
// which the opening crumbles).
constexpr double kStrandKeep = 0.75;
constexpr int kStrandPieces = 3;

void check_frame(const cv::Mat& bgr)
{
    if (bgr.empty()) throw std::invalid_argument("MotionDetector: empty frame");
    if (bgr.type() != CV_8UC3)
        throw std::invalid_argument("MotionDetector: expected CV_8UC3 (BGR), got " + std::to_string(bgr.channels()) +
                                    " channel(s)");
}

// Normalised colour cannot tell the hand from a static object of its skin tone, and
// moving pixels include some of such an object (where the arm or hand uncovers it); its
// brightness mostly differs. Keeps the `pixels` (non-zero) whose brightness R + G + B lies
// near the mode of theirs, so the hand's band is learnt from the hand.
void keep_brightness_mode(const cv::Mat& bgr, cv::Mat1b& pixels)
{
    constexpr int kBinWidth = 8;
    constexpr int kBins = 766 / kBinWidth + 1;
    cv::Mat wide, brightness;  // brightness: R + G + B, 16-bit (it reaches 765)
    bgr.convertTo(wide, CV_16U);
    cv::transform(wide, brightness, cv::Matx13f(1.0f, 1.0f, 1.0f));
    const int channels[] = {0};
    const int bins[] = {kBins};
    const float range[] = {0.0f, float(kBins * kBinWidth)};
    const float* ranges[] = {range};
    cv::Mat hist;
    cv::calcHist(&brightness, 1, channels, pixels, hist, 1, bins, ranges);
    // Smoothed by a [1 2 3 2 1] kernel so the mode is not a noise spike.
    const cv::Matx<float, 5, 1> kernel(1, 2, 3, 2, 1);
    cv::filter2D(hist, hist, -1, kernel, cv::Point(-1, -1), 0.0, cv::BORDER_CONSTANT);
    cv::Point mode;
    cv::minMaxLoc(hist, nullptr, nullptr, nullptr, &mode);
    const double centre = (mode.y + 0.5) * kBinWidth;
    const double half_width = std::max(kModeBandFraction * centre, 2.0 * kBinWidth);
    cv::Mat1b in_band;
    cv::inRange(brightness, cv::Scalar(std::ceil(centre - half_width)), cv::Scalar(std::floor(centre + half_width)),
                in_band);
    cv::bitwise_and(pixels, in_band, pixels);
}

// The skin colour of the moving pixels: the mode of their normalised-colour histogram
// (within a gate around the prior, weighted by it), then a Gaussian fitted to the pixels near the
// mode (near the mode of their brightness too, when their brightness is spread wider than
// a hand's shading), refitted once on the pixels it accepts.
std::optional<SkinModel> learn_skin(const cv::Mat& bgr, const cv::Mat1b& moving, const SkinModel& prior,
                                    double gate_sigma)
{
    const double gate2 = gate_sigma * gate_sigma;
    cv::Mat1f hist(kHistBins, kHistBins, 0.0f);
    cv::Mat1b candidates(bgr.size(), uchar(0));
    int total = 0;
    for (int y = 0; y < bgr.rows; ++y) {
        const auto* p = bgr.ptr<cv::Vec3b>(y);
        const auto* m = moving.ptr<std::uint8_t>(y);
        for (int x = 0; x < bgr.cols; ++x) {
            if (!m[x]) continue;
            const int sum = p[x][0] + p[x][1] + p[x][2];
            if (sum < prior.dark_threshold() || sum == 0) continue;
            const double r = p[x][2] / double(sum), g = p[x][1] / double(sum);
            const double d2 = prior.mahalanobis2(r, g);
            if (d2 > gate2) continue;
            // Weighted by the prior: grey and other weakly chromatic moving things (a sleeve,
            // uncovered wall) must outnumber the hand by far to take the mode.
            hist(std::min(int(g * kHistBins), kHistBins - 1), std::min(int(r * kHistBins), kHistBins - 1)) +=
                static_cast<float>(std::exp(-0.5 * d2));
            candidates(y, x) = 255;
            ++total;
        }
    }
    if (total < 30) return std::nullopt;
    cv::GaussianBlur(hist, hist, cv::Size(5, 5), 1.0);
    cv::Point mode;
    cv::minMaxLoc(hist, nullptr, nullptr, nullptr, &mode);
    const double mr = (mode.x + 0.5) / kHistBins, mg = (mode.y + 0.5) / kHistBins;
    // Seed: pixels within two bins of the mode.
    const double radius = 2.0 / kHistBins;
    cv::Mat1b near(bgr.size(), uchar(0));
    for (int y = 0; y < bgr.rows; ++y) {
        const auto* p = bgr.ptr<cv::Vec3b>(y);
        for (int x = 0; x < bgr.cols; ++x) {
            if (!candidates(y, x)) continue;
            const double sum = p[x][0] + p[x][1] + p[x][2];
            if (std::hypot(p[x][2] / sum - mr, p[x][1] / sum - mg) <= radius) near(y, x) = 255;
        }
    }
    try {
        SkinModel model = SkinModel::fit(bgr, near, prior.dark_threshold());
        // A brightness spread wider than shading gives: the moving pixels mix the hand with
        // a static object of its chromaticity. Learn from the hand's brightness mode only.
        const bool mixed = model.brightness_sd() > kMaxShadingSpread * model.brightness_mean();
        if (mixed) {
            keep_brightness_mode(bgr, near);
            model = SkinModel::fit(bgr, near, prior.dark_threshold());
        }
        cv::Mat1b accepted;
        model.segment(bgr, accepted);
        cv::bitwise_and(accepted, candidates, accepted);
        if (mixed) keep_brightness_mode(bgr, accepted);
        return SkinModel::fit(bgr, accepted, prior.dark_threshold());
    } catch (const std::invalid_argument&) {
        return std::nullopt;  // too few consistent pixels: not a hand
    }
}

// The largest 8-connected component of `mask` and its area (0 and an empty mask if none).
cv::Mat1b largest_component(const cv::Mat1b& mask, int& area)
{
    cv::Mat1i labels;
    cv::Mat stats, centroids;
    const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
    int keep = 0;
    area = 0;
    for (int i = 1; i < n; ++i)
        if (stats.at<int>(i, cv::CC_STAT_AREA) > area) {
            area = stats.at<int>(i, cv::CC_STAT_AREA);
            keep = i;
        }
    if (keep == 0) return {};
    return labels == keep;
}

// The dilation of `mask` by a centred `element`, kept within `where` (zero elsewhere). Only
// the pixels within the element's reach of `where` are read: a dilation of the whole frame
// by a wide disc costs as much as the rest of a detection, where only the blob's box is
// looked at.
cv::Mat1b dilated_within(const cv::Mat1b& mask, const cv::Mat& element, const cv::Rect& where)
{
    const cv::Rect frame(0, 0, mask.cols, mask.rows);
    const cv::Rect inner = where & frame;
    cv::Mat1b out(mask.size(), uchar(0));
    if (inner.area() == 0) return out;
    const int rx = element.cols / 2, ry = element.rows / 2;
    const cv::Rect wide = cv::Rect(inner.x - rx, inner.y - ry, inner.width + 2 * rx, inner.height + 2 * ry) & frame;
    cv::Mat1b grown;
    cv::dilate(mask(wide), grown, element);
    grown(inner - wide.tl()).copyTo(out(inner));
    return out;
}

// The label (1 to count - 1) holding the most `moving` pixels (a view of labels' size), or
// 0 when none holds any.
int most_moving_label(const cv::Mat1i& labels, int count, const cv::Mat1b& moving)
{
    std::vector<int> votes(count, 0);
    for (int y = 0; y < labels.rows; ++y) {
        const int* l = labels.ptr<int>(y);
        const std::uint8_t* m = moving.ptr<std::uint8_t>(y);
        for (int x = 0; x < labels.cols; ++x)
            if (m[x]) ++votes[l[x]];
    }
    votes[0] = 0;
    const int best = static_cast<int>(std::max_element(votes.begin(), votes.end()) - votes.begin());
    return votes[best] > 0 ? best : 0;
}

// Thin strands of the hand's colour touching it (a shelf's edge, a cable, a picture
// frame's rim) are joined to it by the close but are no part of it, and a template that
// keeps one finds no edge along it once the hand moves on. An opening narrower than the
// finger drops them; of what it leaves, the piece holding the most moving pixels is the
// hand, and dilating it by the same element within the blob gives back the outline the
// opening rounded (a strand keeps a root as long as the element is wide).
void drop_thin_strands(cv::Mat1b& blob, int& area, const cv::Mat1b& moving)
{
    const cv::Rect bound = cv::boundingRect(blob);
    if (bound.area() == 0) return;
    cv::Mat1b padded;
    cv::copyMakeBorder(blob(bound), padded, 1, 1, 1, 1, cv::BORDER_CONSTANT, 0);
    cv::Mat1f dist;
    cv::distanceTransform(padded, dist, cv::DIST_L2, cv::DIST_MASK_5);
    double palm_radius = 0.0;
    cv::minMaxLoc(dist, nullptr, &palm_radius);
    const int side = int(std::lround(kStrandOpening * palm_radius)) | 1;
    if (side < 3) return;
    const cv::Mat element = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(side, side));
    const cv::Rect around = cv::Rect(bound.x - side, bound.y - side, bound.width + 2 * side, bound.height + 2 * side) &
                            cv::Rect(0, 0, blob.cols, blob.rows);
    cv::Mat1b opened;
    cv::morphologyEx(blob(around), opened, cv::MORPH_OPEN, element);
    cv::Mat1i labels;
    const int count = cv::connectedComponents(opened, labels, 8, CV_32S);
    if (count < 2 || count - 1 > kStrandPieces) return;
    const int hand = most_moving_label(labels, count, moving(around));
    if (hand == 0) return;
    cv::Mat1b body = labels == hand;
    cv::dilate(body, body, element);
    cv::bitwise_and(body, blob(around), body);
    const int kept = cv::countNonZero(body);
    if (kept < kStrandKeep * area) return;
    body.copyTo(blob(around));  // outside `around` the blob is empty already
    area = kept;
}

// The frame's pixels of `skin` (colour and brightness band together: a face or an object of
// the hand's skin tone touching it is usually brighter or darker), closed; skin of the static
// scene is not the hand's, and what was cleared of it is returned in `cleared`.
cv::Mat1b skin_segments(const cv::Mat& bgr, const SkinModel& skin, const cv::Mat1b& static_scene, const cv::Mat& kernel,
                        cv::Mat1b& cleared)
{
    cv::Mat1b seg;
    skin.membership(bgr, cv::Rect(0, 0, bgr.cols, bgr.rows), seg);
    cv::threshold(seg, seg, 127, 255, cv::THRESH_BINARY);
    if (!static_scene.empty()) {
        cv::bitwise_and(seg, static_scene, cleared);
        seg.setTo(0, static_scene);
    }
    cv::morphologyEx(seg, seg, cv::MORPH_CLOSE, kernel);
    return seg;
}

// The blob as far as it moved lately. Cut only when a large part is static: a hand that
// barely moved keeps its palm. Until motion has been seen for a while, a mostly static blob is
// not trusted either way: false, wait for more of the hand to move.
bool keep_recent_motion(cv::Mat1b& blob, int& area, double& support, bool& cut, const cv::Mat1b& recent_motion,
                        bool history_mature, const DetectionParams& params, const cv::Mat& kernel)
{
    const int k = 2 * params.history_reach + 1;
    cv::Mat1b near = dilated_within(recent_motion, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(k, k)),
                                    cv::boundingRect(blob));
    cv::bitwise_and(near, blob, near);
    const int kept = cv::countNonZero(near);
    support = double(kept) / std::max(1, area);
    if (kept >= 0.75 * area) return true;
    if (!history_mature) return false;
    cv::morphologyEx(near, near, cv::MORPH_OPEN, kernel);
    int keep_area = 0;
    cv::Mat1b kept_part = largest_component(near, keep_area);
    if (keep_area == 0) return false;
    blob = kept_part;
    area = keep_area;
    cut = true;
    return true;
}

// A component that is still not shaped like a pointing hand (a touching object's remnant next
// to the finger or the palm) is cut closer to the motion: the neighbourhood shrinks until the
// shape is a pointing hand (holes filled, since the middle of the palm may not have changed),
// else the wider cut stands.
void cut_to_pointing_shape(cv::Mat1b& blob, int& area, bool& cut, const cv::Mat1b& component,
                           const cv::Rect& component_box, const cv::Mat1b& recent_motion, const DetectionParams& params,
                           const cv::Mat& kernel)
{
    for (const int reach : {params.history_reach * 2 / 3, params.history_reach / 3}) {
        if (reach < 2) break;
        cv::Mat1b near = dilated_within(
            recent_motion, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * reach + 1, 2 * reach + 1)),
            component_box);
        cv::bitwise_and(near, component, near);
        std::vector<std::vector<cv::Point>> outer;
        cv::findContours(near, outer, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
        cv::drawContours(near, outer, -1, 255, cv::FILLED);
        cv::bitwise_and(near, component, near);
        cv::morphologyEx(near, near, cv::MORPH_OPEN, kernel);
        int keep_area = 0;
        cv::Mat1b candidate = largest_component(near, keep_area);
        if (keep_area == 0) break;
        if (!hand_proportions(candidate, recent_motion).pointing()) continue;
        blob = candidate;
        area = keep_area;
        cut = true;
        break;
    }
}

// A blob that static skin was cleared off (more than a sliver along its outline) is not known
// to be the hand alone: its outline there is the cut, not the hand's.
bool touches_cleared_skin(const cv::Mat1b& blob, int area, const cv::Mat1b& cleared)
{
    const cv::Rect frame(0, 0, blob.cols, blob.rows);
    const cv::Rect around = cv::Rect(cv::boundingRect(blob) - cv::Point(2, 2) + cv::Size(4, 4)) & frame;
    cv::Mat1b near;
    cv::dilate(blob(around), near, cv::Mat(), cv::Point(-1, -1), 2);
    cv::bitwise_and(near, cleared(around), near);
    return cv::countNonZero(near) > kStaticCutFraction * area;
}

}  // namespace

std::optional<Detection> segment_hand(const cv::Mat& bgr, const cv::Mat1b& moving, const cv::Rect& box,
                                      const SkinModel& prior, const DetectionParams& params,
                                      const cv::Mat1b& recent_motion, bool history_mature,
                                      const cv::Mat1b& static_scene)
{
    check_frame(bgr);
    if (moving.size() != bgr.size() || moving.type() != CV_8UC1)
        throw std::invalid_argument("segment_hand: moving-pixel mask must be CV_8UC1 of the frame size");
    if (!static_scene.empty() && static_scene.size() != bgr.size())
        throw std::invalid_argument("segment_hand: the static-scene mask must have the frame's size");
    const cv::Rect roi = box & cv::Rect(0, 0, bgr.cols, bgr.rows);
    if (roi.area() == 0) return std::nullopt;
    auto skin = learn_skin(bgr(roi), moving(roi), prior, params.prior_gate_sigma);
    if (!skin) return std::nullopt;
    // Segment the whole frame: the moving pixels may be only the waving fingers, and the
    // hand must not be cut at the box. The hand is the skin component holding the most
    // moving pixels.
    const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(params.close_size, params.close_size));
    cv::Mat1b cleared;
    const cv::Mat1b seg = skin_segments(bgr, *skin, static_scene, kernel, cleared);
    cv::Mat1i labels;
    cv::Mat stats, centroids;
    const int count = cv::connectedComponentsWithStats(seg, labels, stats, centroids, 8, CV_32S);
    if (count < 2) return std::nullopt;
    const int best = most_moving_label(labels(roi), count, moving(roi));
    if (best == 0) return std::nullopt;
    cv::Mat1b blob = labels == best;
    int area = stats.at<int>(best, cv::CC_STAT_AREA);
    drop_thin_strands(blob, area, moving);
    double support = 1.0;
    bool cut = false;
    const bool has_history = !recent_motion.empty() && recent_motion.size() == bgr.size();
    const cv::Mat1b motion = has_history ? recent_motion : cv::Mat1b();
    if (has_history && !keep_recent_motion(blob, area, support, cut, recent_motion, history_mature, params, kernel))
        return std::nullopt;
    if (has_history && history_mature && !hand_proportions(blob, motion).pointing()) {
        const cv::Rect component_box(stats.at<int>(best, cv::CC_STAT_LEFT), stats.at<int>(best, cv::CC_STAT_TOP),
                                     stats.at<int>(best, cv::CC_STAT_WIDTH), stats.at<int>(best, cv::CC_STAT_HEIGHT));
        cut_to_pointing_shape(blob, area, cut, labels == best, component_box, recent_motion, params, kernel);
    }
    if (!cleared.empty() && !cut && touches_cleared_skin(blob, area, cleared)) cut = true;
    if (area < params.min_hand_area || area > params.max_hand_fraction * double(bgr.rows) * bgr.cols)
        return std::nullopt;
    // The history changes with the next frame; the detection keeps the present one.
    Detection d{blob, roi, *skin, double(area), support, cut, motion.clone()};
    // Refit on the whole blob: the moving pixels were only part of the hand.
    try {
        d.skin = SkinModel::fit(bgr, d.mask, prior.dark_threshold());
    } catch (const std::invalid_argument&) {
    }
    return d;
}

CaptureQuality capture_quality(const Detection& d)
{
    if (!hand_proportions(d.mask, d.motion).pointing()) return CaptureQuality::Unsure;
    return !d.cut && d.motion_support >= kCleanSupport ? CaptureQuality::Clean : CaptureQuality::Pointing;
}

MotionDetector::MotionDetector(const DetectionParams& params) : p_(params)
{
    if (p_.diff_threshold < 1 || p_.diff_threshold > 254 || p_.min_changed_pixels < 1 || p_.box_margin < 0 ||
        p_.close_size < 1 || p_.close_size % 2 == 0 || p_.min_hand_area < 1 ||
        !(p_.max_hand_fraction > 0.0 && p_.max_hand_fraction <= 1.0) || !(p_.prior_gate_sigma > 0.0) ||
        p_.history_frames < 1 || p_.history_frames > 250 || p_.history_reach < 0)
        throw std::invalid_argument("MotionDetector: invalid detection parameters");
}

int frame_noise_threshold(const cv::Mat1b& difference)
{
    // Every 4th pixel of every 4th row: a VGA frame gives 19200 samples.
    constexpr int kStride = 4;
    std::array<int, 256> histogram{};
    int samples = 0;
    for (int y = 0; y < difference.rows; y += kStride) {
        const std::uint8_t* row = difference.ptr<std::uint8_t>(y);
        for (int x = 0; x < difference.cols; x += kStride, ++samples) ++histogram[row[x]];
    }
    if (samples == 0) return 0;
    // The quartile of the integer differences below `limit`, interpolated within its level
    // (level k stands for the values in [k - 0.5, k + 0.5)), as the threshold it gives.
    // A frame that changed almost everywhere (a cut, a source starting) gives a first
    // estimate past the last level: the second pass then counts every level.
    const auto threshold_below = [&](int limit) {
        limit = std::min(limit, 256);
        int counted = 0;
        for (int k = 0; k < limit; ++k) counted += histogram[k];
        if (counted == 0) return 0;
        const double target = 0.25 * counted;
        double below = 0.0;
        int level = 0;
        while (below + histogram[level] < target) below += histogram[level++];
        const double quartile = std::max(0.0, level - 0.5 + (target - below) / histogram[level]);
        return static_cast<int>(std::ceil(3.0 * quartile / 0.3186));
    };
    // Pixels that really changed push the quartile up: once more without those above the
    // first estimate (the noise leaves 0.3 % there).
    return threshold_below(threshold_below(256) + 1);
}

void MotionDetector::reset()
{
    primed_ = false;
    motion_frames_ = 0;
}

const cv::Mat1b& MotionDetector::recent_motion() const
{
    static const cv::Mat1b none;
    return primed_ ? history_ : none;
}

std::optional<Detection> MotionDetector::process(const cv::Mat& bgr, const SkinModel& prior, bool segment,
                                                 const cv::Mat1b& static_scene)
{
    check_frame(bgr);
    if (!static_scene.empty() && static_scene.size() != bgr.size())
        throw std::invalid_argument("MotionDetector: the static-scene mask must have the frame's size");
    if (!difference(bgr) || !segment) return std::nullopt;
    return segment_last(bgr, prior, static_scene);
}

bool MotionDetector::difference(const cv::Mat& bgr)
{
    check_frame(bgr);
    cv::cvtColor(bgr, grey_, cv::COLOR_BGR2GRAY);
    if (!primed_ || previous_.size() != grey_.size()) {
        grey_.copyTo(previous_);
        history_.create(grey_.size());
        history_.setTo(0);
        changed_.create(grey_.size());
        changed_.setTo(0);
        motion_frames_ = 0;
        primed_ = true;
        return false;
    }
    cv::absdiff(grey_, previous_, changed_);
    grey_.copyTo(previous_);
    // No morphological opening: a slowly waving hand changes only thin strips along its
    // edges, and the threshold alone leaves just a handful of noise pixels.
    const int threshold = std::max(p_.diff_threshold, frame_noise_threshold(changed_));
    cv::threshold(changed_, changed_, threshold, 255, cv::THRESH_BINARY);
    cv::subtract(history_, cv::Scalar::all(1), history_);  // saturates at 0
    history_.setTo(p_.history_frames, changed_);
    if (cv::countNonZero(changed_) < p_.min_changed_pixels) {
        motion_frames_ = 0;
        return false;
    }
    ++motion_frames_;
    return true;
}

std::optional<Detection> MotionDetector::segment_last(const cv::Mat& bgr, const SkinModel& prior,
                                                      const cv::Mat1b& static_scene) const
{
    if (motion_frames_ == 0 || changed_.size() != bgr.size()) return std::nullopt;
    cv::Rect box = cv::boundingRect(changed_);
    box.x -= p_.box_margin;
    box.y -= p_.box_margin;
    box.width += 2 * p_.box_margin;
    box.height += 2 * p_.box_margin;
    box &= cv::Rect(0, 0, bgr.cols, bgr.rows);
    return segment_hand(bgr, changed_, box, prior, p_, history_, motion_frames_ >= p_.history_frames, static_scene);
}

int MotionDetector::changed_outside(const cv::Rect& box) const
{
    const cv::Rect inside = box & cv::Rect(0, 0, changed_.cols, changed_.rows);
    const int all = changed_.empty() ? 0 : cv::countNonZero(changed_);
    return inside.empty() ? all : all - cv::countNonZero(changed_(inside));
}

}  // namespace gc
