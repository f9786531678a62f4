#include "insitu/trigger.h"

#include <cmath>
#include <sstream>

#include "common/error.h"

namespace sortlast {

bool TriggerState::fires(const RenderAction& render, long long step,
                         const std::map<std::string, double>& quantities) {
  const Trigger& t = render.trigger;
  const bool periodic = t.every > 0 && step % t.every == 0;
  if (t.when.empty()) return t.every <= 0 || periodic;

  auto it = quantities.find(t.when);
  if (it == quantities.end()) {
    std::string known;
    for (const auto& [name, value] : quantities) known += (known.empty() ? "" : ", ") + name;
    throw InputError("render '" + render.name + "': its trigger needs the quantity '" + t.when +
                     "', which step " + std::to_string(step) +
                     " did not publish (published: " + (known.empty() ? "none" : known) + ")");
  }
  const double now = it->second;
  if (!std::isfinite(now)) {
    std::ostringstream v;
    v << now;
    throw InputError("render '" + render.name + "': quantity '" + t.when + "' is " + v.str() +
                     " at step " + std::to_string(step));
  }
  auto [prev, first] = previous_.try_emplace(render.name, now);
  bool crossed = false;
  if (!first) {
    const double x = t.crosses.value_or(0.0), before = prev->second;
    crossed = (before < x && x <= now) || (before > x && x >= now);
    prev->second = now;
  }
  return periodic || crossed;
}

}  // namespace sortlast
