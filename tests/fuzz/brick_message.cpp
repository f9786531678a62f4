// libFuzzer target: a compositing message as a rank receives it (compositing/brick_image.h,
// rect_image.h, blend.h): the packed header + RLE stream, decoded as a partial composite in both
// wire formats within the receiver's region, pasted into a frame and blended into one, as direct
// send, binary-swap and radix-k do. Every malformed message must end in RleError, no other error,
// no read or write outside a buffer, no allocation beyond the receiver's region.
#include <cstdint>
#include <vector>

#include "io/image.h"
#include "compositing/blend.h"
#include "compositing/brick_image.h"
#include "compositing/rect_image.h"
#include "compositing/rle.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sortlast;
  BrickImage b;
  try {
    b = unpackBrickImage(std::vector<uint8_t>(data, data + size));
  } catch (const RleError&) {
    return 0;
  }
  const Rect region{0, 0, 96, 64};
  for (WireFormat f : {WireFormat::RGBA16, WireFormat::RGBA8}) {
    try {
      RectImage part = decodePart(b, f, region);
      ImageF frame(region.w, region.h);
      pastePart(part, frame);
    } catch (const RleError&) {
    }
  }
  try {
    ImageRGBA8 frame(region.w, region.h);
    pastePart(b, frame);
  } catch (const RleError&) {
  }
  try {
    ImageF frame(region.w, region.h);
    blendBackToFront(std::vector<const BrickImage*>{&b}, frame);
  } catch (const RleError&) {
  }
  return 0;
}
