#include "tracker/rim_survey.hpp"

#include "measure/contour_measurement.hpp"
#include "measure/edge_search.hpp"

namespace gc {

namespace {

constexpr double kRimSkinFraction = 0.85;           // inner rim this much skin: the hand is there;
constexpr double kLooseRimSkinFraction = 0.75;      // ... or this much, with the finger's at 0.85
constexpr double kRimDepth = 2.5;                   // px along the normals, in or out: the contour's rims
constexpr double kForegroundRimSkinFraction = 0.5;  // a contour on what moved: this much rim skin,
constexpr double kMovedFraction = 0.5;              // this much of it known to differ from the scene,
constexpr double kMaxSceneInsideFraction = 0.15;    // at most this much of it the scene,
constexpr double kSceneOutsideFraction = 0.5;       // and this much of the outer rim matching it

}  // namespace

RimSurvey survey_rim(const HandTemplate& t, const HandState& s, const cv::Mat1b& membership,
                     const StaticBackground* scene, const cv::Mat& bgr)
{
    RimSurvey rim;
    rim.points = static_cast<int>(t.outline.size());
    const cv::Rect frame(0, 0, membership.cols, membership.rows);
    for (std::size_t i = 0; i < t.outline.size(); ++i) {
        const cv::Point2d p = place(s, t.outline[i]);
        const cv::Point2d n = kRimDepth * place_normal(s, t.outline_normals[i]);
        const cv::Point in(cvRound(p.x - n.x), cvRound(p.y - n.y));
        const bool inside = in.inside(frame);
        rim.in_view = rim.in_view && inside;
        const bool skin = inside && membership(in) >= kSkinEdgeLevel;
        rim.skin += skin;
        if (t.on_finger(t.outline[i])) {
            ++rim.finger;
            rim.finger_skin += skin;
        }
        if (!scene) continue;
        if (inside) {
            const StaticBackground::Look look = scene->look(bgr, in);
            rim.moved += look == StaticBackground::Look::Foreground;
            rim.scene += look == StaticBackground::Look::Scene;
        }
        const cv::Point out(cvRound(p.x + n.x), cvRound(p.y + n.y));
        if (out.inside(frame)) {
            const StaticBackground::Look look = scene->look(bgr, out);
            rim.scene_outside += look == StaticBackground::Look::Scene || look == StaticBackground::Look::Unsure;
        }
    }
    return rim;
}

// Nearly all of the rim above the boundary level, or most of it with nearly all of the
// finger's. The hand's own rim falls short mostly along the creases of the curled fingers;
// a contour turned or slid off the hand keeps most of the palm's rim but not the finger's,
// and the finger carries the direction. A contour cut by the image border is held to the
// first rule: there the rim is missing for want of image, and a hand pushed to the border
// by the head's turn is better found again whole.
bool rim_is_skin(const RimSurvey& rim)
{
    const double all = double(rim.skin) / rim.points;
    const double finger = rim.finger > 0 ? double(rim.finger_skin) / rim.finger : 0.0;
    return all >= kRimSkinFraction || (rim.in_view && all >= kLooseRimSkinFraction && finger >= kRimSkinFraction);
}

// Just inside the contour, at least half known to differ from the scene and hardly any of
// it the scene; just outside it, at least half matching the scene (a point next to
// something that does not, Unsure, counts: the outer rim runs 1.5 px from the hand's edge,
// and along the wrist it borders the moving arm). In front of a face, skin cannot tell the
// hand from the face behind it, and a hand turned away from the rigid template shows less
// of the template's rim; the scene can. A contour slid onto the face has the face, the
// scene, inside it; one shrunk or slid within the hand and arm has them outside it.
// Without a learnt scene the counts are 0 and this is false.
bool outlines_foreground(const RimSurvey& rim)
{
    const double points = rim.points;
    return rim.skin >= kForegroundRimSkinFraction * points && rim.moved >= kMovedFraction * points &&
           rim.scene <= kMaxSceneInsideFraction * points && rim.scene_outside >= kSceneOutsideFraction * points;
}

}  // namespace gc
