#pragma once
// What to tell a user whose command line names a subcommand or option that does not exist: the
// word as typed and the nearest one that does ("unknown subcommand 'rendr'; did you mean
// 'render'?"), instead of CLI11's "A subcommand is required".
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace sortlast {

// The known name closest to `typed` by edit distance (insertions, deletions, substitutions and
// swaps of neighbours), if it is close enough to be a typo: at most 2 edits, and at most a third
// of the typed word's length for short words. Empty: none is.
std::string nearestName(const std::string& typed, const std::vector<std::string>& known);

// After CLI11 refused the command line: a message naming the first unknown subcommand or option of
// argv and the nearest known one, or empty if the error is of another kind (a missing value, a
// value out of range), which CLI11's own message says better.
std::string commandLineHint(CLI::App& app, int argc, const char* const* argv);

}  // namespace sortlast
