#include "transfer/colormap.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/error.h"

namespace sortlast {

namespace {

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// nlohmann's messages start with "[json.exception.parse_error.101] ": keep what a user can read.
std::string withoutExceptionId(const std::string& what) {
  auto close = what.find("] ");
  return what.rfind("[json.exception.", 0) == 0 && close != std::string::npos
             ? what.substr(close + 2)
             : what;
}

// The preset object to read: the one named `pick`, or the first.
const nlohmann::json& choosePreset(const nlohmann::json& doc, const std::string& pick,
                                   const std::string& source) {
  if (doc.is_object()) {
    if (!pick.empty() && doc.value("Name", std::string()) != pick)
      throw InputError(source + ": holds no colour map named \"" + pick + "\" (its one map is \"" +
                       doc.value("Name", std::string()) + "\")");
    return doc;
  }
  if (!doc.is_array())
    throw InputError(
        source +
        ": expected a colour-map preset (a JSON object with RGBPoints) or an array of them");
  if (doc.empty()) throw InputError(source + ": the array holds no colour map");
  for (size_t i = 0; i < doc.size(); ++i)
    if (!doc[i].is_object())
      throw InputError(source + ": entry " + std::to_string(i) +
                       " of the array is not a preset (a JSON object)");
  if (pick.empty()) return doc[0];
  std::string names;
  for (const auto& p : doc) {
    auto n = p.find("Name");
    std::string name = n != p.end() && n->is_string() ? n->get<std::string>() : "";
    if (name == pick) return p;
    names += (names.empty() ? "\"" : ", \"") + name + "\"";
  }
  throw InputError(source + ": holds no colour map named \"" + pick + "\" (it holds " + names +
                   ")");
}

}  // namespace

Rgb ColourMap::at(double x) const {
  if (x <= knots.front().x) return knots.front().rgb;
  if (x >= knots.back().x) return knots.back().rgb;
  auto it = std::upper_bound(knots.begin(), knots.end(), x,
                             [](double v, const ColourKnot& k) { return v < k.x; });
  const ColourKnot& b = *it;
  const ColourKnot& a = *(it - 1);
  return interpolateColour(space, a.rgb, b.rgb, (x - a.x) / (b.x - a.x));
}

std::vector<ColourKnot> ColourMap::sampled(int n) const {
  std::vector<double> xs;
  for (int i = 0; i < n; ++i) xs.push_back(double(i) / (n - 1));
  for (const ColourKnot& k : knots) xs.push_back(k.x);
  std::sort(xs.begin(), xs.end());
  std::vector<ColourKnot> out;
  // Where the curve bends within a step (Lab and Msh paths clipped at the sRGB gamut's edge have
  // kinks), halve the step until its midpoint is within kSampleTolerance of the chord.
  auto refine = [&](auto&& self, const ColourKnot& a, const ColourKnot& b, int depth) -> void {
    double xm = 0.5 * (a.x + b.x);
    Rgb m = at(xm);
    double off = 0;
    for (int c = 0; c < 3; ++c) off = std::max(off, std::abs(m[c] - 0.5 * (a.rgb[c] + b.rgb[c])));
    if (off <= kSampleTolerance || depth == 0) return;
    ColourKnot mid{xm, m};
    self(self, a, mid, depth - 1);
    out.push_back(mid);
    self(self, mid, b, depth - 1);
  };
  for (double x : xs) {
    if (!out.empty() && x - out.back().x <= 1e-9) continue;
    ColourKnot k{x, at(x)};
    if (!out.empty() && space != ColourSpace::Rgb) refine(refine, ColourKnot(out.back()), k, 8);
    out.push_back(k);
  }
  return out;
}

ColourMap parseColourMapJson(const std::string& text, const std::string& source,
                             const std::string& pick) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // parse_error; out_of_range for 1e999
    // Python's json module writes NaN and Infinity, which JSON does not have: say so.
    bool nan = text.find("NaN") != std::string::npos || text.find("Infinity") != std::string::npos;
    throw InputError(source + ": not valid JSON: " + withoutExceptionId(e.what()) +
                     (nan ? " (NaN and Infinity are not JSON numbers, and not colours)" : ""));
  }
  const nlohmann::json& p = choosePreset(doc, pick, source);
  ColourMap map;
  map.name = p.value("Name", std::string());
  // Several maps in one file: say which one is at fault.
  std::string where =
      source + (doc.is_array() && doc.size() > 1 ? ", colour map \"" + map.name + "\"" : "") + ": ";

  auto space = p.find("ColorSpace");
  if (space != p.end()) {
    if (!space->is_string())
      throw InputError(where + "ColorSpace must be a string such as \"RGB\"");
    try {
      map.space = parseColourSpace(space->get<std::string>());
    } catch (const InputError& e) {
      throw InputError(where + e.what());
    }
  }  // none given: RGB, as vtkColorTransferFunction's default

  auto rgb = p.find("RGBPoints");
  if (rgb == p.end()) {
    if (p.contains("IndexedColors"))
      throw InputError(where +
                       "an indexed (categorical) colour map, with IndexedColors and no RGBPoints: "
                       "only a continuous map can colour a volume");
    throw InputError(where + "no RGBPoints (the colour points [x, r, g, b, ...])");
  }
  if (!rgb->is_array())
    throw InputError(where + "RGBPoints must be an array of numbers [x, r, g, b, ...]");
  std::vector<double> v;
  for (size_t i = 0; i < rgb->size(); ++i) {
    const auto& e = (*rgb)[i];
    if (!e.is_number())
      throw InputError(where + "RGBPoints[" + std::to_string(i) + "] is " + e.dump() +
                       ", not a number");
    double d = e.get<double>();
    if (!std::isfinite(d))
      throw InputError(where + "RGBPoints[" + std::to_string(i) + "] is not a finite number");
    v.push_back(d);
  }
  if (v.size() % 4 != 0)
    throw InputError(where + "RGBPoints holds " + std::to_string(v.size()) +
                     " numbers: expected groups of four (x, r, g, b)");
  if (v.size() < 8)
    throw InputError(where + "RGBPoints holds " + std::to_string(v.size() / 4) +
                     " point(s): a colour map needs at least 2");
  for (size_t k = 0; k < v.size() / 4; ++k) {
    const double* q = &v[4 * k];
    for (int c = 1; c <= 3; ++c)
      if (q[c] < 0.0 || q[c] > 1.0)
        throw InputError(where + "RGBPoints point " + std::to_string(k) + " (x = " + number(q[0]) +
                         "): " + "rgb"[c - 1] + " = " + number(q[c]) + " is outside [0, 1]");
    if (k > 0 && !(q[0] > q[-4]))
      throw InputError(where + "RGBPoints point " + std::to_string(k) + ": x = " + number(q[0]) +
                       " does not follow x = " + number(q[-4]) +
                       " of the point before (x must increase)");
  }
  // The preset's x range maps onto the transfer function's normalised [0, 1].
  const double x0 = v.front(), x1 = v[v.size() - 4];
  for (size_t k = 0; k < v.size() / 4; ++k)
    map.knots.push_back({(v[4 * k] - x0) / (x1 - x0), {v[4 * k + 1], v[4 * k + 2], v[4 * k + 3]}});
  map.knots.back().x = 1.0;  // exactly, whatever the rounding
  return map;
}

