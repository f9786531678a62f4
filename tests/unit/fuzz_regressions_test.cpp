// Inputs the fuzzers (tests/fuzz) and the sanitizer build found mishandled, each kept
// here so the fix stays. The corpus entries under tests/fuzz/corpus/ replay them too, but only in
// the fuzz build; these run with every unit test.
#include <gtest/gtest.h>

#include <climits>
#include <string>
#include <vector>

#include "io/image.h"
#include "io/particle_readers.h"
#include "scene/scene.h"
#include "compositing/blend.h"
#include "compositing/brick_image.h"
#include "compositing/rect_image.h"
#include "compositing/rle.h"
#include "input_error_of.h"

namespace sortlast {
namespace {

// A message whose rectangle reaches past INT_MAX: x + w overflowed int (undefined behaviour) in
// the frame checks of pastePart and blendBackToFront and in intersect / unite.
BrickImage farAway() {
  BrickImage b;
  b.brick_id = 0;
  b.rect = Rect{INT_MAX - 2, 5, 10, 1};
  std::vector<uint8_t> clear(size_t(b.rect.area()) * 4, 0);
  b.rle = rleEncode(clear);
  return unpackBrickImage(packBrickImage(b));
}

TEST(FuzzRegressions, RectanglesPastIntMaxAreOutsideTheFrame) {
  const BrickImage b = farAway();
  ImageRGBA8 frame8(16, 16);
  EXPECT_THROW(pastePart(b, frame8), RleError);
  ImageF frame(16, 16);
  EXPECT_THROW(blendBackToFront(std::vector<const BrickImage*>{&b}, frame), RleError);
  EXPECT_FALSE(contains(Rect{0, 0, 16, 16}, b.rect));
  EXPECT_TRUE(intersect(Rect{0, 0, 16, 16}, b.rect).empty());
  EXPECT_EQ(intersect(Rect{INT_MAX - 5, 0, 100, 100}, b.rect), (Rect{INT_MAX - 2, 5, 10, 1}));
  const Rect u = unite(Rect{0, 0, 4, 4}, b.rect);
  EXPECT_EQ(u.x, 0);
  EXPECT_EQ(u.w, INT_MAX);  // cut to what int holds
}

// A small message asking for a huge partial composite (a 4-byte run marker per 2^24 - 1 pixels):
// decodePart allocated rect.w * rect.h pixels before looking at the stream; now the receiver's
// region bounds it.
TEST(FuzzRegressions, PartOutsideTheReceiversRegionIsRefusedBeforeAllocating) {
  BrickImage b;
  b.rect = Rect{0, 0, 46000, 46000};
  b.rle = {0xff, 0xff, 0xff, 0, 0xff, 0xff, 0xff, 0};  // two runs: far from 46000^2 pixels
  EXPECT_THROW(decodePart(b, WireFormat::RGBA8, Rect{0, 0, 256, 256}), RleError);
  EXPECT_THROW(decodePart(b, WireFormat::RGBA16, Rect{0, 0, 256, 256}), RleError);
}

// CSV coordinates beyond float's range were converted to float before the check (undefined).
TEST(FuzzRegressions, CsvCoordinateBeyondFloatIsAnErrorNamingTheLine) {
  std::string msg = inputErrorOf([] { parseCsvParticles("0,0,0\n1,2,1e39\n", "p.csv", -1); });
  EXPECT_NE(msg.find("line 2"), std::string::npos) << msg;
  msg = inputErrorOf([] { parseCsvParticles("-3.5e38,0,0\n", "p.csv", -1); });
  EXPECT_NE(msg.find("line 1"), std::string::npos) << msg;
  EXPECT_EQ(parseCsvParticles("x,y,z\n1,2,3\n", "p.csv", 1).size(), 1u);
}

// Found by tests/fuzz/scene (corpus entry regression_complex_key.yaml): a YAML key that is a list
// or map ended in yaml-cpp's bare "bad conversion" instead of a message naming the place.
TEST(FuzzRegressions, ComplexYamlKeyIsAnInputError) {
  std::string msg = inputErrorOf([] { parseScene(SceneText{"s.yaml", "? [a, b]\n: 1\n"}, {}); });
  EXPECT_NE(msg.find("list or map"), std::string::npos) << msg;
  msg = inputErrorOf([] { parseScene(SceneText{"s.yaml", "camera:\n  ? {a: 1}\n  : 2\n"}, {}); });
  EXPECT_NE(msg.find("under 'camera'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("line 2"), std::string::npos) << msg;
}

}  // namespace
}  // namespace sortlast
