#pragma once
// Where an installed copy of sortlast keeps its files, seen from a running binary: the program
// in <prefix>/CMAKE_INSTALL_BINDIR, libsortlast.so in <prefix>/CMAKE_INSTALL_LIBDIR (Debian's
// multiarch lib/x86_64-linux-gnu, a site's lib64), the viewer in <prefix>/CMAKE_INSTALL_DATADIR.
// Finding the prefix first works for every layout; "<binary's folder>/../share" does not.
#include <filesystem>
#include <string>

namespace sortlast {

// The prefix under which `file` was installed into `subdir` (relative to the prefix): the file's
// folder with one level removed per component of `subdir`. Empty when `subdir` is absolute (a
// folder outside the prefix says nothing about it).
std::filesystem::path installPrefixOf(const std::filesystem::path& file, const std::string& subdir);

}  // namespace sortlast