std::vector<TfPoint> applyColourMap(const std::vector<TfPoint>& points,
                                    const std::vector<ColourKnot>& colours) {
  auto colourAt = [&](double x) -> Rgb {
    if (x <= colours.front().x) return colours.front().rgb;
    if (x >= colours.back().x) return colours.back().rgb;
    auto it = std::upper_bound(colours.begin(), colours.end(), x,
                               [](double v, const ColourKnot& k) { return v < k.x; });
    const ColourKnot &a = *(it - 1), &b = *it;
    double f = (x - a.x) / (b.x - a.x);
    return {a.rgb[0] + f * (b.rgb[0] - a.rgb[0]), a.rgb[1] + f * (b.rgb[1] - a.rgb[1]),
            a.rgb[2] + f * (b.rgb[2] - a.rgb[2])};
  };
  // Opacity between the points (never asked at a point's own x: those points are kept as they
  // are), constant beyond the first and the last, as TransferFunction evaluates it.
  auto opacityAt = [&](double x) {
    if (x <= points.front().value) return points.front().a;
    if (x >= points.back().value) return points.back().a;
    auto it = std::upper_bound(points.begin(), points.end(), x,
                               [](double v, const TfPoint& p) { return v < p.value; });
    const TfPoint &a = *(it - 1), &b = *it;
    return a.a + (x - a.value) / (b.value - a.value) * (b.a - a.a);
  };
  auto isOpacityX = [&](double x) {
    auto it = std::lower_bound(points.begin(), points.end(), x - 1e-12,
                               [](const TfPoint& p, double v) { return p.value < v; });
    return it != points.end() && std::abs(it->value - x) <= 1e-12;
  };
  std::vector<TfPoint> out;
  size_t i = 0;
  for (const ColourKnot& k : colours) {
    while (i < points.size() && points[i].value <= k.x) {
      Rgb c = colourAt(points[i].value);
      out.push_back({points[i].value, c[0], c[1], c[2], points[i].a});
      ++i;
    }
    if (!isOpacityX(k.x)) out.push_back({k.x, k.rgb[0], k.rgb[1], k.rgb[2], opacityAt(k.x)});
  }
  for (; i < points.size(); ++i) {
    Rgb c = colourAt(points[i].value);
    out.push_back({points[i].value, c[0], c[1], c[2], points[i].a});
  }
  return out;
}

}  // namespace sortlast
