// The furnishings of the room's wall, drawn in wall texels: posters, whiteboards, monitors,
// plants, doors, clocks, bookshelves, racks, cables in colours no skin model confuses with
// skin, and the skin-like materials (cardboard, boards, cork, binders, a desk) laid out to a
// chosen share of the wall.
#pragma once

#include "sim/appearance.hpp"
#include "sim/scene.hpp"

#include <opencv2/core.hpp>

namespace gc::sim {

// Millimetre <-> texel conversions of one wall.
struct Layout {
    double texel_mm;
    cv::Size size;
    int px(double mm) const { return std::max(1, int(std::lround(mm / texel_mm))); }
};

int irand(Rng& rng, int lo, int hi);
// A w x h rectangle whose centre lies in `area`.
cv::Rect random_rect(Rng& rng, const cv::Rect& area, int w, int h);
void fill(cv::Mat3b& img, const cv::Rect& r, const cv::Vec3f& c, double gain = 1.0);
// Brightness texture over a rectangle of the wall: smooth variation and fine grain.
void texture_rect(cv::Mat3b& img, const cv::Rect& r, double cell, double amplitude, cv::RNG& cr);

void draw_poster(cv::Mat3b& img, const Layout& L, Rng& rng, cv::RNG& cr, const cv::Rect& area);
void draw_whiteboard(cv::Mat3b& img, const Layout& L, Rng& rng, const cv::Rect& area);
void draw_monitor(cv::Mat3b& img, const Layout& L, Rng& rng, const cv::Rect& area);
void draw_plant(cv::Mat3b& img, const Layout& L, Rng& rng, const cv::Rect& area);
void draw_door(cv::Mat3b& img, const Layout& L, Rng& rng, const cv::Rect& area);
void draw_clock(cv::Mat3b& img, const Layout& L, Rng& rng, const cv::Rect& area);
void draw_bookshelf(cv::Mat3b& img, const Layout& L, Rng& rng, cv::RNG& cr, const cv::Rect& area);
void draw_rack(cv::Mat3b& img, const Layout& L, Rng& rng, const cv::Rect& area);
void draw_cable(cv::Mat3b& img, const Layout& L, Rng& rng, const cv::Rect& area);

enum class Furnishing { Bookshelf, Poster, Rack, Monitor, Whiteboard, Plant, Clock, Door, Cable };
// Draws one furnishing of `kind` in `area` (those with a texture draw it from `cr`).
void draw_furnishing(Furnishing kind, cv::Mat3b& img, const Layout& L, Rng& rng, cv::RNG& cr, const cv::Rect& area);

// Wood: stripes along x whose phase wanders, `amplitude` of brightness.
void grain(cv::Mat3b& img, double period_px, double amplitude, Rng& rng, cv::RNG& cr);

// Lays skin-like items (the materials of `preset`: only small tags for clean) until they
// cover `target` of `view` and of the rest of the wall; returns the share of `view` covered.
double place_skin_like(cv::Mat3b& img, const Layout& L, Preset preset, const cv::Vec3f& skin, const cv::Rect& view,
                       double target, Rng& rng, cv::RNG& cr);

}  // namespace gc::sim
