#include "sim/furnishings.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace gc::sim {

namespace {

constexpr double kPi = std::numbers::pi;

// ---- skin-like materials: drawn on their own canvas with a label of their extent ----------

enum class Material { Cardboard, Board, Cork, Binders, Desk, Tag };

struct Item {
    cv::Mat3b colour;
    cv::Mat1b label;  // 255 where the item is (all of it is skin-coloured)
};

// A wooden item of colour c with `stripes` grain stripes across its height.
void wooden(Item& it, cv::Size s, const cv::Vec3f& c, double stripes, Rng& rng, cv::RNG& cr)
{
    it.colour.create(s);
    it.colour.setTo(to_scalar(c));
    grain(it.colour, std::max(2.0, s.height / stripes), 0.08, rng, cr);
}

Item make_item(Material m, const Layout& L, const cv::Vec3f& skin, double size_factor, Rng& rng, cv::RNG& cr)
{
    auto sized = [&](double lo, double hi) { return L.px(uniform(rng, lo, hi) * size_factor); };
    Item it;
    switch (m) {
    case Material::Cardboard: {
        const cv::Size s(sized(200, 520), sized(150, 400));
        const cv::Vec3f c = skin_like_colour(rng, skin, 330, 520);
        it.colour.create(s);
        it.colour.setTo(to_scalar(c));
        const int side = s.width / 5;  // the side face, turned from the light
        it.colour(cv::Rect(s.width - side, 0, side, s.height)).setTo(to_scalar(c, 0.8));
        it.colour(cv::Rect(0, s.height * 2 / 5, s.width - side, std::max(1, s.height / 8))).setTo(to_scalar(c, 1.12));
        for (int i = irand(rng, 0, 3); i > 0; --i) {
            const int w = std::max(1, s.width / 6), h = std::max(1, s.height / 10);
            it.colour(cv::Rect(irand(rng, 0, s.width - side - w), irand(rng, 0, s.height - h), w, h))
                .setTo(to_scalar(c, 0.65));
        }
        modulate(it.colour, smooth_noise(s, std::max(2, L.px(40)), cr), 0.05);
        break;
    }
    case Material::Board: {
        const cv::Size s(sized(500, 1500), std::max(2, L.px(uniform(rng, 22, 40))));
        wooden(it, s, skin_like_colour(rng, skin, 220, 380), 3.0, rng, cr);
        break;
    }
    case Material::Cork: {
        const cv::Size s(sized(300, 700), sized(250, 500));
        const cv::Vec3f c = skin_like_colour(rng, skin, 300, 430);
        it.colour.create(s);
        it.colour.setTo(to_scalar(c, 0.8));
        const int f = std::max(1, L.px(20));
        if (s.width > 2 * f && s.height > 2 * f)
            it.colour(cv::Rect(f, f, s.width - 2 * f, s.height - 2 * f)).setTo(to_scalar(c));
        cv::Mat1f speckle(s);
        cr.fill(speckle, cv::RNG::NORMAL, 0.0, 1.0);
        modulate(it.colour, speckle, 0.06);
        break;
    }
    case Material::Binders: {
        const int n = irand(rng, 3, 8);
        const int h = sized(280, 320);
        std::vector<int> widths;
        int total = 0;
        for (int i = 0; i < n; ++i) total += widths.emplace_back(sized(40, 80));
        it.colour.create(h, total);
        int x = 0;
        for (int w : widths) {
            const cv::Vec3f c = skin_like_colour(rng, skin, 350, 620);
            it.colour(cv::Rect(x, 0, w, h)).setTo(to_scalar(c));
            it.colour(cv::Rect(x + w / 5, h / 6, std::max(1, w * 3 / 5), std::max(1, h / 5))).setTo(to_scalar(c, 1.15));
            it.colour(cv::Rect(x, 0, 1, h)).setTo(to_scalar(c, 0.75));
            x += w;
        }
        break;
    }
    case Material::Desk: {
        const cv::Size s(sized(1500, 3000), L.px(uniform(rng, 60, 120)));
        wooden(it, s, skin_like_colour(rng, skin, 250, 420), 4.0, rng, cr);
        break;
    }
    case Material::Tag: {
        const cv::Size s(sized(30, 60), sized(40, 70));
        it.colour.create(s);
        it.colour.setTo(to_scalar(skin_like_colour(rng, skin, 350, 460)));
        break;
    }
    }
    it.label.create(it.colour.size());
    it.label.setTo(255);
    return it;
}

Material pick_material(Preset preset, Rng& rng)
{
    if (preset == Preset::Clean) return Material::Tag;
    const double u = uniform(rng, 0, 1);
    if (preset == Preset::Heavy) {
        if (u < 0.30) return Material::Cardboard;
        if (u < 0.50) return Material::Board;
        if (u < 0.65) return Material::Cork;
        if (u < 0.90) return Material::Binders;
        return Material::Desk;
    }
    if (u < 0.35) return Material::Cardboard;
    if (u < 0.60) return Material::Board;
    if (u < 0.80) return Material::Cork;
    return Material::Binders;
}

}  // namespace

