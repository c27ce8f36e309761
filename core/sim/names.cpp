// Text names of the scene presets, motions and varieties: the element's enum nicks, used on
// command lines too. Names are spelt with '-'; '_' is accepted where a user types one.
#include "sim/scene.hpp"

#include <algorithm>
#include <array>
#include <string>
#include <utility>

namespace gc::sim {

namespace {

constexpr std::array<std::pair<Preset, std::string_view>, 5> kPresets{{
    {Preset::Clean, "clean"},
    {Preset::Light, "light"},
    {Preset::Heavy, "heavy"},
    {Preset::FacePass, "face-pass"},
    {Preset::Varied, "varied"},
}};

constexpr std::array<std::pair<Motion, std::string_view>, 7> kMotions{{
    {Motion::Static, "static"},
    {Motion::Translate, "translate"},
    {Motion::Rotate, "rotate"},
    {Motion::Scale, "scale"},
    {Motion::Yaw, "yaw"},
    {Motion::Mixed, "mixed"},
    {Motion::LeaveReturn, "leave-return"},
}};

constexpr std::array<std::pair<Variety, std::string_view>, 2> kVarieties{{
    {Variety::None, "none"},
    {Variety::Wide, "wide"},
}};

template <class Table, class Value>
std::string_view name_of(const Table& table, Value v)
{
    for (const auto& [q, n] : table)
        if (q == v) return n;
    return "unknown";
}

template <class Value, std::size_t N>
std::optional<Value> value_of(const std::array<std::pair<Value, std::string_view>, N>& table, std::string_view name)
{
    std::string spelt(name);
    std::replace(spelt.begin(), spelt.end(), '_', '-');
    for (const auto& [v, n] : table)
        if (n == spelt) return v;
    return std::nullopt;
}

}  // namespace

std::optional<Preset> preset_from_string(std::string_view name) { return value_of(kPresets, name); }
std::optional<Motion> motion_from_string(std::string_view name) { return value_of(kMotions, name); }
std::optional<Variety> variety_from_string(std::string_view name) { return value_of(kVarieties, name); }
std::string_view to_string(Preset p) { return name_of(kPresets, p); }
std::string_view to_string(Motion m) { return name_of(kMotions, m); }
std::string_view to_string(Variety v) { return name_of(kVarieties, v); }

}  // namespace gc::sim
