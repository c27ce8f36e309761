// The wall of the varied preset: a surface drawn from many kinds (paint, often skin-coloured,
// wood panelling, brick, fabric, wallpaper, concrete), furnishings, photo-like posters of
// faces and of hands, skin-like objects, light falling across it, and sometimes defocus.
#pragma once

#include "sim/appearance.hpp"
#include "sim/furnishings.hpp"

#include <opencv2/core.hpp>

namespace gc::sim {

// Draws over all of `img` (wall texels of layout L); `view` is the rest view's rectangle.
// Returns the share of `view` covered by the skin-like objects laid out on purpose (the
// surface and the pictures may add more).
double draw_varied_wall(cv::Mat3b& img, const Layout& L, const cv::Rect& view, const cv::Vec3f& skin, Rng& rng,
                        cv::RNG& cr);

}  // namespace gc::sim
