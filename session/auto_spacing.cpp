// render.sample_spacing: auto: the step from probe frames (session/auto_spacing.h).
#include "session/auto_spacing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sortlast {

namespace {

// RMS over pixels and the three colour channels of the two frames composited over background.
double rmsDifference(const ImageF& a, const ImageF& b, const glm::dvec3& bg) {
  double sum = 0.0;
  const size_t n = size_t(a.width) * a.height;
  for (size_t i = 0; i < n; ++i) {
    const float* p = &a.px[4 * i];
    const float* q = &b.px[4 * i];
    for (int c = 0; c < 3; ++c) {
      double u = double(p[c]) + (1.0 - double(p[3])) * bg[c];
      double v = double(q[c]) + (1.0 - double(q[3])) * bg[c];
      sum += (u - v) * (u - v);
    }
  }
  return n ? std::sqrt(sum / double(3 * n)) : 0.0;
}

}  // namespace

SpacingChoice chooseSpacing(const std::vector<ImageF>& probes, const glm::dvec3& background) {
  const std::vector<double>& steps = probeSpacings();
  if (probes.size() != steps.size()) throw std::logic_error("chooseSpacing: one probe per step");
  for (const ImageF& p : probes)
    if (p.width != probes[0].width || p.height != probes[0].height ||
        p.px.size() != size_t(p.width) * p.height * 4)
      throw std::logic_error("chooseSpacing: probes differ in size");
  SpacingChoice out;
  out.spacing = steps[0];
  const double bound = std::pow(10.0, -kTargetDb / 20.0);
  bool finer_ok = true;  // a step is taken only if every finer one passed too
  for (size_t i = 1; i < steps.size(); ++i) {
    const double e = rmsDifference(probes[i], probes[i - 1], background);
    out.estimated_db.push_back({steps[i], e > 0.0 ? -20.0 * std::log10(e)
                                                  : std::numeric_limits<double>::infinity()});
    finer_ok = finer_ok && e <= bound;
    if (finer_ok) out.spacing = steps[i];
  }
  return out;
}

std::vector<std::pair<double, bool>> stillTries(bool preintegrated, bool may_change) {
  const std::vector<double>& steps = stillSpacings();
  std::vector<std::pair<double, bool>> t;
  for (size_t i = 0; i < steps.size(); ++i) {
    t.push_back({steps[i], preintegrated});
    // Unintegrated by the rule: pre-integrated at the same step before the finest unintegrated
    // one, where that costs less. (Not before 0.25 too: where 0.5 unintegrated missed, 0.5
    // pre-integrated missed as well in every case tried -- neghip default 0.17 %, the two steep
    // functions of auto_spacing.h 0.19-0.24 % over 4/255 -- a frame for nothing.)
    if (may_change && !preintegrated && i + 2 == steps.size() &&
        sampleCost(steps[i], true) < sampleCost(steps[i + 1], false))
      t.push_back({steps[i], true});
  }
  if (may_change) t.push_back({steps.back(), !preintegrated});  // the last resort
  return t;
}

std::vector<double> otherChoiceSteps(bool preintegrated, bool met, double step) {
  const std::vector<double>& all = estimatedSpacings();
  if (met && (preintegrated || step > all.back())) return {};
  std::vector<double> s;
  for (double x : all)
    if (x <= kOtherChoiceCoarsest && (!met || sampleCost(x, !preintegrated) < sampleCost(step, preintegrated)))
      s.push_back(x);
  return s;
}

std::pair<int, int> probeSize(int width, int height) {
  const int longer = std::max(width, height);
  const int side = std::max(8, std::min(kProbeSide, longer / kProbeFraction));
  const double s = double(side) / double(longer);
  return {std::max(8, int(std::lround(width * s))), std::max(8, int(std::lround(height * s)))};
}

std::pair<int, int> estimateProbeSize(int width, int height) {
  const int longer = std::max(width, height);
  if (longer <= kEstimateProbeSide) return {width, height};
  const double s = double(kEstimateProbeSide) / double(longer);
  return {std::max(8, int(std::lround(width * s))), std::max(8, int(std::lround(height * s)))};
}

}  // namespace sortlast
