// Colour maps (transfer/colour_space.h, colormap.h, colormap_presets.h) and transfer.colormap in
// scenes and frame requests: the built-ins, the colour spaces against independent values, a
// preset file's round trip, and every malformed file.
#include "transfer/colormap.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "transfer/colormap_presets.h"
#include "scene/scene.h"
#include "service/request_translation.h"
#include "tests/unit/input_error_of.h"

namespace sortlast {
namespace {

namespace fs = std::filesystem;

double maxDiff(const Rgb& a, const Rgb& b) {
  return std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
}

ColourMap twoPoints(ColourSpace space, Rgb a, Rgb b) {
  ColourMap m;
  m.space = space;
  m.knots = {{0.0, a}, {1.0, b}};
  return m;
}

// The built-in maps by name: ParaView's and a lowercase alias each.
const std::vector<std::pair<std::string, std::string>> kRequired = {
    {"Cool to Warm", "cool_to_warm"},
    {"Viridis (matplotlib)", "viridis"},
    {"Inferno (matplotlib)", "inferno"},
    {"Grayscale", "grayscale"},
    {"Black-Body Radiation", "black_body"}};

TEST(ColourMap, EveryBuiltinLoadsByEveryName) {
  std::vector<std::string> names = builtinColourMapNames();
  EXPECT_GE(names.size(), 5u);
  for (const std::string& entry : names) {
    // "ParaView Name (alias)"
    std::string full = entry.substr(0, entry.rfind(" (")),
                alias = entry.substr(entry.rfind(" (") + 2);
    alias.pop_back();
    SCOPED_TRACE(entry);
    ColourMap m = loadColourMap(full, ".");
    EXPECT_EQ(m.name, full);
    ASSERT_GE(m.knots.size(), 2u);
    EXPECT_EQ(m.knots.front().x, 0.0);
    EXPECT_EQ(m.knots.back().x, 1.0);
    EXPECT_EQ(loadColourMap(alias, ".").name, full);
    EXPECT_EQ(loadColourMap(full.substr(0, full.find(" (")), ".").name, full);  // "Viridis"
    std::vector<ColourKnot> s = m.sampled();
    EXPECT_GE(s.size(), 256u);
    for (size_t i = 0; i < s.size(); ++i) {
      if (i > 0) EXPECT_GT(s[i].x, s[i - 1].x);
      for (double c : s[i].rgb) EXPECT_TRUE(c >= 0.0 && c <= 1.0);
    }
  }
  for (const auto& [paraview, alias] : kRequired) {
    EXPECT_TRUE(isBuiltinColourMap(paraview)) << paraview;
    EXPECT_TRUE(isBuiltinColourMap(alias)) << alias;
  }
  EXPECT_FALSE(isBuiltinColourMap("cool to warm"));
}

TEST(ColourMap, BuiltinsHaveParaViewsPoints) {
  // Black-Body Radiation: black, red (230/255), yellow, white at 0, 0.4, 0.8, 1, linear in RGB.
  ColourMap bb = loadColourMap("black_body", ".");
  EXPECT_LT(maxDiff(bb.at(0.4), {230 / 255.0, 0, 0}), 1e-9);
  EXPECT_LT(maxDiff(bb.at(0.6), {230 / 255.0, 115 / 255.0, 0}), 1e-9);
  // Jet is stored over [-1, 1] as ParaView has it: its second point (-0.777778) lands at 0.111111.
  ColourMap jet = loadColourMap("jet", ".");
  EXPECT_NEAR(jet.knots[1].x, (1 - 0.777778) / 2, 1e-12);
  // Viridis: matplotlib's first and last entries.
  ColourMap v = loadColourMap("viridis", ".");
  EXPECT_EQ(v.knots.size(), 256u);
  EXPECT_LT(maxDiff(v.at(0.0), {0.267004, 0.004874, 0.329415}), 1e-12);
  EXPECT_LT(maxDiff(v.at(1.0), {0.993248, 0.906157, 0.143936}), 1e-12);
  // 256 entries are dense enough that interpolating them in Lab instead of RGB (which ParaView's
  // copy names) moves no colour by 1/255.
  ColourMap lab = v;
  lab.space = ColourSpace::Lab;
  double worst = 0;
  for (int i = 0; i <= 4096; ++i)
    worst = std::max(worst, maxDiff(v.at(i / 4096.0), lab.at(i / 4096.0)));
  EXPECT_LT(worst, 1.0 / 255);
}

TEST(ColourMap, CoolToWarmIsMorelandsDivergingMap) {
  const Rgb cool = {0.23137254902, 0.298039215686, 0.752941176471},
            warm = {0.705882352941, 0.0156862745098, 0.149019607843};
  // The Msh interpolation of the two ends alone puts Moreland's unsaturated white (M = 88, sRGB
  // grey 0.865) in the middle, the point ParaView's preset holds; RGB would give a dull purple.
  Rgb mid = twoPoints(ColourSpace::Diverging, cool, warm).at(0.5);
  EXPECT_LT(maxDiff(mid, {0.865, 0.865, 0.865}), 0.002) << mid[0] << " " << mid[1] << " " << mid[2];
  EXPECT_GT(maxDiff(twoPoints(ColourSpace::Rgb, cool, warm).at(0.5), mid), 0.3);
  ColourMap c2w = loadColourMap("Cool to Warm", ".");
  EXPECT_EQ(c2w.space, ColourSpace::Diverging);
  EXPECT_LT(maxDiff(c2w.at(0.5), {0.865, 0.865, 0.865}), 1e-12);
  // Quarter points against the values the viewer lists for this map (viewer/colormaps.js, written
  // apart from this code, from Moreland's published table), to 0.005.
  EXPECT_LT(maxDiff(c2w.at(0.25), {0.5530, 0.6889, 0.9954}), 0.005);
  EXPECT_LT(maxDiff(c2w.at(0.75), {0.9580, 0.6028, 0.4818}), 0.005);
  // The 3-point preset and the 2-point Msh map are the same curve.
  ColourMap two = twoPoints(ColourSpace::Diverging, cool, warm);
  for (double x : {0.1, 0.3, 0.45, 0.6, 0.9}) EXPECT_LT(maxDiff(c2w.at(x), two.at(x)), 0.003) << x;
}

TEST(ColourMap, LabInterpolatesInLabNotRgb) {
  // sRGB red's CIELAB coordinates (D65), as published: L 53.24, a 80.09, b 67.20.
  auto red = rgbToLab({1, 0, 0});
  EXPECT_NEAR(red[0], 53.24, 0.05);
  EXPECT_NEAR(red[1], 80.09, 0.2);
  EXPECT_NEAR(red[2], 67.20, 0.2);
  for (Rgb c : {Rgb{0.2, 0.5, 0.9}, Rgb{1, 1, 1}, Rgb{0.01, 0.02, 0.0}})
    EXPECT_LT(maxDiff(labToRgb(rgbToLab(c)), c), 2e-4);  // the matrices are given to 4 digits
  // Yellow to blue: through grey in RGB, through a light pink in Lab (whose midpoint is inside
  // the sRGB gamut, so no clipping blurs the check).
  Rgb a = {1, 1, 0}, b = {0, 0, 1};
  Rgb lab_mid = twoPoints(ColourSpace::Lab, a, b).at(0.5);
  auto la = rgbToLab(a), lb = rgbToLab(b), lm = rgbToLab(lab_mid);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(lm[i], 0.5 * (la[i] + lb[i]), 0.05) << i;
  EXPECT_GT(maxDiff(lab_mid, {0.5, 0.5, 0.5}), 0.15);  // the RGB midpoint
  EXPECT_EQ(parseColourSpace("CIELAB"), ColourSpace::Lab);
}

TEST(ColourMap, HsvGoesRoundTheRainbow) {
  // Blue to red in HSV passes through green (hue 2/3 -> 0, not wrapped through magenta), as
  // ParaView's "Blue to Red Rainbow" does.
  ColourMap m = twoPoints(ColourSpace::Hsv, {0, 0, 1}, {1, 0, 0});
  EXPECT_LT(maxDiff(m.at(0.5), {0, 1, 0}), 1e-12);
  EXPECT_LT(maxDiff(m.at(0.25), {0, 1, 1}), 1e-12);
}

// A private temporary directory, removed at the end of the test.
class ColourMapFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    dir_ = fs::temp_directory_path() / ("sortlast_colormap_test_" + std::to_string(::getpid()) +
                                        "_" + std::to_string(counter++));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  fs::path dir_;
};

// As ParaView exports two presets: with opacity Points, NanColor, Creator, over x in [-5, 15].
const char* kTwoPresets = R"([
  {"ColorSpace": "Lab", "Creator": "a test", "Name": "First", "NanColor": [1, 1, 0],
   "Points": [-5, 0, 0.5, 0, 15, 1, 0.5, 0],
   "RGBPoints": [-5, 0, 0, 1,  0, 0, 1, 0,  15, 1, 0, 0]},
  {"ColorSpace": "RGB", "Name": "Second", "RGBPoints": [0, 1, 1, 1, 1, 0, 0, 0]}
])";

