// Names of enum values kept in one table a type, read both ways: the value's name for output
// and the value a name stands for. A name is text, or the value's counterpart in another
// library's enum.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>
#include <type_traits>
#include <utility>

namespace gc {

template <class Enum, std::size_t N, class Name = std::string_view>
using EnumNames = std::array<std::pair<Enum, Name>, N>;

// The name of `value`, or `fallback` for a value the table lacks (a cast integer).
template <class Enum, std::size_t N, class Name>
constexpr Name name_in(const EnumNames<Enum, N, Name>& table, Enum value, std::type_identity_t<Name> fallback)
{
    for (const auto& [v, name] : table)
        if (v == value) return name;
    return fallback;
}

// The value named `name` exactly, if the table has it.
template <class Enum, std::size_t N, class Name>
constexpr std::optional<Enum> value_in(const EnumNames<Enum, N, Name>& table, std::type_identity_t<Name> name)
{
    for (const auto& [v, n] : table)
        if (n == name) return v;
    return std::nullopt;
}

}  // namespace gc
