#include "compositing/radix_k_plan.h"

#include "compositing/rect_image.h"

namespace sortlast {

Rect RadixKPlan::bound(int round, int unit) const {
  auto [first, last] = schedule.mergedUnits(round, unit);
  Rect r;
  for (int p = schedule.firstPosition(first); p <= schedule.lastPosition(last); ++p)
    r = unionOf(r, content[size_t(p)]);
  return intersect(r, schedule.region(round, unit, whole));
}

RadixKPlan::Rounds RadixKPlan::everyRound() const {
  const RadixKSchedule& s = schedule;
  const int units = s.units();
  Rounds out;
  out.region.assign(size_t(s.rounds()) + 1, std::vector<Rect>(size_t(units)));
  out.bound = out.region;
  // run[j]: the content of the j-th run of `stride` units, the runs merged before this round.
  std::vector<Rect> run(static_cast<size_t>(units));
  for (int u = 0; u < units; ++u)
    for (int p = s.firstPosition(u); p <= s.lastPosition(u); ++p)
      run[size_t(u)] = unionOf(run[size_t(u)], content[size_t(p)]);
  int stride = 1;
  out.region[0].assign(size_t(units), whole);
  for (int t = 0; t <= s.rounds(); ++t) {
    if (t > 0) {  // each group of round t - 1 splits its one region among its members
      const int k = s.radices[size_t(t) - 1], prev = stride / k;
      for (int base = 0; base < units; ++base) {
        if (s.digit(t - 1, base) != 0) continue;
        const std::vector<Rect> parts = splitRect(out.region[size_t(t) - 1][size_t(base)], k);
        for (int j = 0; j < k; ++j) out.region[size_t(t)][size_t(base + j * prev)] = parts[size_t(j)];
      }
    }
    for (int u = 0; u < units; ++u)
      out.bound[size_t(t)][size_t(u)] = intersect(run[size_t(u / stride)], out.region[size_t(t)][size_t(u)]);
    if (t == s.rounds()) break;
    const int k = s.radices[size_t(t)];
    std::vector<Rect> next(static_cast<size_t>(units / (stride * k)));
    for (size_t j = 0; j < run.size() && j / size_t(k) < next.size(); ++j)
      next[j / size_t(k)] = unionOf(next[j / size_t(k)], run[j]);
    run = std::move(next);
    stride *= k;
  }
  return out;
}

RadixKPlan makeRadixKPlan(const std::vector<int>& ranks_far_to_near,
                          const std::vector<Rect>& rect_of_rank, int k,
                          std::vector<int>* position_of) {
  RadixKPlan plan;
  if (position_of) position_of->assign(rect_of_rank.size(), -1);
  for (int r : ranks_far_to_near) {
    const Rect& rc = rect_of_rank[size_t(r)];
    if (rc.empty()) continue;
    if (position_of) (*position_of)[size_t(r)] = int(plan.rank_at.size());
    plan.rank_at.push_back(r);
    plan.content.push_back(rc);
    plan.whole = unionOf(plan.whole, rc);
  }
  plan.schedule = makeRadixKSchedule(int(plan.rank_at.size()), k);
  return plan;
}

}  // namespace sortlast
