// The Emission wire format of glow scenes (compositing/rect_image.h, docs/glow.md): light without
// opacity and above 1 survives encoding, RLE and blending within half-float rounding (2^-11
// relative), transparent pixels still become runs, and the transmittance keeps its relative
// precision near 0.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "compositing/blend.h"
#include "compositing/brick_image.h"
#include "compositing/rect_image.h"
#include "compositing/rle.h"

namespace sortlast {
namespace {

constexpr float kRel = 1.0f / 2048.0f;  // half-float rounding, relative

TEST(EmissionWire, GlowAboveOneWithoutOpacityRoundTrips) {
  RectImage img(Rect{0, 0, 6, 1});
  const float px[6][4] = {{0, 0, 0, 0},        {5.25f, 0.3f, 1e-3f, 0},  {0, 0, 0, 0},
                          {0, 0, 0, 0},        {0.2f, 0.1f, 0.05f, 0.9999f}, {300, 2, 0, 1}};
  for (int x = 0; x < 6; ++x)
    for (int c = 0; c < 4; ++c) img.at(x, 0)[c] = px[x][c];
  BrickImage part = encodePart(img, img.rect, 3, WireFormat::Emission);
  EXPECT_EQ(part.rect, (Rect{1, 0, 5, 1}));  // the glow-only pixel counts as active
  RectImage back = decodePart(unpackBrickImage(packBrickImage(part)), WireFormat::Emission, img.rect);
  ASSERT_EQ(back.rect, part.rect);
  for (int x = 1; x < 6; ++x) {
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(back.at(x, 0)[c], px[x][c], kRel * px[x][c]) << x << " " << c;
    // Transmittance T = 1 - alpha, relatively exact even where it is 1e-4.
    EXPECT_NEAR(1.0f - back.at(x, 0)[3], 1.0f - px[x][3], kRel * (1.0f - px[x][3]) + 1e-7f) << x;
  }
  // The two transparent pixels in the middle became one run: 3 pixels + 1 marker, 8 bytes each.
  EXPECT_EQ(part.rle.size(), 4u * 8u);
}

TEST(EmissionWire, BrickImagesBlendGlowOverOpacity) {
  // Back: glow 3.0 alone; front: a half-opaque grey. Over: front + (1 - 0.5) * back.
  RectImage back(Rect{0, 0, 1, 1}), front(Rect{0, 0, 1, 1});
  back.at(0, 0)[0] = 3.0f;
  for (int c = 0; c < 3; ++c) front.at(0, 0)[c] = 0.25f;
  front.at(0, 0)[3] = 0.5f;
  BrickImage b = encodePart(back, back.rect, 0, WireFormat::Emission);
  BrickImage f = encodePart(front, front.rect, 1, WireFormat::Emission);
  ImageF frame(1, 1);
  blendBackToFront({&b, &f}, frame, WireFormat::Emission);
  EXPECT_NEAR(frame.px[0], 0.25f + 0.5f * 3.0f, 2 * kRel * 1.75f);
  EXPECT_NEAR(frame.px[1], 0.25f, kRel);
  EXPECT_NEAR(frame.px[3], 0.5f, kRel);
}

TEST(EmissionWire, CorruptHalvesAreNeverPassedOn) {
  uint8_t in[8] = {0x00, 0x7c, 0xff, 0x7f, 0x00, 0x00, 0x00, 0xfc};  // +inf, NaN, 0, -inf
  float out[4];
  fromEmission16(in, out);
  for (float v : out) EXPECT_TRUE(std::isfinite(v));
}

TEST(EmissionWire, FusedEncodeIsToEmission16ThenRle) {
  // Runs at both ends, a run longer than max_run = 3, glow without opacity, an opaque pixel and
  // NaN / Inf (which toEmission16 clamps or passes to glm): the same bytes either way.
  const float px[][4] = {{0, 0, 0, 0}, {0, 0, 0, 0},     {2.5f, 0, 1e-6f, 0}, {0, 0, 0, 0},
                         {0, 0, 0, 0}, {0, 0, 0, 0},     {0, 0, 0, 0},        {0, 0, 0, 0},
                         {0.1f, 0.2f, 0.3f, 1}, {NAN, 1, 1e9f, 0.5f}, {0, 0, INFINITY, 0},
                         {0, 0, 0, 0}};
  const size_t n = sizeof(px) / sizeof(px[0]);
  std::vector<float> flat(&px[0][0], &px[0][0] + 4 * n);
  std::vector<uint8_t> raw(8 * n);
  for (size_t i = 0; i < n; ++i) toEmission16(px[i], &raw[8 * i]);
  for (uint32_t max_run : {1u, 3u, kMaxRun}) {
    std::vector<uint8_t> fused = {7};  // appends, as rleEncode does
    encodeEmission(flat, fused, max_run);
    std::vector<uint8_t> want = {7};
    rleEncode(raw, want, 8, max_run);
    EXPECT_EQ(fused, want) << max_run;
  }
}

TEST(EmissionWire, UnencodedImageBlendsAsItsEncoding) {
  // A brick image kept in float on the rank that blends it (BrickImage::emission) against the
  // same image encoded: glow, opaque and transparent pixels, colour too small for a half (shows
  // in float, not after rounding), above 65504, NaN and Inf, blended over a frame that already
  // holds light, so every blend counts. The frames must be the same bits.
  const float px[][4] = {{0, 0, 0, 0},        {2.5f, 0, 1e-6f, 0}, {1e-9f, 0, 0, 0},
                         {0.1f, 0.2f, 0.3f, 1}, {NAN, 1, 1e9f, 0.5f}, {0, 0, INFINITY, 0},
                         {0.3f, 0.3f, 0.3f, 0.4f}, {0, 0, 0, 0},        {7.0f, 1e-3f, 0, 1e-7f}};
  const Rect r{1, 2, 3, 3};
  std::vector<float> flat(&px[0][0], &px[0][0] + 4 * 9);
  BrickImage encoded{0, r, {}}, kept{0, r, {}};
  encodeEmission(flat, encoded.rle, kMaxRun);
  kept.emission = flat;
  ImageF a(5, 6), b(5, 6);
  for (size_t i = 0; i < a.px.size(); ++i) a.px[i] = b.px[i] = 0.05f * float(i % 7);
  blendBackToFront({&encoded}, a, WireFormat::Emission);
  blendBackToFront({&kept}, b, WireFormat::Emission);
  EXPECT_EQ(0, std::memcmp(a.px.data(), b.px.data(), a.px.size() * sizeof(float)));
  // Never sent: packing an unencoded image is a programming error.
  EXPECT_THROW(packBrickImage(kept), std::logic_error);
}

}  // namespace
}  // namespace sortlast
