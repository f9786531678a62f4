#pragma once
// A dump of one rendered frame (`sortlast render --dump-layers DIR`): order.txt holds the frame
// size and the brick order far to near, brick_ID.bin each brick's packed image. Read by the
// compositing benchmarks (bench_compositing, bench_scale --layers), which deal the order's bricks
// to P ranks as contiguous runs, the way a kd-split's convex groups of bricks lie in it.
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "compositing/brick_image.h"
#include "compositing/rle.h"

namespace sortlast {

struct LayerDump {
  int width = 0, height = 0;
  std::vector<int> order;  // brick ids, far to near

  // Rank `rank` of `ranks`: its run of the order, [first, last).
  size_t first(int rank, int ranks) const { return order.size() * size_t(rank) / size_t(ranks); }
  size_t last(int rank, int ranks) const { return first(rank + 1, ranks); }
};

inline LayerDump readLayerDump(const std::string& dir) {
  LayerDump d;
  std::ifstream in(dir + "/order.txt");
  if (!(in >> d.width >> d.height)) throw std::runtime_error("cannot read " + dir + "/order.txt");
  for (int id; in >> id;) d.order.push_back(id);
  if (d.order.empty()) throw std::runtime_error(dir + "/order.txt lists no brick");
  return d;
}

inline BrickImage readDumpedBrick(const std::string& dir, int id) {
  std::ifstream in(dir + "/brick_" + std::to_string(id) + ".bin", std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + dir + "/brick_" + std::to_string(id) + ".bin");
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return unpackBrickImage(bytes);
}

// The same image with RLE off (runs of 1, as long as the raw pixels): what compositing.rle: false
// sends.
inline BrickImage withoutRle(const BrickImage& b) {
  BrickImage out{b.brick_id, b.rect, {}};
  if (b.rect.empty()) return out;
  std::vector<uint8_t> px(size_t(b.rect.area()) * 4);
  rleDecode(b.rle, size_t(b.rect.area()), px);
  rleEncode(px, out.rle, 4, 1);
  return out;
}

}  // namespace sortlast
