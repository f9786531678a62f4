// Time series keys (volume.files, particles.files, time.step), which keys a resident session may
// change per frame, and the translation of a client's JSON request into scene overrides.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "common/error.h"
#include "scene/scene.h"
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

}  // namespace
}  // namespace sortlast
