// The strategy selector: the one place that maps compositing.strategy to an implementation.
#include "compositing/compositor.h"

#include <stdexcept>

#include "compositing/direct_send.h"
#include "compositing/radix_k.h"

namespace sortlast {

std::unique_ptr<Compositor> makeCompositor(const std::string& strategy, int radix) {
  if (strategy == "direct") return std::make_unique<DirectSend>();
  if (strategy == "binary-swap") return std::make_unique<RadixK>(2);
  if (strategy == "radix-k") return std::make_unique<RadixK>(radix);
  throw std::invalid_argument("unknown compositing strategy '" + strategy + "'");
}

}  // namespace sortlast
