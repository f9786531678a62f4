#pragma once
// Whether a render's trigger fires on a step. A crossing is a change between two steps, so the
// state remembers each render's quantity from the previous call.
#include <map>
#include <string>

#include "insitu/actions.h"

namespace sortlast {

class TriggerState {
 public:
  // Call once per step for every render, in step order, whether or not an earlier render fired:
  // a crossing compares with the value seen on the previous call. Fires when
  //   every N:           step % N == 0;
  //   when Q, crosses X: prev < X <= now or prev > X >= now, with prev the value of Q at the
  //                      previous call (the first call only records it);
  //   both:              either;  neither: every step.
  // Throws InputError naming the render and the quantity if Q is missing from `quantities` or is
  // not finite; the remembered value is then left as it was.
  bool fires(const RenderAction& render, long long step,
             const std::map<std::string, double>& quantities);

 private:
  std::map<std::string, double> previous_;  // by render name
};

}  // namespace sortlast