int irand(Rng& rng, int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }

cv::Rect random_rect(Rng& rng, const cv::Rect& area, int w, int h)
{
    const int x = irand(rng, area.x - w / 2, area.x + std::max(0, area.width - w / 2));
    const int y = irand(rng, area.y - h / 2, area.y + std::max(0, area.height - h / 2));
    return {x, y, w, h};
}

void fill(cv::Mat3b& img, const cv::Rect& r, const cv::Vec3f& c, double gain)
{
    cv::rectangle(img, r & cv::Rect(0, 0, img.cols, img.rows), to_scalar(c, gain), cv::FILLED);
}

// Brightness texture over a rectangle of the wall: smooth variation and fine grain.
void texture_rect(cv::Mat3b& img, const cv::Rect& r, double cell, double amplitude, cv::RNG& cr)
{
    const cv::Rect c = r & cv::Rect(0, 0, img.cols, img.rows);
    if (c.empty()) return;
    cv::Mat3b roi = img(c);
    modulate(roi, smooth_noise(c.size(), std::max(2.0, cell), cr), amplitude);
}

// ---- non-skin furnishings --------------------------------------------------------------

void draw_poster(cv::Mat3b& img, const Layout& L, Rng& rng, cv::RNG& cr, const cv::Rect& area)
{
    const cv::Rect r = random_rect(rng, area, L.px(uniform(rng, 400, 900)), L.px(uniform(rng, 500, 1000)));
    fill(img, r, non_skin_colour(rng, 0.55, 0.95, 0.5));
    for (int i = irand(rng, 2, 5); i > 0; --i) {
        const int w = int(r.width * uniform(rng, 0.2, 0.7)), h = int(r.height * uniform(rng, 0.1, 0.4));
        const cv::Rect b(r.x + irand(rng, 0, r.width - w), r.y + irand(rng, 0, r.height - h), w, h);
        if (uniform(rng, 0, 1) < 0.4)
            cv::ellipse(img, (b.tl() + b.br()) / 2, b.size() / 2, 0, 0, 360, to_scalar(non_skin_colour(rng, 0.2, 0.9)),
                        cv::FILLED, cv::LINE_AA);
        else
            fill(img, b, non_skin_colour(rng, 0.2, 0.9));
    }
    const cv::Vec3f ink = non_skin_colour(rng, 0.08, 0.25, 0.2);
    for (int i = irand(rng, 3, 8); i > 0; --i) {
        const int y = r.y + irand(rng, r.height / 2, r.height - L.px(30));
        const int x = r.x + L.px(30);
        fill(img, {x, y, int(r.width * uniform(rng, 0.3, 0.8)), L.px(8)}, ink);
    }
    texture_rect(img, r, L.px(80), 0.04, cr);
}

