// The learned models' part in the tracker: the palm detector finds the hand (any pose, any
// background), its key points shape the first template and teach the skin model; while the
// contour is tracked, the landmark model checks it now and then, gives the key points and
// the gesture, and starts the contour again where it has drifted off the hand. Between its
// checks the contour's state carries the key points.
#include "tracker/hand_tracker_impl.hpp"

#include "measure/edge_search.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace gc {

namespace {

// Mean key-point distance to the landmark model's, in palm sizes (wrist to middle
// knuckle), above which the contour has left the hand and starts again from the models.
constexpr double kDriftedError = 0.35;
// ... below which the contour agrees with the models and the next check may wait longer.
constexpr double kAgreedError = 0.12;
// Without a hand, the palm detector looks at every frame for this many frames, then at
// every kSlowSearchEvery-th: an empty room costs less.
constexpr int kEagerSearchFrames = 15;
constexpr int kSlowSearchEvery = 3;
// The square the palm detector searches around what moved: this many times the moving box's
// longer side, at least kMovedRegionLeast pixels, and searched only when the whole frame is at
// least kMovedRegionGain times its side (else the whole frame's search has seen it as well).
constexpr double kMovedRegionMargin = 1.25;
constexpr int kMovedRegionLeast = 160;
constexpr double kMovedRegionGain = 1.25;
// The share of a hand found there that must lie on the moving blob.
constexpr double kMovedShare = 0.5;
// The contour's fingertip is reported when it lies within this angle of the key points'
// index direction and at most this many times their tip's distance from the palm.
constexpr double kContourTipAngle = 20.0 * std::numbers::pi / 180.0;
constexpr double kContourTipReach = 2.5;
// ... and when the skin model sees skin on at least this share of the way from their tip to it.
constexpr double kContourTipSkin = 0.7;
// How far a key point the optical flow followed may lie from where the contour's state
// placed it, in palm sizes.
constexpr double kFlowReach = 0.3;
// How far past the wrist key point the template's region runs, in palm sizes, and how wide,
// in palm widths (thumb to little-finger knuckle): as wide as the heel of the palm, which the
// wrist key point may lie above (docs/adr/0034).
constexpr double kWristReach = 0.6;
constexpr double kWristWidth = 1.2;
// A template the hand has outgrown is made again only once it has been tracked this many
// frames: where camera noise keeps the contour's confidence low, remakes on every check
// would each be made of that frame's noise (docs/adr/0047).
constexpr int kLeastRemadeAge = 4;
// The closing that joins the found hand's skin across small gaps, in pixels.
constexpr int kHandCloseSize = 5;
// The width of the line along each bone whose pixels teach the skin model, in finger widths.
constexpr double kSureBoneWidth = 0.15;

// The bones drawn between key points (MediaPipe's hand topology).
constexpr int kBones[][2] = {{0, 1},   {1, 2},   {2, 3},   {3, 4},   {0, 5},   {5, 6},   {6, 7},
                             {7, 8},   {5, 9},   {9, 10},  {10, 11}, {11, 12}, {9, 13},  {13, 14},
                             {14, 15}, {15, 16}, {13, 17}, {17, 18}, {18, 19}, {19, 20}, {0, 17}};
constexpr int kPalmOutline[] = {0, 1, 5, 9, 13, 17};
// The index finger's key points: knuckle, the two joints, tip.
constexpr int kIndexKnuckle = 5, kIndexTip = 8;

double palm_size(const std::array<cv::Point2f, 21>& p) { return cv::norm(p[9] - p[0]); }

// A finger's width in pixels, drawn as a line: about a third of the palm's size.
int finger_width(const std::array<cv::Point2f, 21>& p) { return std::max(3, cvRound(0.32 * palm_size(p))); }

std::vector<cv::Point> palm_polygon(const std::array<cv::Point2f, 21>& p)
{
    std::vector<cv::Point> palm;
    for (const int i : kPalmOutline) palm.emplace_back(cvRound(p[i].x), cvRound(p[i].y));
    std::vector<cv::Point> hull;
    cv::convexHull(palm, hull);
    return hull;
}

bool touches_border(const cv::Mat1b& mask)
{
    const cv::Rect box = cv::boundingRect(mask);
    return box.x <= 1 || box.y <= 1 || box.br().x >= mask.cols - 1 || box.br().y >= mask.rows - 1;
}

// Whether the frame's border cuts the index finger: a template without the finger's end
// cannot tell where it points.
bool index_finger_cut(const std::array<cv::Point2f, 21>& p, cv::Size size)
{
    cv::Mat1b finger(size, uchar(0));
    for (int i = kIndexKnuckle; i < kIndexTip; ++i) cv::line(finger, p[i], p[i + 1], 255, finger_width(p), cv::LINE_8);
    return touches_border(finger);
}

// The palm filled and every bone drawn as a line `bone_width` pixels wide.
cv::Mat1b palm_and_bones(const std::array<cv::Point2f, 21>& p, cv::Size size, int bone_width)
{
    cv::Mat1b mask(size, uchar(0));
    cv::fillConvexPoly(mask, palm_polygon(p), 255);
    for (const auto& bone : kBones) cv::line(mask, p[bone[0]], p[bone[1]], 255, bone_width, cv::LINE_8);
    return mask;
}

// The pixels surely on the hand, to learn its colours from: the palm and a thin line along
// each bone (a sixth of a finger's width), so the fingers' shading is learnt too without the
// background between them (docs/adr/0033).
cv::Mat1b surely_hand(const std::array<cv::Point2f, 21>& p, cv::Size size)
{
    return palm_and_bones(p, size, std::max(1, cvRound(kSureBoneWidth * finger_width(p))));
}

// Where the hand may be: the palm filled and every bone drawn as thick as a finger.
cv::Mat1b hand_region(const std::array<cv::Point2f, 21>& p, cv::Size size)
{
    cv::Mat1b region = palm_and_bones(p, size, finger_width(p));
    // The heel of the palm and the wrist beyond its key point: a sleeve or the end of the
    // skin ends it in the mask, so the outline closes where the hand's silhouette does.
    const cv::Point2f away = (p[0] - p[9]) * float(kWristReach);
    const int wide = std::max(3, cvRound(kWristWidth * cv::norm(p[17] - p[1])));
    cv::line(region, p[0], p[0] + away, 255, wide, cv::LINE_8);
    return region;
}

// Where a template made from `region` reads the skin map: the region's box, widened by the
// mask's closing, the outline's snap to the skin edge and its bilinear reads (1 px).
cv::Rect around_region(const cv::Mat1b& region)
{
    const int margin = kHandCloseSize / 2 + int(std::ceil(TemplateOptions{}.snap_range)) + 1;
    const cv::Rect box = cv::boundingRect(region);
    const cv::Rect wide(box.x - margin, box.y - margin, box.width + 2 * margin, box.height + 2 * margin);
    return wide & cv::Rect(0, 0, region.cols, region.rows);
}

// The skin of the region's connected part that holds the palm centre; empty if the skin
// model does not see most of the region as skin (then the region itself stands in).
cv::Mat1b skin_of_hand(const cv::Mat1b& region, const cv::Mat1b& membership, cv::Point palm)
{
    cv::Mat1b mask = (membership >= kSkinEdgeLevel) & region;
    cv::morphologyEx(mask, mask, cv::MORPH_CLOSE,
                     cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(kHandCloseSize, kHandCloseSize)));
    cv::Mat1i labels;
    cv::connectedComponents(mask, labels, 8, CV_32S);
    const cv::Rect frame(0, 0, mask.cols, mask.rows);
    const int label = palm.inside(frame) ? labels(palm) : 0;
    if (label == 0) return {};
    mask = labels == label;
    if (cv::countNonZero(mask) < 0.5 * cv::countNonZero(region)) return {};
    return mask;
}

