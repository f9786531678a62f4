#include "compositing/pixel_rates.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace sortlast {

namespace {
constexpr const char* kNames[] = {"decode_blend8", "decode_blend_into8", "blend_float", "scan",
                                  "encode", "decode", "decode_rgba8", "copy", "round8", "fill8", "place"};
static_assert(sizeof kNames / sizeof kNames[0] == size_t(PixelWork::Count));
}  // namespace

const char* pixelWorkName(PixelWork work) { return kNames[int(work)]; }

PixelRates::PixelRates() {
  for (auto& row : ns) row[0] = row[1] = -1.0;
}

double PixelRates::at(PixelWork work, int bytes_per_pixel) const {
  const double v = ns[int(work)][bytes_per_pixel == 8 ? 1 : 0];
  if (v < 0)
    throw std::runtime_error(std::string("pixel rates: no rate for ") + pixelWorkName(work) +
                             " at " + std::to_string(bytes_per_pixel) + " bytes per pixel");
  return v;
}

PixelRates readPixelRates(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("pixel rates: cannot open " + path);
  PixelRates rates;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.empty() || line[0] == '#' || line.rfind("work,", 0) == 0) continue;
    std::stringstream ss(line);
    std::string name, bytes, ns;
    std::getline(ss, name, ',');
    std::getline(ss, bytes, ',');
    std::getline(ss, ns, ',');
    int w = -1;
    for (int i = 0; i < int(PixelWork::Count); ++i)
      if (name == kNames[i]) w = i;
    double v = -1;
    try {
      v = std::stod(ns);
    } catch (const std::exception&) {
    }
    if (w < 0 || (bytes != "4" && bytes != "8") || !(v >= 0))
      throw std::runtime_error("pixel rates: " + path + ":" + std::to_string(n) +
                               ": expected work,4|8,ns_per_pixel, got '" + line + "'");
    rates.ns[w][bytes == "8" ? 1 : 0] = v;
  }
  return rates;
}

PixelRates measuredPixelRates() {
  // results/scale/rates.csv (measure_rates --size 2048 --coverage 0.4 --reps 9).
  struct Row { PixelWork work; int bytes; double ns; };
  static constexpr Row kRows[] = {
      {PixelWork::Copy, 4, 11.2018},
      {PixelWork::Copy, 8, 11.2018},
      {PixelWork::DecodeBlend8, 4, 4.2995},
      {PixelWork::DecodeBlendInto8, 4, 4.6388},
      {PixelWork::Fill8, 4, 0.1414},
      {PixelWork::Scan, 4, 0.8033},
      {PixelWork::Scan, 8, 0.8033},
      {PixelWork::Encode, 4, 17.091},
      {PixelWork::Decode, 4, 11.8782},
      {PixelWork::DecodeRGBA8, 4, 1.6413},
      {PixelWork::Round8, 4, 14.2611},
      {PixelWork::DecodeRGBA8, 8, 1.6413},
      {PixelWork::Round8, 8, 14.2611},
      {PixelWork::Fill8, 8, 0.1414},
      {PixelWork::DecodeBlend8, 8, 4.2995},
      {PixelWork::DecodeBlendInto8, 8, 4.6388},
      {PixelWork::Encode, 8, 16.6977},
      {PixelWork::Decode, 8, 11.9606},
      {PixelWork::BlendFloat, 4, 1.3406},
      {PixelWork::BlendFloat, 8, 1.3406},
      // Measured on 2026-12-06 (measure_rates, three runs 0.37-0.43; the largest), while a
      // simulation kept the other core busy.
      {PixelWork::Place, 4, 0.4318},
      {PixelWork::Place, 8, 0.4318},
  };
  PixelRates r;
  for (const Row& row : kRows) r.ns[int(row.work)][row.bytes == 8 ? 1 : 0] = row.ns;
  return r;
}

}  // namespace sortlast
