#pragma once
// Who holds which image in a radix-k frame, and the bounds of what each unit can hold: every rank
// computes the same plan from the gathered content rectangles, so sender and receiver agree on
// which messages exist (radix_k.cpp). The cost model (strategy_model.h) builds the same plan from
// forecast rectangles, so it counts the messages and pixels the strategy will move.
#include <vector>

#include "common/camera.h"
#include "compositing/schedule.h"

namespace sortlast {

struct RadixKPlan {
  RadixKSchedule schedule;
  std::vector<int> rank_at;   // participant position -> rank, far to near
  std::vector<Rect> content;  // per position: the active rectangle of its own bricks' image
  Rect whole;                 // union of all content

  int carrier(int unit) const { return rank_at[size_t(schedule.firstPosition(unit))]; }
  // A rectangle holding every pixel `unit` may hold before `round`.
  Rect bound(int round, int unit) const;
  // Every unit's region and bound before each round 0 ... rounds() (index [round][unit]), in
  // O(units) a round: bound() costs O(units) at the last rounds, so calling it for every unit
  // (as the cost model does) would cost O(units^2).
  struct Rounds {
    std::vector<std::vector<Rect>> region, bound;
  };
  Rounds everyRound() const;
};

// `ranks_far_to_near`: every rank (VisibilityOrder::ranks); `rect_of_rank[r]`: rank r's content
// (empty: it shows nothing and takes no part). `position_of` (if given) gets each rank's
// participant position, -1 for ranks that take no part.
RadixKPlan makeRadixKPlan(const std::vector<int>& ranks_far_to_near,
                          const std::vector<Rect>& rect_of_rank, int k,
                          std::vector<int>* position_of = nullptr);

}  // namespace sortlast