// The share of the pixels on the line from `a` to `b` that the skin model sees as skin, among
// those inside `roi` (where `membership` holds this frame's); 0 when none is.
double skin_share_along(const cv::Mat1b& membership, const cv::Rect& roi, cv::Point2f a, cv::Point2f b)
{
    int seen = 0, skin = 0;
    cv::LineIterator line(membership, cv::Point(cvRound(a.x), cvRound(a.y)), cv::Point(cvRound(b.x), cvRound(b.y)));
    for (int i = 0; i < line.count; ++i, ++line) {
        if (!roi.contains(line.pos())) continue;
        ++seen;
        skin += **line >= kSkinEdgeLevel;
    }
    return seen > 0 ? double(skin) / seen : 0.0;
}

// The template point that `s` places at `p` (the inverse of place()).
cv::Point2f unplace(const HandState& s, const cv::Point2f& p)
{
    const double dx = (p.x - s.x) / s.squash, dy = p.y - s.y;
    const double c = std::cos(s.rotation), sn = std::sin(s.rotation);
    return {float((c * dx + sn * dy) / s.scale), float((-sn * dx + c * dy) / s.scale)};
}

}  // namespace

// No hand is tracked: the palm detector looks (every frame at first, then less often), and
// a hand it finds with key points the landmark model confirms becomes the template. The
// thesis's detector proposes a waving skin-coloured blob, which the landmark model, given
// the blob's palm and fingertip, confirms or not: this finds hands the palm detector misses
// (a dark hand against clutter, a hand seen edge-on) without trusting colour and motion
// alone. Where it moved, the palm detector looks once more at a larger scale.
void HandTracker::Impl::search_with_models(const cv::Mat& bgr)
{
    const int turn = search_turn++;
    const SkinModel prior = skin ? *skin : SkinModel::generic();
    const auto moved = detector.process(bgr, prior, true, static_scene(bgr, true, {}));
    const std::optional<FoundHand> proposed = moved ? confirm_detection(bgr, *moved) : std::nullopt;
    if (turn >= kEagerSearchFrames && turn % kSlowSearchEvery != 0 && !proposed) return;
    estimate.models_ran = true;
    std::optional<FoundHand> hand = finder->find(bgr);
    if (!hand) hand = proposed;
    if (!hand && moved) hand = search_where_it_moved(bgr, *moved);
    if (hand && adopt_found(bgr, *hand)) search_turn = 0;
}