TEST_F(ColourMapFiles, PresetFileRoundTrip) {
  std::string path = write("two.json", kTwoPresets);
  ColourMap first = loadColourMap(path, "/nowhere");
  EXPECT_EQ(first.name, "First");
  EXPECT_EQ(first.space, ColourSpace::Lab);
  ASSERT_EQ(first.knots.size(), 3u);
  EXPECT_EQ(first.knots[0].x, 0.0);
  EXPECT_NEAR(first.knots[1].x, 0.25, 1e-15);  // x = 0 of [-5, 15]
  EXPECT_EQ(first.knots[2].x, 1.0);
  EXPECT_LT(maxDiff(first.at(0.25), {0, 1, 0}), 1e-12);
  // By name, relative to the base directory; a single object instead of an array.
  EXPECT_EQ(loadColourMap("two.json#Second", dir_).name, "Second");
  EXPECT_EQ(loadColourMap("two.json#Second", dir_).at(0.5), (Rgb{0.5, 0.5, 0.5}));
  write("one.json",
        R"({"Name": "Lone", "ColorSpace": "RGB", "RGBPoints": [2, 0, 0, 0, 4, 1, 1, 1]})");
  EXPECT_EQ(loadColourMap("one.json", dir_).name, "Lone");
  // Written out and read back: the same map.
  nlohmann::json out = nlohmann::json::array();
  nlohmann::json pts = nlohmann::json::array();
  for (const ColourKnot& k : first.knots)
    pts.insert(pts.end(), {k.x, k.rgb[0], k.rgb[1], k.rgb[2]});
  out.push_back({{"Name", "Again"}, {"ColorSpace", "Lab"}, {"RGBPoints", pts}});
  ColourMap again = loadColourMap(write("again.json", out.dump()), ".");
  for (double x = 0; x <= 1; x += 1.0 / 64) EXPECT_LT(maxDiff(again.at(x), first.at(x)), 1e-12);
}

