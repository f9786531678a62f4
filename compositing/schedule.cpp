#include "compositing/schedule.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace sortlast {

namespace {

int largestPrimeFactor(int n) {
  int largest = 1;
  for (int p = 2; p * p <= n; ++p)
    while (n % p == 0) {
      largest = p;
      n /= p;
    }
  return n > 1 ? std::max(largest, n) : largest;
}

}  // namespace

int RadixKSchedule::stride(int round) const {
  int s = 1;
  for (int t = 0; t < round; ++t) s *= radices[size_t(t)];
  return s;
}

std::vector<int> RadixKSchedule::group(int round, int unit) const {
  const int s = stride(round), k = radices[size_t(round)];
  const int base = unit - digit(round, unit) * s;
  std::vector<int> g(size_t(k), 0);
  for (int j = 0; j < k; ++j) g[size_t(j)] = base + j * s;
  return g;
}

std::pair<int, int> RadixKSchedule::mergedUnits(int round, int unit) const {
  const int s = stride(round);
  const int first = unit / s * s;
  return {first, first + s - 1};
}

Rect RadixKSchedule::region(int round, int unit, const Rect& whole) const {
  Rect r = whole;
  for (int t = 0; t < round; ++t) r = splitRect(r, radices[size_t(t)])[size_t(digit(t, unit))];
  return r;
}

RadixKSchedule makeRadixKSchedule(int participants, int k) {
  if (k < 2) throw std::invalid_argument("radix-k: k must be >= 2, got " + std::to_string(k));
  if (participants < 0) throw std::invalid_argument("radix-k: negative participant count");
  RadixKSchedule s;
  s.participants = participants;
  int units = participants;
  while (units > 1 && largestPrimeFactor(units) > k) --units;  // stops at a power of two at worst
  s.folds = participants - units;
  for (int m = units; m > 1;) {
    int f = std::min(k, m);
    while (m % f != 0) --f;
    s.radices.push_back(f);
    m /= f;
  }
  return s;
}

std::vector<Rect> splitRect(const Rect& r, int parts) {
  std::vector<Rect> out;
  out.reserve(size_t(parts));
  if (r.empty()) {
    out.assign(size_t(parts), Rect{r.x, r.y, 0, 0});
    return out;
  }
  const bool along_x = r.w >= r.h;
  const int len = along_x ? r.w : r.h;
  for (int j = 0; j < parts; ++j) {
    int lo = int(1LL * len * j / parts), hi = int(1LL * len * (j + 1) / parts);
    out.push_back(along_x ? Rect{r.x + lo, r.y, hi - lo, r.h} : Rect{r.x, r.y + lo, r.w, hi - lo});
  }
  return out;
}

}  // namespace sortlast
