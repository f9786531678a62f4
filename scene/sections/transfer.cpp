// The transfer section's keys: the transfer function: control points or a preset, colour map,
// range, table, pre-integration.
#include "scene/key_rows.h"

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
    {"transfer.unit_length", "auto",
     "World length over which a sample has the opacity `a` of the transfer function; other "
     "sample spacings are corrected with 1 - (1 - a)^(ds / unit_length). `auto`: the "
     "smallest voxel spacing.",
     OptionalReal{member<&Scene::transfer, &TransferSpec::unit_length>, {kLength}}, AutoValue{}},
    {"transfer.table_size", "4096", "Entries in the transfer-function lookup table used by GL.",
     Int{member<&Scene::transfer, &TransferSpec::table_size>, {{"in [2, 65536]"}}}},
    {"transfer.preintegrated", "auto",
     "`auto`: true where the opacity changes steeply (by 0.5 or more within 10 % of the range "
     "between two control points), where it pays; false on smooth functions, where it does not, "
     "and where it is not supported (`adaptive.tolerance` above 0, `render.sample_spacing` above "
     "2). Pre-integrated transfer function (Engel, Kraus and Ertl 2001) in both GL volume renderers: "
     "each ray segment between two samples takes the exact emission-absorption integral of a "
     "value going linearly from its front to its back value, from a 256 x 256 table rebuilt when "
     "the transfer function or the sample spacing changes (about 30 ms). Coarse steps stay "
     "accurate on sharp transfer functions. Needs `render.sample_spacing` <= 2 (so segment ends "
     "stay within the bricks' ghost layer) and `adaptive.tolerance` 0.",
     Flag{member<&Scene::transfer, &TransferSpec::preintegrated>}, AutoValue{}},
  };
}
