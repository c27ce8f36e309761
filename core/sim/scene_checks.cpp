#include "sim/scene_checks.hpp"

#include <cmath>
#include <stdexcept>

namespace gc::sim {

std::string number_text(double v) { return std::to_string(v); }

void require_valid(bool ok, const std::string& message)
{
    if (!ok) throw std::invalid_argument(message);
}

void validate(const SceneConfig& c)
{
    require_valid(c.preset >= Preset::Clean && c.preset <= Preset::Varied, "SceneConfig: unknown preset");
    require_valid(c.variety == Variety::None || c.variety == Variety::Wide, "SceneConfig: unknown variety");
    require_valid(c.motion >= Motion::Static && c.motion <= Motion::LeaveReturn, "SceneConfig: unknown motion");
    require_valid(c.gesture == Gesture::Pointing || c.gesture == Gesture::Open || c.gesture == Gesture::Fist,
                  "SceneConfig: the hand's gesture must be pointing, open or fist");
    require_valid(std::isfinite(c.gesture_cycle_s) && c.gesture_cycle_s >= 0.0 && c.gesture_cycle_s <= 3600.0,
                  "SceneConfig: gesture_cycle_s " + number_text(c.gesture_cycle_s) + " outside [0, 3600]");
    require_valid(c.width >= 32 && c.width <= 4096 && c.height >= 32 && c.height <= 4096,
                  "SceneConfig: image size " + std::to_string(c.width) + "x" + std::to_string(c.height) +
                      " outside 32..4096");
    require_valid(std::isfinite(c.fps) && c.fps > 0.0 && c.fps <= 1000.0,
                  "SceneConfig: fps " + number_text(c.fps) + " outside (0, 1000]");
    require_valid(std::isfinite(c.focal_px) && c.focal_px >= 0.0 && c.focal_px <= 100.0 * c.width,
                  "SceneConfig: focal_px " + number_text(c.focal_px) + " must be 0 (default) or a positive length");
    require_valid(std::isfinite(c.baseline_mm) && c.baseline_mm > 0.0 && c.baseline_mm <= 1000.0,
                  "SceneConfig: baseline_mm " + number_text(c.baseline_mm) + " outside (0, 1000]");
    require_valid(std::isfinite(c.hand_distance_mm) && c.hand_distance_mm >= 300.0 && c.hand_distance_mm <= 2500.0,
                  "SceneConfig: hand_distance_mm " + number_text(c.hand_distance_mm) + " outside [300, 2500]");
    require_valid(std::isfinite(c.noise_sigma) && c.noise_sigma >= 0.0 && c.noise_sigma <= 50.0,
                  "SceneConfig: noise_sigma " + number_text(c.noise_sigma) + " outside [0, 50]");
    if (c.aim_mm)
        for (int i = 0; i < 3; ++i)
            require_valid(std::isfinite((*c.aim_mm)[i]) && std::abs((*c.aim_mm)[i]) <= 1.0e5,
                          "SceneConfig: aim_mm must be finite and within 100 m");
}

void validate(const HeadPose& h)
{
    const double v[] = {h.pan_deg, h.tilt_deg, h.verge_left_deg, h.verge_right_deg};
    for (double x : v)
        require_valid(std::isfinite(x) && std::abs(x) <= 90.0,
                      "HeadPose: angles must be finite and within +/-90 degrees");
    require_valid(std::isfinite(h.zoom) && h.zoom >= 1.0 && h.zoom <= 100.0, "HeadPose: zoom must be within [1, 100]");
}

void validate(const HandPose& p)
{
    for (int i = 0; i < 3; ++i)
        require_valid(std::isfinite(p.palm_mm[i]) && std::abs(p.palm_mm[i]) <= 1.0e5,
                      "HandPose: palm_mm must be finite and within 100 m");
    require_valid(std::isfinite(p.roll_deg) && std::isfinite(p.yaw_deg) && std::isfinite(p.pitch_deg),
                  "HandPose: angles must be finite");
    require_valid(std::isfinite(p.forearm_mm) && p.forearm_mm >= 100.0 && p.forearm_mm <= 600.0,
                  "HandPose: forearm_mm " + number_text(p.forearm_mm) + " outside [100, 600]");
    require_valid(p.gesture == Gesture::Pointing || p.gesture == Gesture::Open || p.gesture == Gesture::Fist,
                  "HandPose: the hand's gesture must be pointing, open or fist");
}

}  // namespace gc::sim
