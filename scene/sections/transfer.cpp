// The transfer section's keys: the transfer function: control points or a preset, colour map,
// range, table, pre-integration.
#include "scene/key_rows.h"
#include "scene/scene_reader.h"
#include <algorithm>
#include <cmath>
#include "transfer/colormap_presets.h"

std::vector<sortlast::SceneKey> sortlast::transferKeys() {
  const Check kLength = lengthCheck();
  return {
    {"transfer.preset", "default",
     "Control points to use when `transfer.points` is not given: `default`, `ramp` (the "
     "paper's opacity = value, grey) or `sharp` (a narrow opaque band).",
     Structured{"preset name"}},
    {"transfer.points", "null",
     "List of control points `[value, r, g, b, a]`, all in [0, 1], values increasing; value "
     "is normalised over `transfer.range`. Colour and opacity are linear between points.",
     Structured{"list of [value, r, g, b, a]"}},
    {"transfer.colormap", "\"\"",
     "Colour map for the volume: its colours replace those of `transfer.points` / "
     "`transfer.preset`, whose opacity stays as it is. Empty: none. A built-in by ParaView's "
     "name or its alias: `Cool to Warm` (`cool_to_warm`), `Viridis (matplotlib)` (`Viridis`, "
     "`viridis`), `Inferno (matplotlib)` (`inferno`), `Plasma (matplotlib)` (`plasma`), "
     "`Grayscale` (`grayscale`), `Black-Body Radiation` (`black_body`), `Jet` (`jet`). Or a "
     "colour-map file as ParaView exports it (`FILE.json`: an array of presets, or one, each "
     "with `RGBPoints` [x, r, g, b, ...] and `ColorSpace`: `RGB`, `Lab`/`CIELAB`, `Diverging` "
     "(Moreland's Msh interpolation, as ParaView's Cool to Warm uses) or `HSV`; the first "
     "preset, or `FILE.json#Name` for the one with that `Name`). The preset's x range is "
     "stretched onto `transfer.range` (first point at its low end, last at its high end); "
     "`Points` (ParaView's opacity), `NanColor` and other fields are ignored. The map is "
     "resampled at 256 evenly spaced values, its own points, and more where a Lab or "
     "Diverging path bends (to 0.1/255), and interpolated linearly in RGB between them. A relative FILE is relative to the scene file (with `--set`: to the "
     "working directory); the file is read whenever the scene is (a resident session: with "
     "each request). A request to `sortlast serve` may name a built-in only.",
     Structured{"colour map name, or FILE.json[#Name]"}},
    {"transfer.range", "auto",
     "Data values `[lo, hi]` that map to 0 and 1. `auto`: the volume's minimum and maximum.",
     Structured{"`auto` or [lo, hi]",
                {{"in [-1e38, 1e38]", "{value} is beyond float's range (+-3.4e38)"}}}},
    {"transfer.scale", "linear",
     "Domain the transfer function is laid out in: `linear`, `log` (log10 of the value) or "
     "`symlog` (matplotlib's SymLogNorm, base 10, linscale 1: linear within "
     "+-`transfer.linear_width` of zero, logarithmic beyond; it takes zero and negative values). "
     "`transfer.range` stays in data units; the points' values (and the colour map) are places "
     "in the scaled range, so the table is evenly spaced in the scale, and each sample is scaled "
     "after trilinear interpolation. `log` needs a range with both ends > 0 (given, or the data's "
     "with `transfer.range: auto`); samples <= 0 map below the range.",
     Choice{member<&Scene::transfer, &TransferSpec::scale>}},
    {"transfer.linear_width", "1",
     "`transfer.scale: symlog`: the half-width of the linear part around zero, in data units "
     "(SymLogNorm's linthresh).",
     Real{member<&Scene::transfer, &TransferSpec::linear_width>, {{"> 0"}}}},
    {"transfer.unit_length", "auto",
     "World length over which a sample has the opacity `a` of the transfer function; other "
     "sample spacings are corrected with 1 - (1 - a)^(ds / unit_length). `auto`: the "
     "smallest voxel spacing.",
     OptionalReal{member<&Scene::transfer, &TransferSpec::unit_length>, {kLength}}, AutoValue{}},
    {"transfer.table_size", "4096",
     "Entries in the transfer-function lookup table used by GL (a 1D texture: at most 16384, the "
     "largest texture every OpenGL 4.5 implementation takes; llvmpipe refused 65536).",
     Int{member<&Scene::transfer, &TransferSpec::table_size>, {{"in [2, 16384]"}}}},
    {"transfer.preintegrated", "auto",
     "`auto`: true where the opacity changes steeply (by 0.5 or more within 10 % of the range "
     "between two control points), where it pays; false on smooth functions, where it does not, "
     "and where it is not supported (`adaptive.tolerance` above 0, `render.sample_spacing` above "
     "2). With `render.sample_spacing: auto` and the frame's estimate, the estimate may overturn "
     "that rule: the other choice is tried where the rule's misses the target or needs the finest "
     "step, and taken where it meets the target at less cost (`sample_spacing_auto.preintegrated` "
     "in `--stats`). Pre-integrated transfer function (Engel, Kraus and Ertl 2001) in both GL volume renderers: "
     "each ray segment between two samples takes the exact emission-absorption integral of a "
     "value going linearly from its front to its back value, from a 256 x 256 table rebuilt when "
     "the transfer function or the sample spacing changes (about 30 ms). Coarse steps stay "
     "accurate on sharp transfer functions. Needs `render.sample_spacing` <= 2 (so segment ends "
     "stay within the bricks' ghost layer) and `adaptive.tolerance` 0.",
     Flag{member<&Scene::transfer, &TransferSpec::preintegrated>}, AutoValue{}},
  };
}

