#pragma once
// Names that clients send (scene files under --data-dir, the viewer's static files) resolved
// inside one directory, never outside it: the service may face a network, and a name like
// "../../etc/passwd" or a symlink pointing out must not reach a file it was not meant to serve.
#include <filesystem>
#include <string>
#include <vector>

namespace sortlast {

// dir/relative, canonical (symlinks resolved). Throws InputError naming the problem for an empty
// name, an absolute path, a ".." component, a path that leads outside canonical(dir) (through a
// symlink, say), or a file that does not exist.
std::filesystem::path resolveUnder(const std::filesystem::path& dir, const std::string& relative);

// The same for a file to write (a recording under --record-dir): it need not exist, but its folder
// must (inside the directory), and an existing one must be a regular file (it is replaced).
std::filesystem::path resolveNewUnder(const std::filesystem::path& dir, const std::string& relative);

// The .yaml/.yml files under `dir` (recursive), as sorted paths relative to it; only those
// resolveUnder accepts. Throws InputError if `dir` is not a readable directory.
std::vector<std::string> listSceneFiles(const std::filesystem::path& dir);

}  // namespace sortlast
