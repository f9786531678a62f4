#pragma once
// The built-in colour maps and the value of `transfer.colormap`: a built-in's name, or a ParaView
// preset file. The built-ins are ParaView preset files too (transfer/colormaps/*.json, compiled in
// at build time), read by the same parser as a user's file, so every built-in exercises it.
#include <filesystem>
#include <string>
#include <vector>

#include "transfer/colormap.h"

namespace sortlast {

// Every built-in as "ParaView name (alias)", e.g. "Viridis (matplotlib) (viridis)".
std::vector<std::string> builtinColourMapNames();

// Whether `name` is a built-in's name: its ParaView name ("Black-Body Radiation"), that name
// without a parenthesised suffix ("Viridis"), or its lowercase alias, the file's stem
// ("black_body").
bool isBuiltinColourMap(const std::string& name);

// Whether `value` names a file: it ends in ".json", or holds ".json#" (FILE.json#Name).
bool namesColourMapFile(const std::string& value);

// `value` as transfer.colormap takes it: a built-in's name, or FILE.json / FILE.json#Name (a
// relative FILE is relative to base_dir). Throws InputError naming the file and the problem, or
// for an unknown name, listing the built-ins.
ColourMap loadColourMap(const std::string& value, const std::filesystem::path& base_dir);

}  // namespace sortlast
