#include "sim/varied_room.hpp"

#include "sim/hand_model.hpp"
#include "sim/variety.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace gc::sim {

namespace {

constexpr double kPi = std::numbers::pi;

// A colour for any surface: sometimes of the skin's chromaticity (plaster, paint, wood), else
// any hue, grey included.
cv::Vec3f surface_colour(Rng& rng, const cv::Vec3f& skin, double skin_share)
{
    if (uniform(rng, 0, 1) < skin_share) return skin_like_colour(rng, skin, 280, 660);
    return non_skin_colour(rng, 0.25, 0.92, 0.6);
}

void paint(cv::Mat3b& img, const Layout& L, const cv::Vec3f& skin, Rng& rng, cv::RNG& cr)
{
    img.setTo(to_scalar(surface_colour(rng, skin, 0.45)));
    modulate(img, smooth_noise(img.size(), L.px(uniform(rng, 150, 600)), cr), uniform(rng, 0.02, 0.06));
}

void wood_panelling(cv::Mat3b& img, const Layout& L, const cv::Vec3f& skin, Rng& rng, cv::RNG& cr)
{
    // Vertical planks: grain along them, a dark gap between them.
    const int plank = L.px(uniform(rng, 90, 260));
    const bool skin_wood = uniform(rng, 0, 1) < 0.7;
    for (int x = 0; x < img.cols; x += plank) {
        const cv::Rect r(x, 0, std::min(plank, img.cols - x), img.rows);
        const cv::Vec3f c = skin_wood ? skin_like_colour(rng, skin, 200, 520) : non_skin_colour(rng, 0.2, 0.7, 0.3);
        cv::Mat3b board(r.width, r.height);  // transposed: the grain runs along x there
        board.setTo(to_scalar(c));
        grain(board, std::max(2.0, double(L.px(uniform(rng, 6, 20)))), uniform(rng, 0.05, 0.15), rng, cr);
        cv::Mat3b upright = img(r);
        cv::transpose(board, upright);
        fill(img, {x, 0, std::max(1, L.px(4)), img.rows}, c, 0.45);
    }
}

void brick(cv::Mat3b& img, const Layout& L, const cv::Vec3f& skin, Rng& rng, cv::RNG& cr)
{
    const int w = L.px(215), h = L.px(65), joint = std::max(1, L.px(10));
    const bool painted = uniform(rng, 0, 1) < 0.25;
    const cv::Vec3f base =
        painted ? surface_colour(rng, skin, 0.4)
                : cv::Vec3f(float(uniform(rng, 40, 80)), float(uniform(rng, 60, 100)), float(uniform(rng, 120, 190)));
    img.setTo(to_scalar(non_skin_colour(rng, 0.5, 0.75, 0.05)));  // mortar
    for (int row = 0, y = 0; y < img.rows; ++row, y += h + joint)
        for (int x = (row % 2) ? -(w + joint) / 2 : 0; x < img.cols; x += w + joint)
            fill(img, {x, y, w, h}, base, painted ? 1.0 : uniform(rng, 0.8, 1.15));
    cv::Mat1f speckle(img.size());
    cr.fill(speckle, cv::RNG::NORMAL, 0.0, 1.0);
    modulate(img, speckle, 0.05);
    modulate(img, smooth_noise(img.size(), L.px(120), cr), 0.06);
}

void fabric(cv::Mat3b& img, const Layout& L, const cv::Vec3f& skin, Rng& rng, cv::RNG& cr)
{
    img.setTo(to_scalar(surface_colour(rng, skin, 0.3)));
    const double weave = uniform(rng, 2.0, 4.0), fold = L.px(uniform(rng, 150, 400));
    const cv::Mat1f wander = smooth_noise(img.size(), L.px(500), cr);
    cv::Mat1f pattern(img.size());
    for (int y = 0; y < img.rows; ++y)
        for (int x = 0; x < img.cols; ++x)
            pattern(y, x) = float(0.25 * std::sin(2 * kPi * x / weave) * std::sin(2 * kPi * y / weave) +
                                  0.75 * std::sin(2 * kPi * x / fold + 1.5 * wander(y, x)));
    modulate(img, pattern, uniform(rng, 0.1, 0.3));
}

void wallpaper(cv::Mat3b& img, const Layout& L, const cv::Vec3f& skin, Rng& rng, cv::RNG& cr)
{
    const cv::Vec3f a = surface_colour(rng, skin, 0.3), b = surface_colour(rng, skin, 0.2);
    img.setTo(to_scalar(a));
    const int period = L.px(uniform(rng, 60, 250));
    const bool stripes = uniform(rng, 0, 1) < 0.5;
    for (int y = 0; y < img.rows; y += stripes ? img.rows : period)
        for (int x = 0; x < img.cols; x += period) {
            if (stripes)
                fill(img, {x, 0, period / 2, img.rows}, b);
            else
                cv::circle(img, {x + ((y / period) % 2) * period / 2, y}, std::max(1, period / 4), to_scalar(b),
                           cv::FILLED, cv::LINE_AA);
        }
    modulate(img, smooth_noise(img.size(), L.px(300), cr), 0.04);
}

void concrete(cv::Mat3b& img, const Layout& L, Rng& rng, cv::RNG& cr)
{
    img.setTo(to_scalar(non_skin_colour(rng, 0.35, 0.75, 0.05)));
    modulate(img, smooth_noise(img.size(), L.px(400), cr), 0.08);
    modulate(img, smooth_noise(img.size(), L.px(40), cr), 0.05);
    cv::Mat1f speckle(img.size());
    cr.fill(speckle, cv::RNG::NORMAL, 0.0, 1.0);
    modulate(img, speckle, 0.04);
}

// A photograph of a face: head, hair, eyes, mouth, shoulders, lit from one side.
void draw_face_picture(cv::Mat3b& img, const Layout& L, Rng& rng, cv::RNG& cr, const cv::Rect& area,
                       const cv::Vec3f& hand_skin)
{
    const int h = L.px(uniform(rng, 300, 900)), w = int(h * uniform(rng, 0.7, 1.0));
    const cv::Rect r = random_rect(rng, area, w, h) & cv::Rect(0, 0, img.cols, img.rows);
    if (r.width < 8 || r.height < 8) return;
    cv::Mat3b photo = img(r);
    photo.setTo(to_scalar(surface_colour(rng, hand_skin, 0.2)));
    const cv::Vec3f skin = uniform(rng, 0, 1) < 0.5 ? hand_skin : pick_wide_skin(rng).palm;
    const cv::Point c(r.width / 2, int(r.height * uniform(rng, 0.4, 0.5)));
    const cv::Size head(int(r.width * uniform(rng, 0.22, 0.34)), int(r.height * uniform(rng, 0.28, 0.38)));
    const double side = uniform(rng, -1, 1);
    cv::ellipse(photo, c + cv::Point(0, head.height * 2), cv::Size(head.width * 2, head.height), 0, 0, 360,
                to_scalar(non_skin_colour(rng, 0.1, 0.8, 0.6)), cv::FILLED, cv::LINE_AA);
    cv::ellipse(photo, c - cv::Point(0, head.height / 6), cv::Size(head.width * 11 / 10, head.height * 11 / 10), 0, 0,
                360, to_scalar(non_skin_colour(rng, 0.03, 0.2, 0.3)), cv::FILLED, cv::LINE_AA);
    cv::ellipse(photo, c, head, 0, 0, 360, to_scalar(skin, 0.8), cv::FILLED, cv::LINE_AA);
    cv::ellipse(photo, c + cv::Point(int(side * head.width * 0.2), 0),
                cv::Size(head.width * 4 / 5, head.height * 9 / 10), 0, 0, 360, to_scalar(skin), cv::FILLED,
                cv::LINE_AA);
    const cv::Scalar dark = to_scalar(non_skin_colour(rng, 0.03, 0.15, 0.2));
    for (int s : {-1, 1}) {
        const cv::Point eye = c + cv::Point(s * head.width * 2 / 5, -head.height / 8);
        cv::ellipse(photo, eye, cv::Size(std::max(1, head.width / 6), std::max(1, head.height / 14)), 0, 0, 360,
                    to_scalar(non_skin_colour(rng, 0.8, 0.95, 0.05)), cv::FILLED, cv::LINE_AA);
        cv::circle(photo, eye, std::max(1, head.height / 16), dark, cv::FILLED, cv::LINE_AA);
    }
    cv::ellipse(photo, c + cv::Point(0, head.height / 2),
                cv::Size(std::max(1, head.width / 3), std::max(1, head.height / 12)), 0, 0, 360,
                cv::Scalar(skin[0] * 0.7, skin[1] * 0.6, skin[2] * 0.9), cv::FILLED, cv::LINE_AA);
    modulate(photo, smooth_noise(photo.size(), std::max(2, head.width / 2), cr), 0.08);
    cv::GaussianBlur(photo, photo, cv::Size(0, 0), std::max(0.5, head.width / 40.0));
}

// A photograph of a hand (pointing, or a fist) in the hand model's own skin texture.
void draw_hand_picture(cv::Mat3b& img, const Layout& L, Rng& rng, cv::RNG& cr, const cv::Rect& area,
                       const cv::Vec3f& hand_skin)
{
    const HandSkin skin = pick_wide_skin(rng);
    const HandShape shape = pick_hand_shape(rng);
    const HandModel hand = build_hand_model(skin.palm, uniform(rng, 0, 1) < 0.5, rng, shape, &skin);
    const double scale = uniform(rng, 1.0, 3.0) / L.texel_mm;  // texels per hand millimetre
    const int side = int(2.3 * hand.finger_length_mm * scale);
    const cv::Rect r = random_rect(rng, area, side, side) & cv::Rect(0, 0, img.cols, img.rows);
    if (r.width < 8 || r.height < 8) return;
    cv::Mat3b photo = img(r);
    photo.setTo(to_scalar(surface_colour(rng, hand_skin, 0.2)));
    modulate(photo, smooth_noise(photo.size(), std::max(2, side / 3), cr), 0.1);

    // Model (u, v) -> picture pixels: turned, scaled, centred.
    const double a = uniform(rng, 0, 2 * kPi);
    const cv::Matx23d model_to_photo(scale * std::cos(a), -scale * std::sin(a), 0.5 * side, scale * std::sin(a),
                                     scale * std::cos(a), 0.5 * side);
    const cv::Matx33d t = hand.texel_to_model();
    const cv::Matx23d texel_to_photo = model_to_photo * t;
    cv::Mat3b warped;
    cv::warpAffine(hand.texture, warped, texel_to_photo, photo.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    cv::Mat1b mask(photo.size(), std::uint8_t{0});
    const bool fist = uniform(rng, 0, 1) < 0.3;
    for (std::size_t i = 0; i < hand.parts.size(); ++i) {
        if (fist && i == 2) continue;  // the index finger
        std::vector<cv::Point> pts;
        for (const cv::Point2d& q : hand.parts[i]) {
            const cv::Vec2d p = model_to_photo * cv::Vec3d(q.x, q.y, 1.0);
            pts.emplace_back(cvRound(p[0] * 16.0), cvRound(p[1] * 16.0));
        }
        cv::fillConvexPoly(mask, pts, cv::Scalar(255), cv::LINE_AA, 4);
    }
    warped.copyTo(photo, mask);
    cv::GaussianBlur(photo, photo, cv::Size(0, 0), std::max(0.5, side / 150.0));
}

void draw_surface(cv::Mat3b& img, const Layout& L, const cv::Vec3f& skin, Rng& rng, cv::RNG& cr)
{
    const double u = uniform(rng, 0, 1);
    if (u < 0.3)
        paint(img, L, skin, rng, cr);
    else if (u < 0.48)
        wood_panelling(img, L, skin, rng, cr);
    else if (u < 0.63)
        brick(img, L, skin, rng, cr);
    else if (u < 0.75)
        fabric(img, L, skin, rng, cr);
    else if (u < 0.88)
        wallpaper(img, L, skin, rng, cr);
    else
        concrete(img, L, rng, cr);
}

void draw_furnishings(cv::Mat3b& img, const Layout& L, Rng& rng, cv::RNG& cr)
{
    const cv::Rect all(0, 0, img.cols, img.rows);
    const double m2 = double(img.total()) * L.texel_mm * L.texel_mm * 1e-6;
    const int count = int(std::lround(m2 * uniform(rng, 0.0, 2.0)));
    for (int i = 0; i < count; ++i) {
        const auto kind = static_cast<Furnishing>(irand(rng, 0, static_cast<int>(Furnishing::Cable)));
        draw_furnishing(kind, img, L, rng, cr, all);
    }
}

// Light across the wall: a gradient from one side and, often, the pool of a lamp.
void light_wall(cv::Mat3b& img, Rng& rng)
{
    cv::Mat1f light(img.size());
    const double a = uniform(rng, 0, 2 * kPi), slope = uniform(rng, 0.1, 0.35);
    const bool lamp = uniform(rng, 0, 1) < 0.6;
    const cv::Point2d spot(uniform(rng, 0, img.cols), uniform(rng, 0, img.rows));
    const double radius = uniform(rng, 0.1, 0.35) * img.cols, strength = lamp ? uniform(rng, 0.1, 0.4) : 0.0;
    for (int y = 0; y < img.rows; ++y)
        for (int x = 0; x < img.cols; ++x) {
            const double gx = (x / double(img.cols) - 0.5) * std::cos(a) + (y / double(img.rows) - 0.5) * std::sin(a);
            const double d2 = (x - spot.x) * (x - spot.x) + (y - spot.y) * (y - spot.y);
            light(y, x) = float(2.0 * slope * gx + strength * std::exp(-0.5 * d2 / (radius * radius)));
        }
    modulate(img, light, 1.0);
}

}  // namespace

double draw_varied_wall(cv::Mat3b& img, const Layout& L, const cv::Rect& view, const cv::Vec3f& skin, Rng& rng,
                        cv::RNG& cr)
{
    draw_surface(img, L, skin, rng, cr);
    draw_furnishings(img, L, rng, cr);
    // Pictures of faces and hands, a few of them in the rest view.
    const cv::Rect all(0, 0, img.cols, img.rows);
    for (int i = irand(rng, 0, 6); i > 0; --i) {
        const cv::Rect& area = uniform(rng, 0, 1) < 0.5 ? view : all;
        if (uniform(rng, 0, 1) < 0.5)
            draw_face_picture(img, L, rng, cr, area, skin);
        else
            draw_hand_picture(img, L, rng, cr, area, skin);
    }
    const double share = place_skin_like(img, L, Preset::Heavy, skin, view, uniform(rng, 0.0, 0.15), rng, cr);
    light_wall(img, rng);
    if (uniform(rng, 0, 1) < 0.5) cv::GaussianBlur(img, img, cv::Size(0, 0), uniform(rng, 0.5, 1.8));
    return share;
}

}  // namespace gc::sim
