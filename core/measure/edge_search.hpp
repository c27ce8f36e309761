// The one-directional skin-edge search along a contour normal: walk from the interior
// outward and stop at the first fall of the skin-membership map through `level`. Skin
// clutter beyond the hand's own edge is never reached first, unlike a search for the
// nearest edge in both directions.
#pragma once

#include <opencv2/core.hpp>

#include <cmath>
#include <cstdint>

namespace gc {

// The membership level of the skin boundary (see SkinModel::membership).
inline constexpr int kSkinEdgeLevel = 128;
// The grey level that marks the learnt static scene in a grey map (find_grey_step_fast);
// real grey levels are kept above it.
inline constexpr std::uint8_t kSceneGreyLevel = 0;

// Nearest-pixel search, for scoring many hypotheses: samples at t = -half .. +half (pixel
// steps) along p + t * n (n unit, pointing outward); pixels outside `map` count as
// non-skin. On success stores the signed sub-pixel offset of the crossing in `offset` and
// returns true; false when no high-to-low crossing lies in the window. Then, if given,
// `skin_beyond` tells whether the window's outer end is skin: with no fall before it, the
// normal runs from skin into skin (the hand in front of a face).
inline bool find_skin_edge_fast(const cv::Mat1b& map, float px, float py, float nx, float ny, int half, float& offset,
                                bool* skin_beyond = nullptr)
{
    const int w = map.cols, h = map.rows;
    const std::uint8_t* data = map.data;
    const std::size_t step = map.step[0];
    int prev = -1;  // membership at the previous sample, -1 before the first
    for (int k = -half; k <= half; ++k) {
        const int x = cvRound(px + k * nx);
        const int y = cvRound(py + k * ny);
        int v = 0;
        // Unsigned comparison folds the < 0 test in: off-image counts as background.
        if (static_cast<unsigned>(x) < static_cast<unsigned>(w) && static_cast<unsigned>(y) < static_cast<unsigned>(h))
            v = data[y * step + x];
        if (prev >= kSkinEdgeLevel && v < kSkinEdgeLevel) {
            offset =
                static_cast<float>(k - 1) + static_cast<float>(prev - kSkinEdgeLevel) / static_cast<float>(prev - v);
            return true;
        }
        prev = v;
    }
    if (skin_beyond) *skin_beyond = prev >= kSkinEdgeLevel;
    return false;
}

// Where skin meets skin the membership map has no edge, but the grey levels usually do
// (the hand's own shading darkens towards its silhouette; a face is lit differently).
// Nearest-pixel search along p + t * n for the strongest step |g(t + 1) - g(t - 1)|,
// t = -half .. +half, in a grey map; true, with its offset in `offset`, when that step
// reaches `min_step` grey levels. Samples outside the map are not compared.
// kSceneGreyLevel marks the learnt static scene (real grey levels lie above it): a step
// whose inner sample g(t - 1) is the scene is passed over. The hand is never the scene, so the
// scene's border is the hand's outline only where the scene lies outside it; a contour
// lying inside the scene would otherwise find an edge at every border of it.
inline bool find_grey_step_fast(const cv::Mat1b& grey, float px, float py, float nx, float ny, int half, int min_step,
                                float& offset)
{
    const int w = grey.cols, h = grey.rows;
    const std::uint8_t* data = grey.data;
    const std::size_t step = grey.step[0];
    const auto sample = [&](int k) {
        const int x = cvRound(px + k * nx);
        const int y = cvRound(py + k * ny);
        return static_cast<unsigned>(x) < static_cast<unsigned>(w) &&
                       static_cast<unsigned>(y) < static_cast<unsigned>(h)
                   ? int(data[y * step + x])
                   : -1;
    };
    int before = sample(-half - 1), here = sample(-half);
    int best = min_step - 1, at = 0;
    for (int k = -half; k <= half; ++k) {
        const int after = sample(k + 1);
        if (before > kSceneGreyLevel && after >= 0) {
            const int d = after > before ? after - before : before - after;
            if (d > best) {
                best = d;
                at = k;
            }
        }
        before = here;
        here = after;
    }
    if (best < min_step) return false;
    offset = static_cast<float>(at);
    return true;
}

// Bilinear search at a finer step, for the few contours that are refined each frame.
// Same contract as find_skin_edge_fast with a real-valued half length and step.
bool find_skin_edge_precise(const cv::Mat1b& map, cv::Point2d p, cv::Point2d n, double half, double step,
                            double& offset);

// Moves a skin edge found at `offset` along p + t * n to where the colour of `bgr` (CV_8UC3)
// is halfway between the skin `reach` pixels inside it and the background `reach` pixels
// outside: optics and sensors mix the two linearly across the boundary, so that is where
// the hand covers half a pixel, whereas the membership level crossing moves with the
// background's colour (a light grey wall pulls it inward, a dark one much less). Returns
// `offset` unchanged where the two colours are too alike to tell or no crossing is found
// within reach of it.
double colour_edge_offset(const cv::Mat& bgr, cv::Point2d p, cv::Point2d n, double offset, double reach = 3.0);

// Bilinear sample of a CV_8U map, 0 outside.
double sample_bilinear(const cv::Mat1b& map, double x, double y);

}  // namespace gc
