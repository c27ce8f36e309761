// Names of enum values kept in one table a type, read both ways: the value's name for output
// and the value a typed name stands for.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>
#include <utility>

namespace gc {

template <class Enum>
using EnumName = std::pair<Enum, std::string_view>;

template <class Enum, std::size_t N>
using EnumNames = std::array<EnumName<Enum>, N>;

// The name of `value`, or `fallback` for a value the table lacks (a cast integer).
template <class Enum, std::size_t N>
constexpr std::string_view name_in(const EnumNames<Enum, N>& table, Enum value, std::string_view fallback)
{
    for (const auto& [v, name] : table)
        if (v == value) return name;
    return fallback;
}

// The value named `name` exactly, if the table has it.
template <class Enum, std::size_t N>
constexpr std::optional<Enum> value_in(const EnumNames<Enum, N>& table, std::string_view name)
{
    for (const auto& [v, n] : table)
        if (n == name) return v;
    return std::nullopt;
}

}  // namespace gc
