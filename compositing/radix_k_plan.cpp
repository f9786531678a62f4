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