// The palm detector on a square around what moved: larger there than in the whole frame, a
// hand it missed in the whole frame is often found (docs/adr/0037). Nothing when the square
// would be nearly the whole frame.
std::optional<FoundHand> HandTracker::Impl::search_where_it_moved(const cv::Mat& bgr, const Detection& moved)
{
    const int side = std::min(
        std::min(bgr.cols, bgr.rows),
        std::max(kMovedRegionLeast, cvRound(kMovedRegionMargin * std::max(moved.box.width, moved.box.height))));
    if (kMovedRegionGain * side > std::max(bgr.cols, bgr.rows)) return std::nullopt;
    const cv::Point centre = (moved.box.tl() + moved.box.br()) / 2;
    const cv::Rect region(std::clamp(centre.x - side / 2, 0, bgr.cols - side),
                          std::clamp(centre.y - side / 2, 0, bgr.rows - side), side, side);
    const std::optional<FoundHand> hand = finder->find_in(bgr, region);
    if (!hand) return std::nullopt;
    // The hand must be what moved: a face beside a moving arm settles as well as a hand.
    const cv::Mat1b where = hand_region(hand->points, bgr.size());
    const int area = cv::countNonZero(where);
    if (area == 0 || cv::countNonZero(where & moved.mask) < kMovedShare * area) return std::nullopt;
    return hand;
}

// The landmark model's word on a moving skin blob, given the blob's palm and fingertip.
std::optional<FoundHand> HandTracker::Impl::confirm_detection(const cv::Mat& bgr, const Detection& found)
{
    HandLandmarks shape_points;
    try {
        shape_points = find_hand_landmarks(found.mask, found.motion);
    } catch (const std::invalid_argument&) {
        return std::nullopt;
    }
    estimate.models_ran = true;
    return finder->confirm(bgr, cv::Point2f(shape_points.palm), cv::Point2f(shape_points.fingertip));
}

