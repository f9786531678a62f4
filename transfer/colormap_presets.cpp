#include "transfer/colormap_presets.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

#include "transfer/colormap_data.h"
#include "common/error.h"

namespace sortlast {

namespace {

struct Builtin {
  std::string alias;  // the file's stem
  ColourMap map;
};

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Parsed once, on first use (a resident session parses its scene with every request).
const std::vector<Builtin>& builtins() {
  static const std::vector<Builtin> all = [] {
    std::vector<Builtin> v;
    for (const EmbeddedColourMap& e : embeddedColourMaps())
      v.push_back({e.stem, parseColourMapJson(
                               e.json, std::string("built-in colour map ") + e.stem + ".json")});
    return v;
  }();
  return all;
}

const Builtin* findBuiltin(const std::string& name) {
  for (const Builtin& b : builtins()) {
    const std::string& full = b.map.name;
    std::string shortName = full.substr(0, full.find(" ("));
    if (name == full || name == shortName || name == b.alias) return &b;
  }
  return nullptr;
}

}  // namespace

std::vector<std::string> builtinColourMapNames() {
  std::vector<std::string> names;
  for (const Builtin& b : builtins()) names.push_back(b.map.name + " (" + b.alias + ")");
  return names;
}

bool isBuiltinColourMap(const std::string& name) { return findBuiltin(name) != nullptr; }

bool namesColourMapFile(const std::string& value) {
  std::string l = lower(value);
  return l.find(".json#") != std::string::npos || (l.size() > 5 && l.ends_with(".json"));
}

ColourMap loadColourMap(const std::string& value, const std::filesystem::path& base_dir) {
  if (!namesColourMapFile(value)) {
    if (const Builtin* b = findBuiltin(value)) return b->map;
    std::string known;
    for (const std::string& n : builtinColourMapNames()) known += (known.empty() ? "" : ", ") + n;
    throw InputError("unknown colour map '" + value + "' (built in: " + known +
                     "; or a ParaView preset file, FILE.json or FILE.json#Name)");
  }
  size_t hash = lower(value).find(".json#");
  std::string file = hash == std::string::npos ? value : value.substr(0, hash + 5);
  std::string pick = hash == std::string::npos ? "" : value.substr(hash + 6);
  std::filesystem::path path(file);
  if (path.is_relative()) path = base_dir / path;
  const std::string source = "colour-map file " + path.string();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(source + ": is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(source + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(source + ": cannot read");
  return parseColourMapJson(text.str(), source, pick);
}

}  // namespace sortlast
