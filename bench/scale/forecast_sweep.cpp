// forecast_sweep: the cost model of `compositing.strategy: auto` (compositing/strategy_model.h)
// at every point of a bench_scale sweep, for comparing with the simulated times
// (bench/scale/auto.py). No MPI run: each point's footprint is the synthetic layers'
// forecast rectangles (scale_layers.h sphereLayerBound), the network the platform's as
// scripts/scale_platform.py --print-network gives it (--networks).
// Reads CSV lines of bench_scale (platform,strategy,radix,precision,rle,ranks,width,height,
// coverage,...) and prints, per distinct point, one line per candidate:
//   platform,precision,rle,ranks,width,height,coverage,strategy,radix,forecast_s,chosen
// Usage: forecast_sweep --networks NETWORKS.csv [--radices 2,4,8,16,32] [--first-frame] SWEEP.csv...
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <stdexcept>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "bench/comma_list.h"
#include "bench/scale/scale_layers.h"
#include "compositing/strategy_model.h"

namespace {

using namespace sortlast;

// --networks FILE: lines `platform,ranks,latency_us,gbit_per_s,ranks_per_core`, as
// bench/scale/run records them from scale_platform.py --print-network.
using NetworkTable = std::map<std::pair<std::string, int>, std::pair<NetworkModel, double>>;

NetworkTable readNetworks(const std::string& path) {
  NetworkTable t;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) f.push_back(c);
    if (f.size() != 5 || f[0] == "platform") continue;
    t[{f[0], std::stoi(f[1])}] = {NetworkModel{std::stod(f[2]) * 1e-6, std::stod(f[3]) * 1e9 / 8},
                                  std::stod(f[4])};
  }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> radices = {2, 4, 8, 16, 32};
  std::vector<std::string> files;
  bool first_frame = false;
  NetworkTable networks;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "forecast_sweep: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--radices") {
      radices.clear();
      for (const std::string& k : splitCommas(next())) radices.push_back(std::stoi(k));
    } else if (a == "--first-frame") first_frame = true;
    else if (a == "--networks") {
      try {
        networks = readNetworks(next());
      } catch (const std::exception& e) {
        std::fprintf(stderr, "forecast_sweep: %s\n", e.what());
        return 2;
      }
    } else files.push_back(a);
  }
  using Point = std::tuple<std::string, std::string, std::string, int, int, int, double>;
  std::vector<Point> points;
  for (const std::string& path : files) {
    std::ifstream in(path);
    if (!in) {
      std::fprintf(stderr, "forecast_sweep: cannot open %s\n", path.c_str());
      return 2;
    }
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line.rfind("platform,", 0) == 0) continue;
      std::vector<std::string> f;
      std::stringstream ss(line);
      for (std::string c; std::getline(ss, c, ',');) f.push_back(c);
      if (f.size() < 9) continue;
      Point p{f[0], f[3], f[4], std::stoi(f[5]), std::stoi(f[6]), std::stoi(f[7]), std::stod(f[8])};
      if (std::find(points.begin(), points.end(), p) == points.end()) points.push_back(p);
    }
  }
  std::printf("platform,precision,rle,ranks,width,height,coverage,strategy,radix,forecast_s,chosen\n");
  for (const auto& [kind, precision, rle, ranks, w, h, coverage] : points) {
    ModelSettings m;
    m.first_frame = first_frame;
    // The measured runs (native bench_scale) ran on the machine the `local` platform describes.
    auto it = networks.find({kind == "measured" ? "local" : kind, ranks});
    if (it == networks.end()) {
      std::fprintf(stderr, "forecast_sweep: no network for %s at %d ranks\n", kind.c_str(), ranks);
      continue;
    }
    m.network = it->second.first;
    m.ranks_per_core = it->second.second;
    FrameFootprint fp;
    for (int r = 0; r < ranks; ++r) {
      const Rect rc = scale::sphereLayerBound(r, ranks, w, h, coverage);
      fp.rect.push_back(rc);
      fp.brick_pixels.push_back(double(rc.area()));
      fp.bricks.push_back(1);
    }
    CompositeOptions opt;
    opt.precision = precision == "rgba8" ? Precision::kRgba8 : Precision::kFloat;
    opt.rle = rle == "on";
    const std::vector<StrategyForecast> fc =
        forecastStrategies(scale::sphereOrder(ranks), fp, w, h, opt, m, radices);
    const StrategyForecast& best = fastest(fc);
    for (const StrategyForecast& f : fc)
      std::printf("%s,%s,%s,%d,%d,%d,%.4g,%s,%s,%.6g,%d\n", kind.c_str(), precision.c_str(),
                  rle.c_str(), ranks, w, h, coverage, f.strategy.c_str(),
                  f.radix ? std::to_string(f.radix).c_str() : "", f.seconds, &f == &best);
  }
  return 0;
}
