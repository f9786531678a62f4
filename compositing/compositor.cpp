// The strategy selector: the one place that maps compositing.strategy to an implementation.
#include "compositing/compositor.h"

#include <stdexcept>

#include "compositing/auto_compositor.h"
#include "compositing/direct_send.h"
#include "compositing/radix_k.h"

namespace sortlast {

ImageRGBA8 Compositor::composite(std::vector<BrickImage> mine, const VisibilityOrder& order,
                                 int width, int height, MPI_Comm comm, CompositeStats& stats,
                                 const FrameFootprint* footprint) {
  begin(FrameSetup{&order, int(mine.size()), width, height, comm, footprint});
  for (BrickImage& b : mine) add(std::move(b));
  return finish(stats);
}

std::unique_ptr<Compositor> makeCompositor(Strategy strategy, int radix, const CompositeOptions& options) {
  switch (strategy) {
    case Strategy::kDirect: return std::make_unique<DirectSend>(options);
    case Strategy::kBinarySwap: return std::make_unique<RadixK>(2, options);
    case Strategy::kRadixK: return std::make_unique<RadixK>(radix, options);
    case Strategy::kAuto: return std::make_unique<AutoCompositor>(options);
  }
  throw std::logic_error("makeCompositor: no such strategy");
}

std::unique_ptr<Compositor> makeCompositor(const std::string& strategy, int radix,
                                           const CompositeOptions& options) {
  for (const auto& [name, value] : enumNamesAndValues<Strategy>())
    if (strategy == name) return makeCompositor(value, radix, options);
  throw std::invalid_argument("unknown compositing strategy '" + strategy + "'");
}

}  // namespace sortlast
