// Writes the binary seeds of the codec targets with the real encoders, so the seeds are messages a
// rank could send: tests/fuzz/corpus/{rle_rgba8,rle_rgba16,brick_message}/. Run by scripts/fuzz
// --seeds (the committed seeds came from it); small images so the corpus stays small.
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "compositing/brick_image.h"
#include "compositing/rect_image.h"
#include "compositing/rle.h"

namespace {

using namespace sortlast;

void write(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                              std::streamsize(bytes.size()));
}

// A w x h partial composite: a disc of translucent colour on transparency (runs and visible
// stretches), premultiplied.
RectImage disc(const Rect& r) {
  RectImage img(r);
  for (int y = r.y; y < r.y + r.h; ++y)
    for (int x = r.x; x < r.x + r.w; ++x) {
      double dx = (x - r.x) / double(r.w) - 0.5, dy = (y - r.y) / double(r.h) - 0.5;
      if (dx * dx + dy * dy > 0.16) continue;
      float a = float(0.2 + 0.6 * (x - r.x) / r.w);
      float* p = img.at(x, y);
      p[0] = a * 0.9f, p[1] = a * 0.5f, p[2] = a * 0.1f, p[3] = a;
    }
  return img;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s CORPUS_DIR\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  int n = 0;
  for (Rect r : {Rect{0, 0, 12, 9}, Rect{3, 5, 31, 17}, Rect{10, 2, 40, 30}}) {
    RectImage img = disc(r);
    for (WireFormat f : {WireFormat::RGBA8, WireFormat::RGBA16}) {
      BrickImage b = encodePart(img, r, n, f);
      // The RLE targets: 2 bytes of pixel count (12 bits), then the stream.
      const size_t pixels = size_t(b.rect.area());
      std::vector<uint8_t> rle{uint8_t(pixels & 0xff), uint8_t(pixels >> 8)};
      rle.insert(rle.end(), b.rle.begin(), b.rle.end());
      write(dir + (f == WireFormat::RGBA8 ? "/rle_rgba8/disc" : "/rle_rgba16/disc") +
                std::to_string(n) + ".bin",
            rle);
      write(dir + "/brick_message/disc" + std::to_string(n) + "_" + std::to_string(int(f)) + ".bin",
            packBrickImage(b));
      // Without runs ("RLE off"): every transparent pixel its own marker.
      if (n == 0) {
        BrickImage raw = encodePart(img, r, n, f, false);
        write(dir + "/brick_message/raw" + std::to_string(int(f)) + ".bin", packBrickImage(raw));
      }
    }
    ++n;
  }
  // An empty part (nothing to show) and a fully transparent image of 4095 pixels (the most the
  // RLE targets' 12-bit count asks for).
  write(dir + "/brick_message/empty.bin", packBrickImage(BrickImage{7, Rect{}, {}}));
  std::vector<uint8_t> clear(size_t(4095) * 4, 0);
  std::vector<uint8_t> run{0xff, 0x0f};
  std::vector<uint8_t> s = rleEncode(clear, 4);
  run.insert(run.end(), s.begin(), s.end());
  write(dir + "/rle_rgba8/clear.bin", run);
  return 0;
}
