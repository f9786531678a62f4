#pragma once
// Enums that a scene key names: each enum lists its names once (EnumNames<E>), the parser reads
// them (scene/scene_keys.h, Choice), and nameOf prints them (--stats, errors). Here, below every
// layer, so the types of any layer (the particle set in io/, the scene's sections) can name theirs.
#include <string_view>
#include <type_traits>
#include <utility>

namespace sortlast {

// Specialise EnumNames<E> with `static constexpr std::pair<const char*, E> list[]`.
template <class E>
struct EnumNames;
template <class E>
concept NamedEnum = std::is_enum_v<E> && requires { EnumNames<E>::list; };
// An enum value's name (as the scene key takes it).
template <NamedEnum E>
std::string_view nameOf(E value) {
  for (const auto& [name, v] : EnumNames<E>::list)
    if (v == value) return name;
  return "?";
}

}  // namespace sortlast
