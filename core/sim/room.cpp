#include "sim/room.hpp"

#include "sim/furnishings.hpp"
#include "sim/varied_room.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <numbers>

namespace gc::sim {

namespace {

constexpr double kPi = std::numbers::pi;

// A preset's furnishings and the share of each, as cumulative bounds on a uniform draw in
// [0, 1): a draw below `below` (and not below the one before) picks `kind`.
struct MixEntry {
    double below;
    Furnishing kind;
};

constexpr MixEntry kHeavyMix[] = {
    {0.30, Furnishing::Bookshelf},  {0.45, Furnishing::Poster}, {0.58, Furnishing::Rack}, {0.70, Furnishing::Monitor},
    {0.78, Furnishing::Whiteboard}, {0.86, Furnishing::Plant},  {1.00, Furnishing::Cable}};

constexpr MixEntry kLightMix[] = {{0.40, Furnishing::Poster},  {0.52, Furnishing::Whiteboard},
                                  {0.64, Furnishing::Monitor}, {0.76, Furnishing::Plant},
                                  {0.86, Furnishing::Clock},   {1.00, Furnishing::Door}};

// The last entry takes whatever the others leave.
template <std::size_t N>
Furnishing pick(const MixEntry (&mix)[N], double u)
{
    for (std::size_t i = 0; i + 1 < N; ++i)
        if (u < mix[i].below) return mix[i].kind;
    return mix[N - 1].kind;
}

}  // namespace

double target_skin_area(Preset preset)
{
    switch (preset) {
    case Preset::Clean:
        return 0.0003;
    case Preset::Light:
        return 0.0374;
    case Preset::Heavy:
        return 0.0935;
    case Preset::FacePass:
        return 0.0374;
    case Preset::Varied:
        return 0.0;  // drawn per seed
    }
    return 0.0;
}

Wall build_wall(Preset preset, const cv::Vec3f& skin, const cv::Rect2d& view_mm, double distance_mm, double texel_mm,
                Rng& rng)
{
    cv::RNG cr(std::uniform_int_distribution<std::uint64_t>()(rng));
    Wall wall;
    wall.distance_mm = distance_mm;
    wall.texel_mm = texel_mm;
    // The wall reaches well beyond the rest view, so the head can pan and tilt over it.
    const cv::Rect2d extent(view_mm.x - 1.3 * view_mm.width, view_mm.y - 0.8 * view_mm.height, 3.6 * view_mm.width,
                            2.6 * view_mm.height);
    wall.origin_mm = extent.tl();
    const Layout L{texel_mm,
                   cv::Size(int(std::ceil(extent.width / texel_mm)), int(std::ceil(extent.height / texel_mm)))};
    const cv::Rect view(int(std::floor((view_mm.x - extent.x) / texel_mm)),
                        int(std::floor((view_mm.y - extent.y) / texel_mm)), int(std::ceil(view_mm.width / texel_mm)),
                        int(std::ceil(view_mm.height / texel_mm)));
    const cv::Rect all(0, 0, L.size.width, L.size.height);
    wall.image.create(L.size);
    const double wall_m2 = extent.area() * 1e-6;

    if (preset == Preset::Varied) {
        wall.skin_like_area = draw_varied_wall(wall.image, L, view, skin, rng, cr);
        return wall;
    }
    if (preset == Preset::Clean) {
        // A black curtain: dark cloth in vertical folds.
        wall.image.setTo(to_scalar(non_skin_colour(rng, 0.085, 0.11, 0.15)));
        const double p1 = uniform(rng, 140, 260) / texel_mm, p2 = uniform(rng, 300, 600) / texel_mm;
        const double f1 = uniform(rng, 0, 2 * kPi), f2 = uniform(rng, 0, 2 * kPi);
        const cv::Mat1f wander = smooth_noise(L.size, L.px(400), cr);
        cv::Mat1f folds(L.size);
        for (int y = 0; y < L.size.height; ++y)
            for (int x = 0; x < L.size.width; ++x)
                folds(y, x) = float(0.7 * std::sin(2 * kPi * x / p1 + f1 + 0.8 * wander(y, x)) +
                                    0.3 * std::sin(2 * kPi * x / p2 + f2));
        modulate(wall.image, folds, 0.35);
    } else {
        const bool heavy = preset == Preset::Heavy;
        wall.image.setTo(
            to_scalar(heavy ? non_skin_colour(rng, 0.55, 0.8, 0.12) : non_skin_colour(rng, 0.72, 0.9, 0.12)));
        texture_rect(wall.image, all, L.px(300), 0.04, cr);
        // Furnishings over the whole wall, with the density of the preset.
        const int count = int(std::lround(wall_m2 * (heavy ? 2.2 : 0.8)));
        for (int i = 0; i < count; ++i) {
            const double u = uniform(rng, 0, 1);
            draw_furnishing(heavy ? pick(kHeavyMix, u) : pick(kLightMix, u), wall.image, L, rng, cr, all);
        }
    }
    wall.skin_like_area = place_skin_like(wall.image, L, preset, skin, view, target_skin_area(preset), rng, cr);
    return wall;
}

}  // namespace gc::sim
