// The table of every scene key (scene/scene_keys.h). Scripts outside the project use these
// names: keep them.
#include "scene/scene_keys.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "scene/key_rows.h"
#include "scene/scene.h"

namespace sortlast {

namespace {

[[noreturn]] void unreadable(const std::string& phrase) {
  throw std::logic_error("scene key table: cannot read the allowed values '" + phrase + "'");
}

bool consume(std::string_view& s, std::string_view prefix) {
  if (!s.starts_with(prefix)) return false;
  s.remove_prefix(prefix.size());
  return true;
}

// A bound as written: a number, a/b or a^b.
double readBound(std::string_view& s, std::string& text, const std::string& phrase) {
  const std::string rest(s);
  char* end = nullptr;
  double v = std::strtod(rest.c_str(), &end);
  size_t n = size_t(end - rest.c_str());
  if (n == 0 || std::isnan(v)) unreadable(phrase);
  if (n < rest.size() && (rest[n] == '/' || rest[n] == '^')) {
    char* end2 = nullptr;
    const double w = std::strtod(rest.c_str() + n + 1, &end2);
    if (end2 == rest.c_str() + n + 1) unreadable(phrase);
    v = rest[n] == '/' ? v / w : std::pow(v, w);
    n = size_t(end2 - rest.c_str());
  }
  text = rest.substr(0, n);
  s.remove_prefix(n);
  return v;
}

std::string joined(const std::vector<std::string>& items, const char* last) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i)
    out += (i == 0 ? "" : i + 1 == items.size() ? last : ", ") + items[i];
  return out;
}

}  // namespace

Allowed::Allowed(const char* phrase) : phrase_(phrase) {
  std::string_view s = phrase_;
  if (consume(s, "a finite number "))
    finite_ = true;
  else if (consume(s, "integers "))
    integer_ = true;
  else if (consume(s, "a power of two "))
    integer_ = power_of_two_ = true;
  const bool interval = consume(s, "in ");
  range_ = std::string(s);
  if (interval) {
    if (s.empty() || (s[0] != '[' && s[0] != '(')) unreadable(phrase_);
    lo_open_ = s[0] == '(';
    s.remove_prefix(1);
    lo_ = readBound(s, lo_text_, phrase_);
    if (!consume(s, ", ")) unreadable(phrase_);
    hi_ = readBound(s, hi_text_, phrase_);
    if (s.size() != 1 || (s[0] != ']' && s[0] != ')') || !(lo_ < hi_)) unreadable(phrase_);
    hi_open_ = s[0] == ')';
    s.remove_prefix(1);
  } else if (consume(s, ">= ")) {
    lo_ = readBound(s, lo_text_, phrase_);
  } else if (consume(s, "> ")) {
    lo_open_ = true;
    lo_ = readBound(s, lo_text_, phrase_);
  } else {  // a list: "4 or 8"
    std::string text;
    do list_.push_back(readBound(s, text, phrase_));
    while (consume(s, " or "));
    if (list_.size() < 2) unreadable(phrase_);
  }
  if (!s.empty()) unreadable(phrase_);
}

bool Allowed::admits(double v) const {
  if (std::isnan(v) || (finite_ && !std::isfinite(v)) || (integer_ && v != std::floor(v)))
    return false;
  if (!list_.empty()) return std::find(list_.begin(), list_.end(), v) != list_.end();
  if (lo_open_ ? !(v > lo_) : !(v >= lo_)) return false;
  if (hi_open_ ? !(v < hi_) : !(v <= hi_)) return false;
  if (power_of_two_) {
    const auto n = static_cast<unsigned long long>(v);  // in range, so finite and >= 1
    return (n & (n - 1)) == 0;
  }
  return true;
}

Allowed Allowed::within(const Allowed& other) const {
  if (isList()) return *this;
  if (other.isList()) return other;
  Allowed r = *this;
  if (other.lo_ > r.lo_ || (other.lo_ == r.lo_ && other.lo_open_))
    r.lo_ = other.lo_, r.lo_open_ = other.lo_open_, r.lo_text_ = other.lo_text_;
  if (other.hi_ < r.hi_ || (other.hi_ == r.hi_ && other.hi_open_))
    r.hi_ = other.hi_, r.hi_open_ = other.hi_open_, r.hi_text_ = other.hi_text_;
  r.finite_ = r.finite_ || other.finite_;
  r.integer_ = r.integer_ || other.integer_;
  r.power_of_two_ = r.power_of_two_ || other.power_of_two_;
  return r;
}

std::string Allowed::describe() const {
  if (isList()) return range_;
  const bool low = std::isfinite(lo_), high = std::isfinite(hi_);
  std::string bounds;
  if (low && high)
    bounds = "in " + std::string(lo_open_ ? "(" : "[") + lo_text_ + ", " + hi_text_ +
             (hi_open_ ? ")" : "]");
  else if (low)
    bounds = (lo_open_ ? "> " : ">= ") + lo_text_;
  else if (high)
    bounds = (hi_open_ ? "< " : "<= ") + hi_text_;
  return power_of_two_ ? "power of two " + bounds : bounds;
}

