#pragma once
// Enums that a scene key names. Each lists its names once, in the order of its enumerators
// (0, 1, ...), beside its declaration:
//   enum class ToneMap { kNone, kExponential };
//   template <> inline constexpr std::array kEnumNames<ToneMap>{"none", "exponential"};
// The parser reads them (scene/scene_keys.h, Choice) and nameOf prints them (--stats, errors).
// Here, below every layer, so the types of any layer (the particle set in io/, the scene's
// sections) can name theirs.
#include <array>
#include <cstddef>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace sortlast {

template <class E>
inline constexpr std::array<const char*, 0> kEnumNames{};
template <class E>
concept NamedEnum = std::is_enum_v<E> && (kEnumNames<E>.size() > 0);

// An enum value's name (as the scene key takes it).
template <NamedEnum E>
std::string_view nameOf(E value) {
  const auto i = static_cast<size_t>(value);
  return i < kEnumNames<E>.size() ? kEnumNames<E>[i] : "?";
}

// Every name with the value it stands for.
template <NamedEnum E>
std::vector<std::pair<const char*, E>> enumNamesAndValues() {
  std::vector<std::pair<const char*, E>> out;
  for (size_t i = 0; i < kEnumNames<E>.size(); ++i) out.emplace_back(kEnumNames<E>[i], static_cast<E>(i));
  return out;
}

}  // namespace sortlast
