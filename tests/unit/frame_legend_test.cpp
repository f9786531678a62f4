// image.legend (session/frame_legend.h): the legend changes only its own rectangle, its bar holds
// the transfer function's colours, and its ticks sit where the scale puts their values.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "input_error_of.h"
#include "io/text_raster.h"
#include "session/frame_legend.h"

namespace sortlast {
namespace {

// Black to red over [0, 10]: the bar's red is round(255 t) at place t.
TransferFunction blackToRed(ValueScale s = {}, double lo = 0.0, double hi = 10.0) {
  return TransferFunction({{0.0, 0, 0, 0, 0.1}, {1.0, 1, 0, 0, 0.1}}, lo, hi, 1.0, s);
}

ImageRGBA8 noise(int w, int h) {
  ImageRGBA8 img(w, h);
  std::mt19937 rng(7);
  for (size_t i = 0; i < img.px.size(); i += 4) {
    const uint8_t a = uint8_t(rng() % 256);
    for (int c = 0; c < 3; ++c) img.px[i + size_t(c)] = uint8_t(rng() % (a + 1u));
    img.px[i + 3] = a;
  }
  return img;
}

class Legend : public ::testing::TestWithParam<LegendPosition> {};

TEST_P(Legend, ChangesOnlyItsRectangleAndHoldsTheTableColours) {
  if (!std::filesystem::exists(kLegendFontPath)) GTEST_SKIP() << "no " << kLegendFontPath;
  const ImageRGBA8 before = noise(200, 150);
  ImageRGBA8 after = before;
  LegendSpec spec;
  spec.position = GetParam();
  spec.title = "density";
  spec.units = "g/cm3";
  const TransferFunction tf = blackToRed();
  const LegendRect r = drawLegend(after, tf, spec, {0, 0, 0});
  ASSERT_GT(r.width, 0);
  ASSERT_GT(r.bar_width * r.bar_height, 0);
  int changed_inside = 0;
  for (int y = 0; y < before.height; ++y)
    for (int x = 0; x < before.width; ++x) {
      const bool inside = x >= r.x && x < r.x + r.width && y >= r.y && y < r.y + r.height;
      const bool same = std::equal(before.at(x, y), before.at(x, y) + 4, after.at(x, y));
      if (!inside) ASSERT_TRUE(same) << "pixel " << x << ", " << y << " outside the legend changed";
      changed_inside += !same;
    }
  EXPECT_GT(changed_inside, r.bar_width * r.bar_height);  // the bar, and text beside it
  // The rectangle stays in the frame and on its side.
  EXPECT_GE(r.x, 0);
  EXPECT_LE(r.x + r.width, before.width);
  if (spec.position == LegendPosition::kRight) EXPECT_GT(r.x, before.width / 2);
  if (spec.position == LegendPosition::kLeft) EXPECT_LT(r.x + r.width, before.width / 2);
  if (spec.position == LegendPosition::kBottom) EXPECT_GT(r.y, before.height / 2);
  if (spec.position == LegendPosition::kTop) EXPECT_LT(r.y + r.height, before.height / 2);
  // Every bar pixel is opaque and the function's colour at its place: red = round(255 t).
  const int len = r.vertical ? r.bar_height : r.bar_width;
  for (int y = r.bar_y; y < r.bar_y + r.bar_height; ++y)
    for (int x = r.bar_x; x < r.bar_x + r.bar_width; ++x) {
      const int i = r.vertical ? r.bar_y + r.bar_height - 1 - y : x - r.bar_x;
      const double t = (i + 0.5) / len;
      const uint8_t* p = after.at(x, y);
      ASSERT_EQ(p[3], 255);
      ASSERT_EQ(p[0], uint8_t(std::lround(255.0 * t))) << "at " << x << ", " << y;
      ASSERT_EQ(p[1], 0);
      ASSERT_EQ(p[2], 0);
    }
}

INSTANTIATE_TEST_SUITE_P(Positions, Legend,
                         ::testing::Values(LegendPosition::kRight, LegendPosition::kLeft,
                                           LegendPosition::kBottom, LegendPosition::kTop));

TEST(LegendTicks, LinearRoundSteps) {
  const std::vector<LegendTick> t = legendTicks(blackToRed(), 5);
  ASSERT_EQ(t.size(), 6u);  // 0, 2, ..., 10: the round step for about 5 ticks over 10
  EXPECT_EQ(t[0].label, "0");
  EXPECT_EQ(t[5].label, "10");
  EXPECT_NEAR(t[1].place, 0.2, 1e-12);
}

TEST(LegendTicks, LogDecades) {
  const std::vector<LegendTick> t = legendTicks(blackToRed({ValueScaleKind::kLog, 1.0}, 1.0, 1e4), 5);
  ASSERT_EQ(t.size(), 5u);
  const char* labels[] = {"1", "10", "100", "1000", "1e4"};
  for (size_t i = 0; i < t.size(); ++i) {
    EXPECT_EQ(t[i].label, labels[i]);
    EXPECT_NEAR(t[i].place, 0.25 * double(i), 1e-12);  // evenly spaced in log10
  }
  // Twelve decades, at most about 5 ticks: every third.
  EXPECT_LE(legendTicks(blackToRed({ValueScaleKind::kLog, 1.0}, 1e-6, 1e6), 5).size(), 5u);
}

TEST(LegendTicks, SymlogZeroAndDecades) {
  const std::vector<LegendTick> t = legendTicks(blackToRed({ValueScaleKind::kSymlog, 1.0}, -100.0, 100.0), 7);
  std::vector<std::string> labels;
  for (const auto& k : t) labels.push_back(k.label);
  EXPECT_EQ(labels, (std::vector<std::string>{"-100", "-10", "-1", "0", "1", "10", "100"}));
  EXPECT_NEAR(t[3].place, 0.5, 1e-12);
}

TEST(LegendFont, MissingFontNamesTheFileAndPackage) {
  const std::string msg = inputErrorOf([] { TextRaster r(12, "/nonexistent/DejaVuSans.ttf"); });
  EXPECT_NE(msg.find("/nonexistent/DejaVuSans.ttf"), std::string::npos) << msg;
  EXPECT_NE(msg.find("fonts-dejavu-core"), std::string::npos) << msg;
}

}  // namespace
}  // namespace sortlast
