// Text names of the scene presets and motions, as used on command lines and element
// properties.
#include "sim/scene.hpp"

#include <array>
#include <utility>

namespace gc::sim {

namespace {

constexpr std::array<std::pair<Preset, std::string_view>, 4> kPresets{{
    {Preset::Clean, "clean"},
    {Preset::Light, "light"},
    {Preset::Heavy, "heavy"},
    {Preset::FacePass, "face_pass"},
}};

constexpr std::array<std::pair<Motion, std::string_view>, 7> kMotions{{
    {Motion::Static, "static"},
    {Motion::Translate, "translate"},
    {Motion::Rotate, "rotate"},
    {Motion::Scale, "scale"},
    {Motion::Yaw, "yaw"},
    {Motion::Mixed, "mixed"},
    {Motion::LeaveReturn, "leave_return"},
}};

}  // namespace

std::optional<Preset> preset_from_string(std::string_view name)
{
    for (const auto& [p, n] : kPresets)
        if (n == name) return p;
    return std::nullopt;
}

std::optional<Motion> motion_from_string(std::string_view name)
{
    for (const auto& [m, n] : kMotions)
        if (n == name) return m;
    return std::nullopt;
}

std::string_view to_string(Preset p)
{
    for (const auto& [q, n] : kPresets)
        if (q == p) return n;
    return "unknown";
}

std::string_view to_string(Motion m)
{
    for (const auto& [q, n] : kMotions)
        if (q == m) return n;
    return "unknown";
}

}  // namespace gc::sim