void draw_whiteboard(cv::Mat3b& img, const Layout& L, Rng& rng, const cv::Rect& area)
{
    const cv::Rect r = random_rect(rng, area, L.px(uniform(rng, 1200, 2000)), L.px(uniform(rng, 800, 1200)));
    fill(img, r, non_skin_colour(rng, 0.55, 0.7, 0.05));
    fill(img, {r.x + L.px(20), r.y + L.px(20), r.width - L.px(40), r.height - L.px(40)},
         non_skin_colour(rng, 0.86, 0.95, 0.03));
    for (int s = irand(rng, 2, 6); s > 0; --s) {
        std::vector<cv::Point> line;
        cv::Point p(r.x + irand(rng, r.width / 8, r.width * 7 / 8), r.y + irand(rng, r.height / 8, r.height * 7 / 8));
        for (int k = 0; k < 8; ++k) {
            line.push_back(p);
            p += cv::Point(irand(rng, -L.px(120), L.px(120)), irand(rng, -L.px(60), L.px(60)));
        }
        cv::polylines(img, line, false, to_scalar(non_skin_colour(rng, 0.2, 0.6, 0.9)), std::max(1, L.px(5)),
                      cv::LINE_AA);
    }
}

void draw_monitor(cv::Mat3b& img, const Layout& L, Rng& rng, const cv::Rect& area)
{
    const cv::Rect r = random_rect(rng, area, L.px(uniform(rng, 480, 720)), L.px(uniform(rng, 300, 450)));
    fill(img, r, non_skin_colour(rng, 0.07, 0.18, 0.1));
    const cv::Rect screen(r.x + L.px(20), r.y + L.px(20), r.width - L.px(40), r.height - L.px(40));
    fill(img, screen, non_skin_colour(rng, 0.15, 0.5, 0.6));
    for (int i = irand(rng, 1, 3); i > 0; --i) {
        const int w = int(screen.width * uniform(rng, 0.3, 0.6)), h = int(screen.height * uniform(rng, 0.3, 0.6));
        fill(img, {screen.x + irand(rng, 0, screen.width - w), screen.y + irand(rng, 0, screen.height - h), w, h},
             non_skin_colour(rng, 0.5, 0.95, 0.3));
    }
    fill(img, {r.x + r.width / 2 - L.px(40), r.y + r.height, L.px(80), L.px(120)}, non_skin_colour(rng, 0.1, 0.2, 0.1));
}

void draw_plant(cv::Mat3b& img, const Layout& L, Rng& rng, const cv::Rect& area)
{
    const cv::Rect pot = random_rect(rng, area, L.px(uniform(rng, 180, 300)), L.px(uniform(rng, 180, 260)));
    fill(img, pot, non_skin_colour(rng, 0.3, 0.8, 0.5));
    const cv::Point base(pot.x + pot.width / 2, pot.y);
    for (int i = irand(rng, 12, 26); i > 0; --i) {
        const double v = uniform(rng, 0.2, 0.6) * 255.0;
        const cv::Scalar green(v * uniform(rng, 0.2, 0.5), v, v * uniform(rng, 0.25, 0.55));
        const cv::Point c = base + cv::Point(irand(rng, -L.px(250), L.px(250)), -irand(rng, L.px(20), L.px(500)));
        cv::ellipse(img, c, cv::Size(L.px(uniform(rng, 30, 70)), L.px(uniform(rng, 12, 25))), uniform(rng, 0, 180), 0,
                    360, green, cv::FILLED, cv::LINE_AA);
    }
}

void draw_door(cv::Mat3b& img, const Layout& L, Rng& rng, const cv::Rect& area)
{
    const cv::Rect r = random_rect(rng, area, L.px(900), L.px(2050));
    fill(img, r, non_skin_colour(rng, 0.35, 0.6, 0.1));
    fill(img, {r.x + L.px(25), r.y + L.px(25), r.width - L.px(50), r.height - L.px(25)},
         non_skin_colour(rng, 0.45, 0.9, 0.35));
    cv::circle(img, {r.x + r.width - L.px(110), r.y + r.height / 2}, L.px(30),
               to_scalar(non_skin_colour(rng, 0.5, 0.8, 0.05)), cv::FILLED, cv::LINE_AA);
}