TEST_F(ColourMapFiles, SceneKeyColoursKeepOpacity) {
  fs::create_directories(dir_ / "maps");
  write("maps/two.json", kTwoPresets);
  // Relative to the scene file; the sharp preset's opacity (a narrow band) kept exactly.
  std::string scene =
      write("scene.yaml", "transfer: {preset: sharp, colormap: maps/two.json#First}\n");
  Scene s = loadScene(scene, {});
  EXPECT_EQ(s.transfer.colormap, "maps/two.json#First");
  TransferFunction with(s.transfer.points, 0, 1, 1),
      plain(TransferFunction::preset("sharp"), 0, 1, 1);
  ColourMap first = loadColourMap("two.json", dir_ / "maps");
  std::vector<ColourKnot> colours = first.sampled();
  double worst = 0;  // the chords of a Lab curve: measured 0.1/255 (296 knots)
  for (int i = 0; i <= 2000; ++i) {
    double x = i / 2000.0;
    EXPECT_NEAR(with.opacity(x), plain.opacity(x), 1e-12) << x;
    worst = std::max(worst, maxDiff(with.colour(x), first.at(x)));
  }
  EXPECT_LT(worst, 0.5 / 255);
  for (const ColourKnot& k : colours) EXPECT_LT(maxDiff(with.colour(k.x), k.rgb), 1e-12);
  // A step in the opacity (two points at one value) survives.
  std::vector<TfPoint> step = {
      {0, 0, 0, 0, 0}, {0.5, 0, 0, 0, 0}, {0.5, 0, 0, 0, 1}, {1, 0, 0, 0, 1}};
  std::vector<TfPoint> merged = applyColourMap(step, colours);
  TransferFunction st(merged, 0, 1, 1);
  EXPECT_EQ(st.opacity(0.5 - 1e-9), 0.0);
  EXPECT_EQ(st.opacity(0.5 + 1e-9), 1.0);
  // With --set, relative to the working directory: the scene's folder is not searched.
  std::string msg = inputErrorOf([&] { loadScene(scene, {"transfer.colormap=two.json"}); });
  EXPECT_NE(msg.find("cannot open"), std::string::npos) << msg;
  // A frame key, like every transfer.* key.
  EXPECT_TRUE(isFrameKey("transfer.colormap"));
}

