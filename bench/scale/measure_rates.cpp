// measure_rates: the per-pixel cost of each compositing kernel (compositing/pixel_cost.h) on this
// machine, for the SMPI build to charge as simulated computation (docs/smpi.md). Runs the same
// library functions the strategies call, on the sphere layers of scale_layers.h (64 ranks' images
// of a SIZE^2 frame at the given coverage), single-threaded, each the median of --reps timings,
// and prints CSV `work,bytes_per_pixel,ns_per_pixel` (pixel_rates.h). Where one call does two
// kinds of work (encodePart scans for the active rectangle, then encodes), the kind measured
// first is subtracted.
//
// Usage: measure_rates [--size 2048] [--coverage 0.4] [--reps 7] > rates.csv
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "compositing/pixel_rates.h"
#include "bench/scale/scale_layers.h"
#include "io/image.h"
#include "compositing/blend.h"
#include "compositing/rect_image.h"

namespace {

using namespace sortlast;

double medianSeconds(int reps, const std::function<void()>& f) {
  std::vector<double> t;
  f();  // warm-up: page faults, caches
  for (int i = 0; i < reps; ++i) {
    auto t0 = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

void print(PixelWork w, int bytes, double seconds, double pixels) {
  std::printf("%s,%d,%.4f\n", pixelWorkName(w), bytes, std::max(0.0, seconds * 1e9 / pixels));
}

}  // namespace

int main(int argc, char** argv) {
  int size = 2048, reps = 7;
  double coverage = 0.4;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (i + 1 >= argc) {
      std::fprintf(stderr, "measure_rates: %s needs a value\n", a.c_str());
      return 2;
    }
    if (a == "--size") size = std::stoi(argv[++i]);
    else if (a == "--coverage") coverage = std::stod(argv[++i]);
    else if (a == "--reps") reps = std::max(1, std::stoi(argv[++i]));
    else {
      std::fprintf(stderr, "measure_rates: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  const int kRanks = 64;
  std::vector<BrickImage> layers;
  for (int r = 0; r < kRanks; ++r)
    layers.push_back(scale::sphereLayer(r, kRanks, size, size, coverage, true));
  const VisibilityOrder order = scale::sphereOrder(kRanks);
  std::vector<const BrickImage*> seq;
  double layer_px = 0;
  for (int id : order.bricks)
    if (!layers[size_t(id)].rect.empty()) {
      seq.push_back(&layers[size_t(id)]);
      layer_px += double(layers[size_t(id)].rect.area());
    }

  std::printf("work,bytes_per_pixel,ns_per_pixel\n");
  std::fprintf(stderr, "measure_rates: %d^2, coverage %.2f, %zu non-empty layers, %.0f layer pixels\n",
               size, coverage, seq.size(), layer_px);
  // Copy: a new float image filled from another (crop) over the whole composite.
  RectImage whole = blendBackToFront(seq);
  const double whole_px = double(whole.rect.area());
  const double copy_s = medianSeconds(reps, [&] { RectImage c = crop(whole, whole.rect); });
  print(PixelWork::Copy, 4, copy_s, whole_px);
  print(PixelWork::Copy, 8, copy_s, whole_px);
  // DecodeBlend8: every layer decoded and blended into one new image (minus its zero fill).
  const double db_s = medianSeconds(reps, [&] { RectImage c = blendBackToFront(seq); });
  print(PixelWork::DecodeBlend8, 4, db_s - copy_s, layer_px);
  // DecodeBlendInto8: the same over an RGBA8 frame, rounding at every blend.
  ImageRGBA8 frame8(size, size);
  const double db8_s = medianSeconds(reps, [&] {
    std::fill(frame8.px.begin(), frame8.px.end(), 0);
    blendBackToFront(seq, frame8);
  });
  const double fill_s = medianSeconds(reps, [&] { ImageRGBA8 f(size, size); });
  print(PixelWork::DecodeBlendInto8, 4, db8_s - fill_s, layer_px);
  print(PixelWork::Fill8, 4, fill_s, double(size) * size);
  // Scan: the active rectangle of the composite.
  const double scan_s = medianSeconds(reps, [&] { volatile int w = activeRect(whole, whole.rect).w; (void)w; });
  print(PixelWork::Scan, 4, scan_s, whole_px);
  print(PixelWork::Scan, 8, scan_s, whole_px);
  // Encode and Decode in both wire formats; BlendFloat: two decoded layers into a new image.
  for (WireFormat f : {WireFormat::RGBA8, WireFormat::RGBA16}) {
    const int bytes = pixelBytes(f);
    BrickImage part;
    const double enc_s = medianSeconds(reps, [&] { part = encodePart(whole, whole.rect, 0, f); });
    const double part_px = double(part.rect.area());
    print(PixelWork::Encode, bytes, enc_s - scan_s, part_px);
    RectImage back;
    const double dec_s = medianSeconds(reps, [&] { back = decodePart(part, f, whole.rect); });
    print(PixelWork::Decode, bytes, dec_s, part_px);
    if (f == WireFormat::RGBA8) {
      ImageRGBA8 into(size, size);
      const double paste_s = medianSeconds(reps, [&] { pastePart(part, into); });
      print(PixelWork::DecodeRGBA8, 4, paste_s, part_px);
      // Round8: float pixels to RGBA8, as direct send's final pass.
      const double round_s = medianSeconds(reps, [&] {
        for (size_t i = 0; i < size_t(whole_px); ++i) toRGBA8(&whole.px[4 * i], &into.px[4 * i]);  // whole lies inside the frame
      });
      print(PixelWork::Round8, 4, round_s, whole_px);
      print(PixelWork::DecodeRGBA8, 8, paste_s, part_px);
      print(PixelWork::Round8, 8, round_s, whole_px);
      print(PixelWork::Fill8, 8, fill_s, double(size) * size);
      print(PixelWork::DecodeBlend8, 8, db_s - copy_s, layer_px);
      print(PixelWork::DecodeBlendInto8, 8, db8_s - fill_s, layer_px);
    }
  }
  // Place: raw RGBA8 rows copied into a frame, what MPI's unpacking of rank 0's strided gather
  // receives does; over tiles of 128^2 (rows of 512 bytes, the size of the final parts of 8192^2
  // on about 4,000 ranks), per 4 bytes.
  {
    const int tile = 128;
    std::vector<uint8_t> raw(size_t(tile) * tile * 4, 7);
    ImageRGBA8 into(size, size);
    const Rect& r = whole.rect;
    double tiles_px = 0;
    for (int y = r.y; y + tile <= r.y + r.h; y += tile)
      for (int x = r.x; x + tile <= r.x + r.w; x += tile) tiles_px += double(tile) * tile;
    const double place_s = medianSeconds(reps, [&] {
      for (int y = r.y; y + tile <= r.y + r.h; y += tile)
        for (int x = r.x; x + tile <= r.x + r.w; x += tile)
          for (int row = 0; row < tile; ++row)
            std::memcpy(into.at(x, y + row), &raw[size_t(row) * tile * 4], size_t(tile) * 4);
    });
    print(PixelWork::Place, 4, place_s, tiles_px);
    print(PixelWork::Place, 8, place_s, tiles_px);
  }
  const std::vector<const RectImage*> two{&whole, &whole};
  const double bf_s = medianSeconds(reps, [&] { RectImage c = blendBackToFront(two); });
  print(PixelWork::BlendFloat, 4, (bf_s - copy_s) / 2, whole_px);
  print(PixelWork::BlendFloat, 8, (bf_s - copy_s) / 2, whole_px);
  return 0;
}
