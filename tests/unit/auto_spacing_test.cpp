// render.sample_spacing: auto's choice from probe frames (session/auto_spacing.h), on
// synthetic probes whose differences are known.
#include <cmath>

#include <gtest/gtest.h>

#include "session/auto_spacing.h"

namespace sortlast {
namespace {

// A grey frame of premultiplied value v, alpha a.
ImageF frame(float v, float a, int w = 16, int h = 12) {
  ImageF f(w, h);
  for (size_t i = 0; i < f.px.size(); i += 4) f.px[i] = f.px[i + 1] = f.px[i + 2] = v, f.px[i + 3] = a;
  return f;
}

double db(double rms) { return -20.0 * std::log10(rms); }

TEST(AutoSpacing, TakesTheLargestStepWhoseDifferenceStaysWithinTheTarget) {
  const glm::dvec3 black(0.0);
  const double ok = 0.5 * std::pow(10.0, -kTargetDb / 20.0), bad = 2.0 * std::pow(10.0, -kTargetDb / 20.0);
  // Identical probes: the coarsest step, estimates infinite.
  SpacingChoice same = chooseSpacing({frame(0.3f, 0.5f), frame(0.3f, 0.5f), frame(0.3f, 0.5f)}, black);
  EXPECT_EQ(same.spacing, 2.0);
  ASSERT_EQ(same.estimated_db.size(), 2u);
  EXPECT_TRUE(std::isinf(same.estimated_db[0].second));
  // 1 within the target, 2 not: 1.
  SpacingChoice one = chooseSpacing({frame(0.3f, 0.5f), frame(float(0.3 + ok), 0.5f), frame(float(0.3 + ok + bad), 0.5f)}, black);
  EXPECT_EQ(one.spacing, 1.0);
  EXPECT_NEAR(one.estimated_db[0].second, db(ok), 0.01);
  EXPECT_NEAR(one.estimated_db[1].second, db(bad), 0.01);
  // 1 over the target: 0.5, even if 2 against 1 happens to be close (every finer step must pass).
  SpacingChoice half = chooseSpacing({frame(0.3f, 0.5f), frame(float(0.3 + bad), 0.5f), frame(float(0.3 + bad), 0.5f)}, black);
  EXPECT_EQ(half.spacing, 0.5);
}

TEST(AutoSpacing, ComparesTheFramesOverTheirBackground) {
  // The same colour, different alpha: over black the RGB values are equal, over white they are not.
  const double bad = 4.0 * std::pow(10.0, -kTargetDb / 20.0);
  std::vector<ImageF> probes{frame(0.2f, 0.5f), frame(0.2f, float(0.5 + bad)), frame(0.2f, float(0.5 + bad))};
  EXPECT_EQ(chooseSpacing(probes, glm::dvec3(0.0)).spacing, 2.0);
  EXPECT_EQ(chooseSpacing(probes, glm::dvec3(1.0)).spacing, 0.5);
}

TEST(AutoSpacing, ProbeSizeKeepsTheAspectWithinItsSide) {
  EXPECT_EQ(probeSize(64, 48), std::make_pair(16, 12));
  EXPECT_EQ(probeSize(256, 128), std::make_pair(64, 32));
  EXPECT_EQ(probeSize(20, 20), std::make_pair(8, 8));
  EXPECT_EQ(probeSize(512, 512), std::make_pair(kProbeSide, kProbeSide));
  EXPECT_EQ(probeSize(1024, 512), std::make_pair(kProbeSide, kProbeSide / 2));
  EXPECT_EQ(probeSize(4096, 16), std::make_pair(kProbeSide, 8));
  EXPECT_THROW(chooseSpacing({frame(0, 0), frame(0, 0, 8, 8), frame(0, 0)}, glm::dvec3(0.0)), std::logic_error);
}

}  // namespace
// transfer.preintegrated `auto` (auto_spacing.h): what a still frame tries, in order, and which
// probes of the other choice follow the rule's.
TEST(AutoSpacing, TriesTheOtherPreintegrationWhereItCanPay) {
  using Tries = std::vector<std::pair<double, bool>>;
  // Unintegrated by the rule: pre-integrated at 0.25 (cost 6) before unintegrated 0.125 (8);
  // the other choice last.
  EXPECT_EQ(stillTries(false, true), (Tries{{0.5, false}, {0.25, false}, {0.25, true}, {0.125, false}, {0.125, true}}));
  // Pre-integrated by the rule (a steep function): unintegrated only as the last resort.
  EXPECT_EQ(stillTries(true, true), (Tries{{0.5, true}, {0.25, true}, {0.125, true}, {0.125, false}}));
  // Pinned by the scene: the steps alone.
  EXPECT_EQ(stillTries(true, false), (Tries{{0.5, true}, {0.25, true}, {0.125, true}}));
  // Probes: unintegrated met the target only at the finest step -> pre-integrated where cheaper.
  EXPECT_EQ(otherChoiceSteps(false, true, 0.125), (std::vector<double>{0.5, 0.25}));
  EXPECT_TRUE(otherChoiceSteps(false, true, 0.25).empty());  // met above the finest: no probes
  EXPECT_TRUE(otherChoiceSteps(true, true, 0.125).empty());   // pre-integrated met it: kept
  // Missed at every step: the other choice at every step up to kOtherChoiceCoarsest.
  EXPECT_EQ(otherChoiceSteps(true, false, 0.125), (std::vector<double>{0.5, 0.25, 0.125}));
  EXPECT_EQ(otherChoiceSteps(false, false, 0.125), (std::vector<double>{0.5, 0.25, 0.125}));
}

}  // namespace sortlast
