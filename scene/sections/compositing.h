#pragma once
// The compositing section (compositing.*): how brick images reach rank 0. Rows: compositing.cpp.
#include <utility>

#include "scene/scene_keys.h"

namespace sortlast {

// compositing.strategy
enum class Strategy { kDirect, kBinarySwap, kRadixK, kAuto };
template <>
struct EnumNames<Strategy> {
  static constexpr std::pair<const char*, Strategy> list[] = {{"direct", Strategy::kDirect},
                                                               {"binary-swap", Strategy::kBinarySwap},
                                                               {"radix-k", Strategy::kRadixK},
                                                               {"auto", Strategy::kAuto}};
};

// compositing.precision: how partial results are held. kFloat: blend in float, round to RGBA8
// once per frame (partial composites travel at 16 bits), so every strategy and rank count gives
// the same frame within 1/255. kRgba8: the paper's intermediate images; direct send rounds after
// every blend, the swap strategies send their partial composites as RGBA8 (fewer bytes, up to
// half a step of error per round).
enum class Precision { kFloat, kRgba8 };
template <>
struct EnumNames<Precision> {
  static constexpr std::pair<const char*, Precision> list[] = {{"float", Precision::kFloat},
                                                                {"rgba8", Precision::kRgba8}};
};

struct CompositingSection {
  Strategy strategy = Strategy::kDirect;
  int radix = 4;                // radix-k: partners per round
  double latency_us = 40;       // auto: the network its cost model assumes
  double bandwidth_gbps = 10;
  Precision precision = Precision::kFloat;
  bool overlap = true;  // direct send: send while the next brick renders
  bool rle = true;      // run-length code image messages
};

}  // namespace sortlast