void draw_clock(cv::Mat3b& img, const Layout& L, Rng& rng, const cv::Rect& area)
{
    const int rad = L.px(uniform(rng, 120, 170));
    const cv::Rect r = random_rect(rng, area, 2 * rad, 2 * rad);
    const cv::Point c = (r.tl() + r.br()) / 2;
    cv::circle(img, c, rad, to_scalar(non_skin_colour(rng, 0.05, 0.2, 0.2)), cv::FILLED, cv::LINE_AA);
    cv::circle(img, c, rad * 9 / 10, to_scalar(non_skin_colour(rng, 0.88, 0.97, 0.03)), cv::FILLED, cv::LINE_AA);
    const cv::Scalar hand = to_scalar(non_skin_colour(rng, 0.03, 0.1, 0.05));
    for (double len : {0.5, 0.8}) {
        const double a = uniform(rng, 0, 2 * kPi);
        cv::line(img, c, c + cv::Point(int(len * rad * 0.9 * std::cos(a)), int(len * rad * 0.9 * std::sin(a))), hand,
                 std::max(1, L.px(10)), cv::LINE_AA);
    }
}

void draw_bookshelf(cv::Mat3b& img, const Layout& L, Rng& rng, cv::RNG& cr, const cv::Rect& area)
{
    const cv::Rect r = random_rect(rng, area, L.px(uniform(rng, 800, 1600)), L.px(uniform(rng, 1300, 2000)));
    fill(img, r, non_skin_colour(rng, 0.25, 0.55, 0.1));
    fill(img, {r.x + L.px(20), r.y + L.px(20), r.width - L.px(40), r.height - L.px(40)},
         non_skin_colour(rng, 0.06, 0.14, 0.1));  // the shadowed inside
    const int rows = irand(rng, 4, 6);
    const int row_h = (r.height - L.px(40)) / rows;
    for (int k = 0; k < rows; ++k) {
        const int floor_y = r.y + L.px(20) + (k + 1) * row_h;
        fill(img, {r.x, floor_y - L.px(20), r.width, L.px(20)}, non_skin_colour(rng, 0.25, 0.55, 0.1));
        int x = r.x + L.px(25);
        while (x < r.x + r.width - L.px(60)) {
            const int w = L.px(uniform(rng, 18, 55));
            const int h = std::min(row_h - L.px(30), L.px(uniform(rng, 150, 290)));
            if (uniform(rng, 0, 1) < 0.12) {  // a gap
                x += w;
                continue;
            }
            const cv::Rect book(x, floor_y - L.px(20) - h, w, h);
            fill(img, book, non_skin_colour(rng, 0.12, 0.85, 0.8));
            fill(img, {book.x, book.y + h / 5, w, std::max(1, L.px(8))}, non_skin_colour(rng, 0.6, 0.95, 0.2));
            x += w + (uniform(rng, 0, 1) < 0.3 ? 1 : 0);
        }
    }
    texture_rect(img, r, L.px(60), 0.05, cr);
}

void draw_rack(cv::Mat3b& img, const Layout& L, Rng& rng, const cv::Rect& area)
{
    const cv::Rect r = random_rect(rng, area, L.px(uniform(rng, 450, 650)), L.px(uniform(rng, 600, 1400)));
    fill(img, r, non_skin_colour(rng, 0.05, 0.12, 0.1));
    for (int y = r.y + L.px(20); y < r.y + r.height - L.px(90); y += L.px(uniform(rng, 90, 180))) {
        fill(img, {r.x + L.px(15), y, r.width - L.px(30), L.px(80)}, non_skin_colour(rng, 0.1, 0.4, 0.15));
        for (int i = irand(rng, 1, 4); i > 0; --i) {
            const double v = uniform(rng, 0.6, 1.0) * 255.0;
            const cv::Scalar led =
                uniform(rng, 0, 1) < 0.5 ? cv::Scalar(v * 0.3, v, v * 0.3) : cv::Scalar(v, v * 0.6, v * 0.2);
            cv::circle(img, {r.x + L.px(40) + i * L.px(30), y + L.px(40)}, std::max(1, L.px(6)), led, cv::FILLED);
        }
    }
}

void draw_cable(cv::Mat3b& img, const Layout& L, Rng& rng, const cv::Rect& area)
{
    std::vector<cv::Point> line;
    cv::Point p(irand(rng, area.x, area.x + area.width), irand(rng, area.y, area.y + area.height));
    for (int k = 0; k < 6; ++k) {
        line.push_back(p);
        p += cv::Point(irand(rng, -L.px(300), L.px(300)), irand(rng, L.px(50), L.px(300)));
    }
    cv::polylines(img, line, false, to_scalar(non_skin_colour(rng, 0.03, 0.12, 0.1)), std::max(1, L.px(10)),
                  cv::LINE_AA);
}

