#pragma once
// A comma-separated command-line list ("direct,radix-k:4") as its non-empty items, for the
// benchmark drivers (bench_compositing, bench/scale/bench_scale in both its builds).
#include <sstream>
#include <string>
#include <vector>

namespace sortlast {

inline std::vector<std::string> splitCommas(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string t; std::getline(ss, t, ',');)
    if (!t.empty()) out.push_back(t);
  return out;
}

}  // namespace sortlast
