// The strategy selector: the one place that maps compositing.strategy to an implementation.
#include "compositing/compositor.h"

#include <stdexcept>

#include "compositing/direct_send.h"

namespace sortlast {

std::unique_ptr<Compositor> makeCompositor(const std::string& strategy) {
  if (strategy == "direct") return std::make_unique<DirectSend>();
  throw std::invalid_argument("unknown compositing strategy '" + strategy + "'");
}

}  // namespace sortlast