void draw_furnishing(Furnishing kind, cv::Mat3b& img, const Layout& L, Rng& rng, cv::RNG& cr, const cv::Rect& area)
{
    switch (kind) {
    case Furnishing::Bookshelf:
        return draw_bookshelf(img, L, rng, cr, area);
    case Furnishing::Poster:
        return draw_poster(img, L, rng, cr, area);
    case Furnishing::Rack:
        return draw_rack(img, L, rng, area);
    case Furnishing::Monitor:
        return draw_monitor(img, L, rng, area);
    case Furnishing::Whiteboard:
        return draw_whiteboard(img, L, rng, area);
    case Furnishing::Plant:
        return draw_plant(img, L, rng, area);
    case Furnishing::Clock:
        return draw_clock(img, L, rng, area);
    case Furnishing::Door:
        return draw_door(img, L, rng, area);
    case Furnishing::Cable:
        return draw_cable(img, L, rng, area);
    }
}

void grain(cv::Mat3b& img, double period_px, double amplitude, Rng& rng, cv::RNG& cr)
{
    // Wood: stripes along x, their phase wandering.
    const cv::Mat1f wander = smooth_noise(img.size(), std::max(4.0, period_px * 3), cr);
    cv::Mat1f pattern(img.size());
    const double phase = uniform(rng, 0, 2 * kPi);
    for (int y = 0; y < img.rows; ++y)
        for (int x = 0; x < img.cols; ++x)
            pattern(y, x) = float(std::sin(2 * kPi * y / period_px + phase + 2.0 * wander(y, x)));
    modulate(img, pattern, amplitude);
}

// Lays skin-like items until they cover `target` of the view and of the rest of the wall.
// The items are drawn after the furnishings, so their coverage is exact.
double place_skin_like(cv::Mat3b& img, const Layout& L, Preset preset, const cv::Vec3f& skin, const cv::Rect& view,
                       double target, Rng& rng, cv::RNG& cr)
{
    cv::Mat1b label(img.size(), std::uint8_t{0});
    const double view_area = double(view.area());
    const double target_in = target * view_area;
    const double target_out = target * (double(img.total()) - view_area);
    double in = 0.0, out = 0.0;
    const cv::Rect wall(0, 0, img.cols, img.rows);
    for (int attempt = 0; attempt < 6000; ++attempt) {
        const bool need_in = in < 0.985 * target_in;
        const bool need_out = out < 0.95 * target_out;
        if (!need_in && !need_out) break;
        const bool inside = need_in && (!need_out || uniform(rng, 0, 1) < 0.5);
        // Shrink the items as the budget runs out, so the last ones still fit.
        const double remaining = inside ? target_in - in : target_out - out;
        const double typical = double(L.px(300)) * L.px(250);
        const double size_factor = std::clamp(std::sqrt(remaining / typical), 0.15, 1.0);
        const Item it =
            make_item(pick_material(preset, rng), L, skin, preset == Preset::Clean ? 1.0 : size_factor, rng, cr);
        const cv::Rect area = inside ? view : wall;
        const cv::Rect r = random_rect(rng, area, it.colour.cols, it.colour.rows);
        const cv::Rect clipped = r & wall;
        if (clipped.empty()) continue;
        double add_in = 0.0, add_out = 0.0;
        for (int y = clipped.y; y < clipped.br().y; ++y)
            for (int x = clipped.x; x < clipped.br().x; ++x) {
                if (!it.label(y - r.y, x - r.x) || label(y, x)) continue;
                (view.contains({x, y}) ? add_in : add_out) += 1.0;
            }
        if (add_in + add_out == 0.0) continue;
        if (in + add_in > 1.02 * target_in + 1.0 || out + add_out > 1.05 * target_out + 1.0) continue;
        const cv::Rect src(clipped.x - r.x, clipped.y - r.y, clipped.width, clipped.height);
        it.colour(src).copyTo(img(clipped), it.label(src));
        label(clipped) |= it.label(src);
        in += add_in;
        out += add_out;
    }
    return in / view_area;
}

}  // namespace gc::sim
