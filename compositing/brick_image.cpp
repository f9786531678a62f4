#include "compositing/brick_image.h"

#include <cstring>
#include <stdexcept>

#include "compositing/rle.h"

namespace sortlast {

std::vector<uint8_t> packBrickImage(const BrickImage& b) {
  if (!b.emission.empty()) throw std::logic_error("brick image: unencoded pixels are never sent");
  int32_t head[6] = {b.brick_id, b.rect.x, b.rect.y, b.rect.w, b.rect.h, int32_t(b.rle.size())};
  std::vector<uint8_t> out(sizeof head + b.rle.size());
  std::memcpy(out.data(), head, sizeof head);
  if (!b.rle.empty()) std::memcpy(out.data() + sizeof head, b.rle.data(), b.rle.size());
  return out;
}

BrickImage unpackBrickImage(const std::vector<uint8_t>& bytes) {
  int32_t head[6];
  if (bytes.size() < sizeof head) throw RleError("brick image message shorter than its header");
  std::memcpy(head, bytes.data(), sizeof head);
  if (head[5] < 0 || size_t(head[5]) != bytes.size() - sizeof head || head[3] < 0 || head[4] < 0)
    throw RleError("brick image message: header does not match its length");
  BrickImage b;
  b.brick_id = head[0];
  b.rect = {head[1], head[2], head[3], head[4]};
  b.rle.assign(bytes.begin() + sizeof head, bytes.end());
  return b;
}

}  // namespace sortlast
