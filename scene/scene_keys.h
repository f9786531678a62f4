#pragma once
// The table of every scene key (scene_keys.cpp): its type, default, allowed range or values and
// help text, and the Scene field it fills. parseScene reads every typed key through its row (so a
// new key is one row plus its field), range errors are worded by the row, and `sortlast keys`
// prints the table as docs/scene.md. Keys with structure of their own (transfer points, file
// series, glow emitters, surfaces, glow.box, ...) are `Structured`: parseScene's own code reads
// them, with the row's default and, where the row has them, its checks.
#include <glm/glm.hpp>
#include <functional>
#include <iterator>
#include <type_traits>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "common/enum_names.h"
#include "io/volume_source.h"

namespace sortlast {

struct Scene;

// Where a key's value goes: a function returning a reference to a Scene member, written
// member<&Scene::camera, &Camera::fov_deg> for scene.camera.fov_deg.
template <class T>
using Field = T& (*)(Scene&);
// clang-format off
template <auto... Members>
auto& member(Scene& s) { return (s .* ... .* Members); }
// clang-format on

// The values a number may take, in the words the error messages and docs use:
//   "in [0, 1e9]", "in (0, 180)", "in [1/64, 8]"   an interval (bounds: a number, a/b or a^b)
//   ">= 1", "> 0"                                   a half-line (+inf included)
//   "4 or 8"                                        a list
// optionally after "a finite number " (+-inf refused), "integers " or "a power of two ".
// NaN is never admitted.
class Allowed {
 public:
  Allowed(const char* phrase);  // throws std::logic_error on a phrase it cannot read
  bool admits(double v) const;
  const std::string& phrase() const { return phrase_; }  // as written
  const std::string& range() const { return range_; }    // the phrase less its qualifier and "in "

  // For the docs and tests: the intersection with `other` (bounds written as the tighter one
  // writes them), and the values in words ("in [1e-12, 1e18]", ">= 1", "power of two in [1, 256]").
  Allowed within(const Allowed& other) const;
  std::string describe() const;
  bool isList() const { return !list_.empty(); }
  const std::vector<double>& list() const { return list_; }
  double lo() const { return lo_; }
  double hi() const { return hi_; }
  bool loOpen() const { return lo_open_; }
  bool hiOpen() const { return hi_open_; }

 private:
  std::string phrase_, range_, lo_text_, hi_text_;
  double lo_ = -std::numeric_limits<double>::infinity(),
         hi_ = std::numeric_limits<double>::infinity();
  bool lo_open_ = false, hi_open_ = false, finite_ = false, integer_ = false, power_of_two_ = false;
  std::vector<double> list_;
};

// One check of a number, or of each entry (or the length) of a list of numbers, with its error
// after "scene key 'KEY': ". The message may use {allowed} (the phrase), {range} (its interval),
// {value} (the value: %g, integers in full) and {text} (the value as written); a message that
// names {key} itself is the whole message. Messages differ between keys where they always have
// (units, a note, "got ..."): each row keeps its key's wording.
struct Check {
  Allowed allowed;
  // nullptr: parseScene words the error (a message that names two keys).
  const char* says = "must be {allowed}";
  bool of_length = false;  // a list: the check is of the vector's length

  std::string error(std::string_view key, const std::string& value, const std::string& text) const;
};

// A message: `says` with {key} and the named values filled in, after "scene key 'KEY': " unless
// it names {key} itself.
std::string fillMessage(std::string_view key, std::string_view says,
                        const std::vector<std::pair<std::string_view, std::string>>& values);
// A Choice's error: {names} "a, b or c", {list} "a, b, c", {text} the name given.
std::string choiceError(std::string_view key, std::string_view says,
                        const std::vector<std::string>& names, const std::string& text);

// The key types. A number is read as T (double, int, long long: "expected a number" / "an
// integer"), or std::optional<double> for a key that may be `auto` (then unset).
template <class T>
struct Number {
  Field<T> field;
  std::vector<Check> checks = {};
};
struct Flag {
  Field<bool> field;
};
struct Text {
  Field<std::string> field;
  // A file name: relative to the scene file (to the working directory when given with --set).
  bool file = false;
};
// One of a list of names, each standing for a value of the field.
struct Choice {
  static constexpr const char* kSays = "expected {names}, got '{text}'";
  std::vector<std::string> names;
  std::function<void(Scene&, size_t)> set;  // the field takes the value names[i] stands for
  // {names}: "a, b or c"; {list}: "a, b, c"; {text}: the value given.
  const char* says = kSays;

  template <class T>
  Choice(Field<T> field, std::vector<std::pair<const char*, T>> named, const char* says_ = kSays)
      : says(says_) {
    std::vector<T> values;
    for (auto& [name, value] : named) {
      names.emplace_back(name);
      values.push_back(std::move(value));
    }
    set = [field, values = std::move(values)](Scene& s, size_t i) { field(s) = values[i]; };
  }
  // An enum's names (kEnumNames, common/enum_names.h).
  template <NamedEnum E>
  Choice(Field<E> field, const char* says_ = kSays) : Choice(field, enumNamesAndValues<E>(), says_) {}
};
// A list of 3 numbers (glm::ivec3: integers; say so with an "integers ..." check).
template <class T>
struct Vector {
  Field<T> field;
  std::vector<Check> checks = {};
};
// Read by parseScene's own code. `values`: what the docs say it takes.
struct Structured {
  const char* values;
  std::vector<Check> checks = {};  // of each number it holds, where it has them
};

using KeyType =
    std::variant<Number<double>, Number<std::optional<double>>, Number<int>, Number<long long>,
                 Flag, Text, Choice,
                 Vector<glm::dvec3>, Vector<glm::ivec3>, Structured>;

// `auto` (or null) is a value of the key: the field keeps its default (an optional stays unset,
// or parseScene derives the value), and `flag`, if given, says whether the key was auto.
struct AutoValue {
  Field<bool> flag = nullptr;
};

struct SceneKey {
  const char* path;          // dotted key, e.g. "camera.orbit.frames"
  const char* default_yaml;  // default value as YAML ("auto" where it is derived)
  const char* doc;
  KeyType type;
  std::optional<AutoValue> auto_value = std::nullopt;
};

// Every key, in the order of docs/scene.md.
const std::vector<SceneKey>& sceneKeys();
// The row of `path`; nullptr if there is none.
const SceneKey* findSceneKey(std::string_view path);
// The row of a key the caller knows exists (throws std::logic_error if not).
const SceneKey& sceneKey(std::string_view path);
// The checks of a key's numbers (none for a key that has none).
const std::vector<Check>& sceneKeyChecks(std::string_view path);
// What the docs say a key takes ("number in (0, 1]", "`auto` or integer in [1, 64]", ...).
std::string sceneKeyValues(const SceneKey& key);
// The whole table as docs/scene.md (`sortlast keys`).
std::string sceneKeysMarkdown();

}  // namespace sortlast