std::string fillMessage(std::string_view key, std::string_view says,
                        const std::vector<std::pair<std::string_view, std::string>>& values) {
  std::string out;
  bool names_key = false;
  for (size_t i = 0; i < says.size();) {
    const size_t open = says.find('{', i);
    out += says.substr(i, open - i);
    if (open == std::string_view::npos) break;
    const size_t close = says.find('}', open);
    const std::string_view name = says.substr(open + 1, close - open - 1);
    if (name == "key") {
      out += key;
      names_key = true;
    } else {
      auto it = std::find_if(values.begin(), values.end(),
                             [&](const auto& v) { return v.first == name; });
      if (close == std::string_view::npos || it == values.end())
        throw std::logic_error("scene key table: message '" + std::string(says) + "' has no {" +
                               std::string(name) + "}");
      out += it->second;
    }
    i = close + 1;
  }
  return names_key ? out : "scene key '" + std::string(key) + "': " + out;
}

std::string Check::error(std::string_view key, const std::string& value,
                         const std::string& text) const {
  return fillMessage(key, says ? says : "must be {allowed}",
                     {{"allowed", allowed.phrase()},
                      {"range", allowed.range()},
                      {"value", value},
                      {"text", text}});
}

std::string choiceError(std::string_view key, std::string_view says,
                        const std::vector<std::string>& names, const std::string& text) {
  return fillMessage(
      key, says, {{"names", joined(names, " or ")}, {"list", joined(names, ", ")}, {"text", text}});
}

namespace {

// The table: every section's rows, in the order of docs/scene.md.
std::vector<SceneKey> makeTable() {
  std::vector<SceneKey> table;
  for (auto rows : {volumeKeys, particleKeys, transferKeys, volumesKeys, imageKeys, cameraKeys, clipKeys, brickKeys, renderKeys,
                    adaptiveKeys, compositingKeys, timeKeys, limitKeys, glowKeys, surfaceKeys, referenceKeys}) {
    std::vector<SceneKey> section = rows();
    table.insert(table.end(), std::make_move_iterator(section.begin()), std::make_move_iterator(section.end()));
  }
  return table;
}

}  // namespace

const std::vector<SceneKey>& sceneKeys() {
  static const std::vector<SceneKey> keys = makeTable();
  return keys;
}

const SceneKey* findSceneKey(std::string_view path) {
  for (const SceneKey& k : sceneKeys())
    if (path == k.path) return &k;
  return nullptr;
}

const SceneKey& sceneKey(std::string_view path) {
  if (const SceneKey* k = findSceneKey(path)) return *k;
  throw std::logic_error("no scene key '" + std::string(path) + "' in the table");
}

const std::vector<Check>& sceneKeyChecks(std::string_view path) {
  static const std::vector<Check> none;
  return std::visit(
      [](const auto& type) -> const std::vector<Check>& {
        if constexpr (requires { type.checks; })
          return type.checks;
        else
          return none;
      },
      sceneKey(path).type);
}

namespace {

// What the checks of a number (or of each entry of a list) allow together, for the docs.
std::string bounds(const std::vector<Check>& checks) {
  std::optional<Allowed> all;
  for (const Check& c : checks)
    if (!c.of_length) all = all ? all->within(c.allowed) : c.allowed;
  return all ? all->describe() : "";
}

std::string lengthBounds(const std::vector<Check>& checks) {
  for (const Check& c : checks)
    if (c.of_length) return "length " + c.allowed.describe();
  return "";
}

// The non-empty parts, joined.
std::string sentence(std::initializer_list<std::string> parts, const char* separator = " ") {
  std::string out;
  for (const std::string& p : parts)
    if (!p.empty()) out += (out.empty() ? "" : separator) + p;
  return out;
}

template <class T>
std::string values(const Number<T>& n) {
  const bool listed = std::any_of(n.checks.begin(), n.checks.end(),
                                  [](const Check& c) { return c.allowed.isList(); });
  const std::string b = bounds(n.checks);
  if (listed || b.starts_with("power of two")) return b;  // "4 or 8": integers anyway
  return sentence({std::is_integral_v<T> ? "integer" : "number", b});
}
std::string values(const Flag&) { return "`true` or `false`"; }
std::string values(const Text& t) { return t.file ? "file name" : "string"; }
std::string values(const Choice& c) {
  std::vector<std::string> quoted;
  for (const std::string& name : c.names) quoted.push_back("`" + name + "`");
  return joined(quoted, " or ");
}
template <class T>
std::string values(const Vector<T>& v) {
  constexpr bool integer = std::is_same_v<T, glm::ivec3>;
  return sentence(
      {sentence({integer ? "3 integers" : "3 numbers", bounds(v.checks)}), lengthBounds(v.checks)},
      ", ");
}
std::string values(const Structured& s) { return s.values; }

}  // namespace

std::string sceneKeyValues(const SceneKey& key) {
  const std::string v = std::visit([](const auto& type) { return values(type); }, key.type);
  if (!key.auto_value) return v;
  return std::holds_alternative<Flag>(key.type) ? "`auto`, `true` or `false`" : "`auto` or " + v;
}

std::string sceneKeysMarkdown() {
  std::ostringstream md;
  md << "# Scene keys\n\n"
        "A scene is a YAML file of nested maps; `a.b.c` below means `a: {b: {c: ...}}`. Every key "
        "may be omitted (its default applies) and overridden on the command line with "
        "`--set a.b.c=VALUE` (VALUE is YAML: `--set volume.dims=[64,64,64]`). Unknown keys are "
        "errors, and so is a value outside what the key takes (the values column). This page is "
        "generated by `sortlast keys` from the table the parser reads the keys through; a test "
        "checks it is current.\n\n"
        "| key | default | values | meaning |\n| --- | --- | --- | --- |\n";
  for (const SceneKey& k : sceneKeys())
    md << "| `" << k.path << "` | `" << k.default_yaml << "` | " << sceneKeyValues(k) << " | "
       << k.doc << " |\n";
  return md.str();
}

}  // namespace sortlast