TEST_F(ColourMapFiles, EveryMalformedFileIsNamedWithItsProblem) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{\"RGBPoints\": [0, 0, 0", "not valid JSON"},
      {"[{\"RGBPoints\": [0, 0, 0, 0, 1, NaN, 1, 1]}]", "NaN and Infinity are not JSON numbers"},
      {"42", "expected a colour-map preset"},
      {"[]", "the array holds no colour map"},
      {"[{\"Name\": \"x\"}]", "no RGBPoints"},
      {"[{\"IndexedColors\": [1, 0, 0]}]", "indexed (categorical) colour map"},
      {"{\"RGBPoints\": \"0 0 0 0\"}", "RGBPoints must be an array"},
      {"{\"ColorSpace\": \"Step\", \"RGBPoints\": [0, 0, 0, 0, 1, 1, 1, 1]}",
       "unknown ColorSpace \"Step\" (known: RGB, Lab, CIELAB, Diverging, HSV)"},
      {"{\"ColorSpace\": 3, \"RGBPoints\": [0, 0, 0, 0, 1, 1, 1, 1]}",
       "ColorSpace must be a string"},
      {"{\"RGBPoints\": [0, 0, 0, 0]}",
       "RGBPoints holds 1 point(s): a colour map needs at least 2"},
      {"{\"RGBPoints\": [0, 0, 0, 0, 1, 1, 1]}",
       "RGBPoints holds 7 numbers: expected groups of four"},
      {"{\"RGBPoints\": [0, 0, 0, 0, 1, \"red\", 1, 1]}", "RGBPoints[5] is \"red\", not a number"},
      {"{\"RGBPoints\": [0, 0, 0, 0, 1, null, 1, 1]}", "RGBPoints[5] is null, not a number"},
      {"{\"RGBPoints\": [0, 0, 0, 0, 1e999, 1, 1, 1]}",
       "not valid JSON: number overflow parsing '1e999'"},
      {"{\"RGBPoints\": [0, 0, 0, 0, 0.5, 1, 1, 1, 0.5, 1, 1, 1]}",
       "RGBPoints point 2: x = 0.5 does not follow x = 0.5 of the point before (x must increase)"},
      {"{\"RGBPoints\": [1, 0, 0, 0, 0, 1, 1, 1]}", "x must increase"},
      {"{\"RGBPoints\": [0, 0, 0, 0, 1, 1, 1.5, 1]}",
       "RGBPoints point 1 (x = 1): g = 1.5 is outside [0, 1]"},
      {"{\"RGBPoints\": [0, -0.1, 0, 0, 1, 1, 1, 1]}", "r = -0.1 is outside [0, 1]"},
  };
  int n = 0;
  for (const auto& [text, problem] : cases) {
    std::string path = write("bad" + std::to_string(n++) + ".json", text);
    std::string msg = inputErrorOf([&] { loadScene("", {"transfer.colormap=" + path}); });
    SCOPED_TRACE(text);
    EXPECT_EQ(msg.rfind("scene key 'transfer.colormap': colour-map file " + path + ": ", 0), 0u)
        << msg;
    EXPECT_NE(msg.find(problem), std::string::npos) << msg;
  }
  // Several presets: the message names the one at fault; a name the file lacks lists its names.
  std::string two = write("two.json", R"([{"Name": "A", "RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1]},
                                          {"Name": "B", "RGBPoints": [0, 0, 0, 0]}])");
  std::string msg = inputErrorOf([&] { loadColourMap(two + "#B", "."); });
  EXPECT_NE(msg.find("colour map \"B\": RGBPoints holds 1 point(s)"), std::string::npos) << msg;
  msg = inputErrorOf([&] { loadColourMap(two + "#C", "."); });
  EXPECT_NE(msg.find("holds no colour map named \"C\" (it holds \"A\", \"B\")"), std::string::npos)
      << msg;
  msg = inputErrorOf([&] { loadColourMap((dir_ / "missing.json").string(), "."); });
  EXPECT_NE(msg.find("colour-map file " + (dir_ / "missing.json").string() + ": cannot open"),
            std::string::npos)
      << msg;
}

TEST(ColourMap, UnknownNameListsTheBuiltins) {
  std::string msg = inputErrorOf([] { loadScene("", {"transfer.colormap=Viridian"}); });
  EXPECT_EQ(msg.rfind("scene key 'transfer.colormap': unknown colour map 'Viridian'", 0), 0u)
      << msg;
  for (const auto& [paraview, alias] : kRequired)
    EXPECT_NE(msg.find(paraview + " (" + alias + ")"), std::string::npos) << msg;
  EXPECT_NE(msg.find("FILE.json#Name"), std::string::npos) << msg;
}

TEST(ColourMap, RequestsMayNameBuiltinsOnly) {
  auto t = translateRequest(nlohmann::json::parse(R"({"transfer.colormap": "Cool to Warm"})"));
  ASSERT_EQ(t.overrides.size(), 1u);
  Scene s = loadScene("", t.overrides);  // the override parses back to the name
  EXPECT_EQ(s.transfer.colormap, "Cool to Warm");
  EXPECT_EQ(
      translateRequest(nlohmann::json::parse(R"({"transfer": {"colormap": ""}})")).overrides.size(),
      1u);
  for (const char* body :
       {R"({"transfer.colormap": "maps/x.json"})", R"({"transfer": {"colormap": "/etc/x.json#A"}})",
        R"({"transfer.colormap": 3})"}) {
    std::string msg = inputErrorOf([&] { translateRequest(nlohmann::json::parse(body)); });
    EXPECT_EQ(msg.rfind("key 'transfer.colormap': ", 0), 0u) << msg;
    EXPECT_NE(msg.find("built-in colour map"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace sortlast