// A tracked frame: the landmark model checks the contour when the check is due, the edges
// are weak, or the caller is in doubt (the view changed under it, the flow bent the
// finger). No hand where the contour is: lost. Key points far from where the contour
// carried them: a new template from this frame. Else the key points and gesture are the
// model's, re-expressed on the template, and the next check waits longer while the two agree.
void HandTracker::Impl::check_with_models(const cv::Mat& bgr, bool in_doubt)
{
    ++frames_since_check;
    const bool doubt = in_doubt || estimate.confidence < params.lost_ratio;
    if (!doubt && frames_since_check < check_interval) return;
    frames_since_check = 0;
    estimate.models_ran = true;
    std::array<cv::Point2f, 21> carried;
    std::copy(estimate.landmarks.begin(), estimate.landmarks.end(), carried.begin());
    // A look that disagrees with the carried points looks again (docs/adr/0031).
    std::optional<FoundHand> hand = finder->follow(bgr, carried, kAgreedError);
    if (!hand) hand = finder->find(bgr);
    if (!hand) {
        lose();
        return;
    }
    const double error = key_point_move(carried, hand->points);
    if (error > kDriftedError) {
        if (!adopt_found(bgr, *hand)) lose();
        return;
    }
    // A template made of a hand the border cut is made again once the hand is whole in view.
    if (template_cut && !touches_border(hand_region(hand->points, bgr.size())) && adopt_found(bgr, *hand)) return;
    const int interval = error < kAgreedError ? std::min(2 * check_interval, params.max_model_interval) : 1;
    // Edges that fit far worse than when the template was made, on a hand whose key points
    // the model confirms: the real hand has turned or flexed out of the rigid outline, and
    // low confidence would call a check on every frame. The template is made again from
    // this hand (P_init measured again) and the schedule goes on (docs/adr/0047).
    const bool outgrown = !in_doubt && estimate.confidence < params.lost_ratio && error < kAgreedError &&
                          tracked_frames >= kLeastRemadeAge;
    if (!outgrown || !adopt_found(bgr, *hand, TrackStart::SameHand))
        for (std::size_t i = 0; i < key_points.size(); ++i) key_points[i] = unplace(previous, hand->points[i]);
    check_interval = interval;
    take_gesture(hand->gesture);
    report(previous);
}

// A gesture one check reads differently from the last is taken when the next check, a frame
// later, reads it too (docs/adr/0038): one check's misreading would otherwise hold until the
// next check, up to max_model_interval frames.
void HandTracker::Impl::take_gesture(Gesture read)
{
    if (read == gesture || read == new_gesture) {
        gesture = read;
        new_gesture.reset();
        return;
    }
    new_gesture = read;
    check_interval = 1;
}

// A template from a hand the models found: the skin model learnt from its palm, the mask
// the skin inside the region its key points span. False (nothing changed) when the border
// cuts the index finger or no template can be made of it; a hand entering from the border
// (its wrist or palm cut) is taken as far as it is in view. The same hand made again keeps
// its motion noise and its gesture, which the check then reads as any check does (twice
// before a change is taken).
bool HandTracker::Impl::adopt_found(const cv::Mat& bgr, const FoundHand& hand, TrackStart start)
{
    if (index_finger_cut(hand.points, bgr.size())) return false;
    const cv::Mat1b region = hand_region(hand.points, bgr.size());
    SkinModel model = SkinModel::generic();
    try {
        model = SkinModel::fit(bgr, surely_hand(hand.points, bgr.size()));
    } catch (const std::invalid_argument&) {
        return false;  // too few or too uniform palm pixels to learn from
    }
    cv::Mat1b membership_map(bgr.size(), uchar(0));
    model.membership(bgr, around_region(region), membership_map);
    const cv::Point centre = palm_centre(hand.points);
    cv::Mat1b mask = skin_of_hand(region, membership_map, centre);
    if (mask.empty()) mask = region;
    std::optional<HandTemplate> shaped;
    try {
        shaped = HandTemplate::from_mask(mask, membership_map, TemplateOptions{}, bgr);
    } catch (const std::invalid_argument&) {
        return false;
    }
    const HandState at{shaped->origin_px.x, shaped->origin_px.y, 0.0, 1.0};
    for (std::size_t i = 0; i < key_points.size(); ++i) key_points[i] = unplace(at, hand.points[i]);
    has_key_points = true;
    template_cut = touches_border(region);
    if (start == TrackStart::NewHand) {
        gesture = hand.gesture;
        new_gesture.reset();
    }
    frames_since_check = 0;
    check_interval = 1;
    adopt(std::move(*shaped), model, CaptureQuality::Clean, at, start);
    estimate.models_ran = true;
    return true;
}

