// Text names of the scene presets, motions and varieties: the element's enum nicks, used on
// command lines too. Names are spelt with '-'; '_' is accepted where a user types one.
#include "common/enum_names.hpp"
#include "sim/scene.hpp"

#include <algorithm>
#include <string>

namespace gc::sim {

namespace {

constexpr EnumNames<Preset, 5> kPresets{{
    {Preset::Clean, "clean"},
    {Preset::Light, "light"},
    {Preset::Heavy, "heavy"},
    {Preset::FacePass, "face-pass"},
    {Preset::Varied, "varied"},
}};

constexpr EnumNames<Motion, 7> kMotions{{
    {Motion::Static, "static"},
    {Motion::Translate, "translate"},
    {Motion::Rotate, "rotate"},
    {Motion::Scale, "scale"},
    {Motion::Yaw, "yaw"},
    {Motion::Mixed, "mixed"},
    {Motion::LeaveReturn, "leave-return"},
}};

constexpr EnumNames<Variety, 2> kVarieties{{
    {Variety::None, "none"},
    {Variety::Wide, "wide"},
}};

template <class Enum, std::size_t N>
std::optional<Enum> value_named(const EnumNames<Enum, N>& table, std::string_view name)
{
    std::string spelt(name);
    std::replace(spelt.begin(), spelt.end(), '_', '-');
    return value_in(table, spelt);
}

}  // namespace

std::optional<Preset> preset_from_string(std::string_view name) { return value_named(kPresets, name); }
std::optional<Motion> motion_from_string(std::string_view name) { return value_named(kMotions, name); }
std::optional<Variety> variety_from_string(std::string_view name) { return value_named(kVarieties, name); }
std::string_view to_string(Preset p) { return name_in(kPresets, p, "unknown"); }
std::string_view to_string(Motion m) { return name_in(kMotions, m, "unknown"); }
std::string_view to_string(Variety v) { return name_in(kVarieties, v, "unknown"); }

}  // namespace gc::sim