namespace sortlast {

// transfer.points (or transfer.preset), transfer.range and transfer.colormap.
void readTransferKeys(const Reader& r, const Origin& o, TransferSpec& tf) {
  YAML::Node pts = r.get("transfer.points");
  if (pts.IsNull()) {
    tf.points = TransferFunction::preset(r.as<std::string>("transfer.preset"));
  } else {
    if (!pts.IsSequence() || pts.size() == 0)
      throw InputError("scene key 'transfer.points': expected a list of [value, r, g, b, a]" + where(pts));
    for (const auto& p : pts) {
      std::vector<double> v;
      try {
        for (const auto& e : p) v.push_back(e.as<double>());
      } catch (const YAML::Exception&) {
        v.clear();
      }
      if (v.size() != 5)
        throw InputError("scene key 'transfer.points': each point is [value, r, g, b, a]" + where(p));
      tf.points.push_back({v[0], v[1], v[2], v[3], v[4]});
    }
  }
  if (!r.isAuto("transfer.range")) {
    auto v = r.numbers("transfer.range", 2);
    if (!(v[1] > v[0])) throw InputError("scene key 'transfer.range': needs lo < hi");
    // Samples are floats on the GPU: the range must be one, and wide enough not to collapse there.
    for (double x : v) requireTable("transfer.range", x, "transfer.range");
    if (v[1] - v[0] < 1e-6 * std::max(std::abs(v[0]), std::abs(v[1])))
      throw InputError("scene key 'transfer.range': [" + numText(v[0]) + ", " + numText(v[1]) +
                       "] is narrower than float precision at that magnitude (hi - lo must be at "
                       "least 1e-6 of |hi|)");
    if (tf.scale == ValueScaleKind::kLog && !(v[0] > 0.0))
      throw InputError("scene key 'transfer.range': [" + numText(v[0]) + ", " + numText(v[1]) +
                       "] has an end <= 0, which transfer.scale: log cannot map (use "
                       "transfer.scale: symlog for data through zero)");
    tf.range = std::make_pair(v[0], v[1]);
  }
  // Validate the points now (range and unit length are placeholders until the data is known).
  TransferFunction(tf.points, 0.0, 1.0, tf.unit_length.value_or(1.0));
  // A colour map replaces the points' colours (their opacity stays): resolved here, once per
  // parse, so the rest of the program sees plain control points.
  if (!r.get("transfer.colormap").IsNull()) tf.colormap = r.as<std::string>("transfer.colormap");
  if (!tf.colormap.empty()) {
    try {
      const bool given = o.fromOverride("transfer.colormap");
      ColourMap map =
          loadColourMap(tf.colormap, given ? std::filesystem::current_path() : o.base_dir);
      tf.points = applyColourMap(tf.points, map.sampled());
    } catch (const InputError& e) {
      throw InputError(std::string("scene key 'transfer.colormap': ") + e.what());
    }
  }
}

TransferFunction TransferSpec::build(double data_min, double data_max, double min_spacing) const {
  double lo = range ? range->first : data_min, hi = range ? range->second : data_max;
  if (!range && !(hi > lo)) hi = lo + 1.0;  // constant volume: any non-empty range will do
  if (!range && scale == ValueScaleKind::kLog && !(lo > 0.0))
    throw InputError("transfer.scale: log needs a range with both ends > 0, and transfer.range "
                     "is auto while the data's range is [" + numText(lo) + ", " + numText(hi) +
                     "]: give transfer.range: [lo, hi] with lo > 0 (samples <= 0 then map below "
                     "it), or use transfer.scale: symlog");
  return TransferFunction(points, lo, hi, unit_length.value_or(min_spacing), ValueScale{scale, linear_width});
}

bool hasSteepOpacity(const std::vector<TfPoint>& points) {
  for (size_t i = 1; i < points.size(); ++i) {
    const double dx = points[i].value - points[i - 1].value, da = std::abs(points[i].a - points[i - 1].a);
    if (da > 0.0 && da >= kSteepOpacitySlope * dx) return true;
  }
  return false;
}

}  // namespace sortlast
