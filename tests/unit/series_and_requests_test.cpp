// Time series keys (volume.files, particles.files, time.step), which keys a resident session may
// change per frame, and the translation of a client's JSON request into scene overrides.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "app/render_job.h"
#include "common/error.h"
#include "scene/scene.h"
#include "service/frame_recorder.h"
#include "service/request_translation.h"
#include "tests/unit/input_error_of.h"

namespace sortlast {
namespace {

namespace fs = std::filesystem;

class SeriesFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("sortlast_series_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    for (const char* f : {"step_2.raw", "step_0.raw", "step_1.raw", "other.raw"}) std::ofstream(dir_ / f) << "x";
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string scene(const std::string& text) {
    std::ofstream(dir_ / "s.yaml") << text;
    return (dir_ / "s.yaml").string();
  }
  fs::path dir_;
};

TEST_F(SeriesFiles, GlobIsSortedAndRelativeToTheSceneFile) {
  Scene s = loadScene(scene("volume: {files: \"step_*.raw\"}\n"), {});
  ASSERT_EQ(s.time.volume_files.size(), 3u);
  EXPECT_EQ(s.time.steps, 3);
  EXPECT_EQ(fs::path(s.time.volume_files[0]).filename(), "step_0.raw");
  EXPECT_EQ(fs::path(s.time.volume_files[2]).filename(), "step_2.raw");
  EXPECT_EQ(s.volume.file, s.time.volume_files[0]);  // time.step 0
  Scene s2 = loadScene(scene("volume: {files: \"step_*.raw\"}\n"), {"time.step=2"});
  EXPECT_EQ(fs::path(s2.volume.file).filename(), "step_2.raw");
}

TEST_F(SeriesFiles, ListKeepsItsOrder) {
  Scene s = loadScene(scene("volume: {files: [other.raw, step_0.raw]}\n"), {"time.step=1"});
  EXPECT_EQ(fs::path(s.volume.file).filename(), "step_0.raw");
  EXPECT_EQ(s.time.steps, 2);
}

TEST_F(SeriesFiles, BadSeriesAreNamed) {
  EXPECT_NE(inputErrorOf([&] { loadScene(scene("volume: {files: \"nothing_*.raw\"}\n"), {}); }).find("no file matches"),
            std::string::npos);
  EXPECT_NE(inputErrorOf([&] { loadScene(scene("volume: {files: \"step_*.raw\"}\n"), {"time.step=3"}); })
                .find("'time.step': 3 is out of range"),
            std::string::npos);
  EXPECT_NE(inputErrorOf([&] { loadScene(scene("volume: {files: \"step_*.raw\", file: other.raw}\n"), {}); })
                .find("both set"),
            std::string::npos);
  EXPECT_NE(inputErrorOf([&] { loadScene(scene("volume: {files: \"step_*.raw\"}\nparticles: {files: [other.raw]}\n"), {}); })
                .find("3 and 1 steps"),
            std::string::npos);
  EXPECT_NE(inputErrorOf([&] { loadScene("", {"time.step=1"}); }).find("out of range"), std::string::npos);
}

// Glow emitters' rates run on through a series: step s of a scene with an N-frame orbit starts at
// frame s N (s without an orbit), and a rate is checked up to the last step's last frame.
TEST_F(SeriesFiles, GlowRatesRunThroughTheSeries) {
  const std::string text =
      "volume: {files: \"step_*.raw\"}\nglow: {box: [[-1, -1, -1], [1, 1, 1]], emitters: [{center: "
      "[0, 0, 0], velocity: [1, 0, 0], a: 1, a_rate: -0.1}]}\n";
  EXPECT_DOUBLE_EQ(loadScene(scene(text), {"time.step=2"}).glow.emittersAt(0)[0].centre.x, 2.0);
  Scene orbit = loadScene(scene(text), {"time.step=1", "camera.orbit.frames=3"});
  EXPECT_DOUBLE_EQ(orbit.glow.emittersAt(2)[0].centre.x, 5.0);  // frame 1 x 3 + 2
  EXPECT_DOUBLE_EQ(orbit.glow.emittersAt(2)[0].a, 0.5);
  // 3 steps x 4 frames: a reaches 1 - 11 x 0.1 < 0 at the last frame, refused at step 0 already.
  EXPECT_NE(inputErrorOf([&] { loadScene(scene(text), {"camera.orbit.frames=4"}); }).find("negative at frame 11"),
            std::string::npos);
}

TEST(FrameKeys, LayoutKeysAreNotFrameKeys) {
  for (const char* k : {"camera.position", "image.width", "transfer.points", "render.method",
                        "compositing.strategy", "time.step", "particles.color", "render.sample_spacing"})
    EXPECT_TRUE(isFrameKey(k)) << k;
  for (const char* k : {"volume.file", "volume.dims", "volume.files", "bricks.per_axis", "render.backend",
                        "adaptive.tolerance", "particles.file", "particles.count", "time.cache_mib",
                        "render.block_cells"})
    EXPECT_FALSE(isFrameKey(k)) << k;
}

// One entry of volumes, dotted or nested; its colour map is a built-in's name, never a file.
TEST(RequestTranslation, FieldEntryKeys) {
  auto t = translateRequest(nlohmann::json::parse(
      R"({"volumes[1]": {"transfer": {"colormap": "Viridis", "range": [0, 2]}, "visible": false},
          "volumes[0].transfer.scale": "log"})"));
  std::vector<std::string> want = {"volumes[0].transfer.scale=\"log\"", "volumes[1].transfer.colormap=\"Viridis\"",
                                   "volumes[1].transfer.range=[0,2]", "volumes[1].visible=false"};
  std::sort(t.overrides.begin(), t.overrides.end());
  EXPECT_EQ(t.overrides, want);
  EXPECT_NE(inputErrorOf([] { translateRequest(nlohmann::json::parse(R"({"volumes[1].transfer.colormap": "/etc/hostname"})")); })
                .find("key 'volumes[1].transfer.colormap': a request may name a built-in colour map only"),
            std::string::npos);
  EXPECT_NE(inputErrorOf([] { translateRequest(nlohmann::json::parse(R"({"volumes[0]": {"transfer": {"colormap": "x.json"}}})")); })
                .find("volumes[0].transfer.colormap"),
            std::string::npos);
}

TEST(RequestTranslation, DottedAndNestedKeysBecomeOverrides) {
  auto t = translateRequest(nlohmann::json::parse(
      R"({"id": 7, "camera": {"fov": 30, "position": [1, 2, 3]}, "image.width": 64,
          "render.method": "raycast", "format": "jpeg", "quality": 50})"));
  std::vector<std::string> want = {"camera.fov=30", "camera.position=[1,2,3]", "image.width=64",
                                   "render.method=\"raycast\""};
  std::sort(t.overrides.begin(), t.overrides.end());
  EXPECT_EQ(t.overrides, want);
  EXPECT_EQ(t.format, "jpeg");
  EXPECT_EQ(t.quality, 50);
  // The overrides parse as --set values would.
  Scene s = loadScene("", t.overrides);
  EXPECT_EQ(s.camera.fov_deg, 30);
  EXPECT_EQ(s.camera.position, glm::dvec3(1, 2, 3));
  EXPECT_EQ(nameOf(s.render.method), "raycast");
}

TEST(RequestTranslation, BadRequestsAreNamed) {
  EXPECT_NE(inputErrorOf([] { translateRequest(nlohmann::json::array()); }).find("JSON object"), std::string::npos);
  EXPECT_NE(inputErrorOf([] { nlohmann::json j;  // the parser refuses 1e999 itself; a client library might not
                              j["camera.position"] = {HUGE_VAL, 0.0, 0.0};
                              translateRequest(j); })
                .find("'camera.position'"),
            std::string::npos);
  EXPECT_NE(inputErrorOf([] { translateRequest(nlohmann::json::parse(R"({"format": "gif"})")); }).find("format"),
            std::string::npos);
  EXPECT_NE(inputErrorOf([] { translateRequest(nlohmann::json::parse(R"({"quality": 0})")); }).find("quality"),
            std::string::npos);
}

TEST(RequestTranslation, PackRoundTrips) {
  std::vector<std::string> o = {"camera.position=[1,2,3]", "transfer.points=[[0,0,0,0,0],[1,1,1,1,1]]", "x=\"a,b\""};
  EXPECT_EQ(unpackOverrides(packOverrides(o)), o);
}

// sortlast render --steps: all, A:B (both included), A:B:S; anything else refused naming --steps.
TEST(RenderSteps, ParsesRangesAndStrides) {
  EXPECT_EQ(parseSteps("all", 3), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(parseSteps("all", 1), (std::vector<int>{0}));
  EXPECT_EQ(parseSteps("1:3", 5), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(parseSteps("0:9:4", 10), (std::vector<int>{0, 4, 8}));
  EXPECT_EQ(parseSteps("2:2", 3), (std::vector<int>{2}));
  EXPECT_EQ(parseSteps("4:7", -1), (std::vector<int>{4, 5, 6, 7}));  // the count not known yet
  EXPECT_NE(inputErrorOf([] { parseSteps("0:5", 3); }).find("--steps 0:5: step 5 is out of range"), std::string::npos);
  EXPECT_NE(inputErrorOf([] { parseSteps("3:1", 5); }).find("before the first"), std::string::npos);
  EXPECT_NE(inputErrorOf([] { parseSteps("0:4:0", 5); }).find("stride"), std::string::npos);
  EXPECT_NE(inputErrorOf([] { parseSteps("-1:2", 5); }).find("below 0"), std::string::npos);
  for (const char* bad : {"", "3", "1:", ":2", "a:b", "1:2:3:4", "1.5:2", "1:2x"})
    EXPECT_NE(inputErrorOf([&] { parseSteps(bad, 5); }).find("--steps"), std::string::npos) << bad;
}

// A recorded frame of another size than the movie's is scaled to fit, aspect kept, centred on the
// background.
TEST(FrameRecorder, FitKeepsAspectOnTheBackground) {
  const std::vector<uint8_t> red = [] {
    std::vector<uint8_t> v(4 * 2 * 3, 0);
    for (size_t p = 0; p < 8; ++p) v[3 * p] = 200;
    return v;
  }();
  EXPECT_EQ(fitRGB8(red, 4, 2, 4, 2, glm::dvec3(0.0)), red);  // the same size: as is
  // 4x2 into 8x8: scaled by 2 to 8x4, rows 2-5; rows 0-1 and 6-7 are the background (blue).
  const std::vector<uint8_t> out = fitRGB8(red, 4, 2, 8, 8, glm::dvec3(0, 0, 1));
  ASSERT_EQ(out.size(), size_t(8 * 8 * 3));
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const uint8_t* px = &out[(size_t(y) * 8 + x) * 3];
      const bool inside = y >= 2 && y < 6;
      EXPECT_EQ(px[0], inside ? 200 : 0) << x << "," << y;
      EXPECT_EQ(px[2], inside ? 0 : 255) << x << "," << y;
    }
  // A horizontal ramp 30 x halved: output pixel i samples the input between pixels 2i and 2i + 1
  // (its centre at 2i + 0.5), so 30 (2i + 0.5) = 15, 75, 135, 195.
  std::vector<uint8_t> ramp(8 * 3 * 1);
  for (int x = 0; x < 8; ++x) ramp[3 * x] = ramp[3 * x + 1] = ramp[3 * x + 2] = uint8_t(30 * x);
  const std::vector<uint8_t> half = fitRGB8(ramp, 8, 1, 4, 1, glm::dvec3(0.0));
  for (int x = 0; x < 4; ++x) EXPECT_EQ(half[3 * x], 30 * (2 * x) + 15) << x;
}

}  // namespace
}  // namespace sortlast