// estimate.landmarks: the template's key points placed by `s`; the fingertip and palm
// reported are theirs (index tip; mean of wrist and knuckles).
void HandTracker::Impl::place_key_points(const HandState& s)
{
    estimate.landmarks.resize(key_points.size());
    std::array<cv::Point2f, 21> placed;
    for (std::size_t i = 0; i < key_points.size(); ++i)
        placed[i] = estimate.landmarks[i] = cv::Point2f(place(s, key_points[i]));
    estimate.palm = palm_centre(placed);
    estimate.fingertip = placed[8];
    // The contour's own fingertip (its extreme point along the finger) is where the
    // silhouette ends, which the key points only estimate: it is taken when the hand points
    // and it lies the way the key points' index finger points, no nearer the palm than their
    // tip. A rigid contour keeps the finger it was made with after the index has curled. One
    // that slid along the finger onto the background (camera noise gives it edges everywhere)
    // ends where the skin does not go: the skin must run from their tip to it (docs/adr/0039).
    if (gesture != Gesture::Pointing) return;
    const cv::Point2f by_contour = cv::Point2f(place(s, shape->fingertip)) - estimate.palm;
    const cv::Point2f by_points = placed[8] - estimate.palm;
    const double along = by_contour.dot(by_points), points_length = cv::norm(by_points);
    const double contour_length = cv::norm(by_contour);
    if (!(points_length > 0.0 && contour_length >= points_length &&
          contour_length <= kContourTipReach * points_length &&
          along >= std::cos(kContourTipAngle) * contour_length * points_length))
        return;
    const cv::Point2f tip = placed[8] + (by_contour - by_points);
    if (skin_share_along(membership, membership_roi, placed[8], tip) >= kContourTipSkin) estimate.fingertip = tip;
}

// The key points the contour placed on this frame, moved to where optical flow followed
// them from the last frame, and re-expressed on the template so the contour carries them on.
// True when the flow took the index finger beyond the contour's reach.
bool HandTracker::Impl::carry_key_points(const cv::Mat& bgr)
{
    if (!has_key_points || estimate.landmarks.size() != KeyPointFlow::kPoints) return false;
    KeyPointFlow::Points points;
    std::copy(estimate.landmarks.begin(), estimate.landmarks.end(), points.begin());
    std::array<bool, KeyPointFlow::kPoints> moved;
    const KeyPointFlow::Points placed = points;
    flow.carry(bgr, points, moved);
    // A point the flow took farther from where the contour put it than a finger can bend
    // is not taken: it slid onto something else, or, on the index finger, the finger bent
    // against the rigid contour, which the landmark model then checks.
    const double reach = kFlowReach * palm_size(placed);
    bool bent = false;
    for (std::size_t i = 0; i < key_points.size(); ++i) {
        if (!moved[i]) continue;
        if (cv::norm(points[i] - placed[i]) <= reach)
            key_points[i] = unplace(previous, points[i]);
        else if (int(i) > kIndexKnuckle && int(i) <= kIndexTip)
            bent = true;  // the finger bent or swung against the rigid contour
    }
    report(previous);
    return bent;
}

// After the frame: its key points are where the next frame's flow starts.
void HandTracker::Impl::keep_key_points(const cv::Mat& bgr, bool carried)
{
    if (estimate.state != TrackState::Tracking || !has_key_points ||
        estimate.landmarks.size() != KeyPointFlow::kPoints) {
        flow.forget();
        return;
    }
    KeyPointFlow::Points points;
    std::copy(estimate.landmarks.begin(), estimate.landmarks.end(), points.begin());
    if (carried)
        flow.replace_points(points);  // carry() kept this frame already
    else
        flow.keep(bgr, points);
}

}  // namespace gc
