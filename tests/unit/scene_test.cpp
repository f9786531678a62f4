// Scene loading (common/scene.h): defaults, --set overrides, and rejection of bad input.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "tests/unit/input_error_of.h"
#include "common/error.h"
#include "common/scene.h"

namespace sortlast {
namespace {

namespace fs = std::filesystem;

// A private temporary directory, removed at the end of the test.
class SceneFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    dir_ = fs::temp_directory_path() /
           ("sortlast_scene_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string write(const std::string& name, const std::string& text) {
    fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }
  fs::path dir_;
};


// The default of `key` in the key table, as written there.
std::string tableDefault(const std::string& key) {
  for (const SceneKey& k : sceneKeys())
    if (key == k.path) return k.default_yaml;
  ADD_FAILURE() << "no key " << key << " in sceneKeys()";
  return "0";
}

TEST(Scene, BuiltInDefaults) {
  Scene s = loadScene("", {});
  // Defaults the rest of the project relies on.
  EXPECT_EQ(s.volume.grid.dims, glm::ivec3(128, 128, 128));
  EXPECT_EQ(s.volume.grid.spacing, glm::dvec3(1.0));
  EXPECT_TRUE(s.volume.file.empty());
  EXPECT_EQ(s.volume.procedural, "blobs");
  EXPECT_EQ(s.camera.width, 512);
  EXPECT_EQ(s.camera.height, 512);
  EXPECT_EQ(s.bricks_per_axis, 2);
  EXPECT_EQ(s.backend, "osmesa");
  EXPECT_EQ(s.strategy, "direct");
  EXPECT_TRUE(s.camera_auto);
  EXPECT_EQ(s.orbit_frames, 0);
  EXPECT_EQ(s.camera.up, glm::dvec3(0.0, 1.0, 0.0));
  // Tunable numbers: whatever the key table says (it is also the documentation).
  EXPECT_DOUBLE_EQ(s.camera.fov_deg, std::stod(tableDefault("camera.fov")));
  EXPECT_DOUBLE_EQ(s.sample_spacing, std::stod(tableDefault("render.sample_spacing")));
  EXPECT_DOUBLE_EQ(s.reference_step, std::stod(tableDefault("reference.step")));
  EXPECT_EQ(s.transfer.table_size, std::stoi(tableDefault("transfer.table_size")));
  EXPECT_FALSE(s.transfer.range.has_value());
  EXPECT_FALSE(s.transfer.unit_length.has_value());
  EXPECT_EQ(s.transfer.points.size(), TransferFunction::preset("default").size());
  EXPECT_EQ(s.frameCameras(s.volume.grid.worldBox()).size(), 1u);
}

TEST(Scene, SetOverrides) {
  Scene s = loadScene("", {"volume.dims=[64,32,16]", "camera.orbit.frames=8", "image.width=100",
                           "render.backend=egl", "bricks.per_axis=3",
                           "transfer.points=[[0,0,0,0,0],[1,1,0.5,0.25,0.75]]"});
  EXPECT_EQ(s.volume.grid.dims, glm::ivec3(64, 32, 16));
  EXPECT_EQ(s.orbit_frames, 8);
  EXPECT_EQ(s.frameCameras(s.volume.grid.worldBox()).size(), 8u);
  EXPECT_EQ(s.camera.width, 100);
  EXPECT_EQ(s.camera.height, 512);  // untouched keys keep their defaults
  EXPECT_EQ(s.backend, "egl");
  EXPECT_EQ(s.bricks_per_axis, 3);
  ASSERT_EQ(s.transfer.points.size(), 2u);
  EXPECT_DOUBLE_EQ(s.transfer.points[1].g, 0.5);
  EXPECT_DOUBLE_EQ(s.transfer.points[1].a, 0.75);
}

TEST_F(SceneFiles, FileValuesAndOverridesOnTop) {
  std::string path = write("scene.yaml",
                           "volume:\n  dims: [10, 20, 30]\n  spacing: [1, 2, 0.5]\n"
                           "image:\n  width: 64\n  height: 48\n"
                           "camera:\n  position: [0, 0, 100]\n  orbit:\n    frames: 3\n"
                           "bricks:\n  per_axis: 4\n");
  Scene s = loadScene(path, {});
  EXPECT_EQ(s.volume.grid.dims, glm::ivec3(10, 20, 30));
  EXPECT_EQ(s.volume.grid.spacing, glm::dvec3(1.0, 2.0, 0.5));
  EXPECT_EQ(s.camera.width, 64);
  EXPECT_EQ(s.camera.height, 48);
  EXPECT_FALSE(s.camera_auto);
  EXPECT_EQ(s.camera.position, glm::dvec3(0.0, 0.0, 100.0));
  EXPECT_EQ(s.orbit_frames, 3);
  EXPECT_EQ(s.bricks_per_axis, 4);
  EXPECT_EQ(s.backend, "osmesa");

  Scene o = loadScene(path, {"image.width=100", "camera.orbit.frames=0"});
  EXPECT_EQ(o.camera.width, 100);
  EXPECT_EQ(o.camera.height, 48);
  EXPECT_EQ(o.orbit_frames, 0);
  EXPECT_EQ(o.volume.grid.dims, glm::ivec3(10, 20, 30));
}

TEST_F(SceneFiles, UnknownKeyInFileNamesTheKey) {
  std::string path = write("typo.yaml", "image:\n  widht: 64\n");
  std::string msg = inputErrorOf([&] { loadScene(path, {}); });
  EXPECT_NE(msg.find("image.widht"), std::string::npos) << msg;
  path = write("typo_top.yaml", "colour_map: hot\n");
  msg = inputErrorOf([&] { loadScene(path, {}); });
  EXPECT_NE(msg.find("colour_map"), std::string::npos) << msg;
}

TEST(Scene, UnknownKeyInSetNamesTheKey) {
  std::string msg = inputErrorOf([] { loadScene("", {"camera.orbit.framez=8"}); });
  EXPECT_NE(msg.find("camera.orbit.framez"), std::string::npos) << msg;
  msg = inputErrorOf([] { loadScene("", {"nonsense=1"}); });
  EXPECT_NE(msg.find("nonsense"), std::string::npos) << msg;
}

TEST_F(SceneFiles, MalformedYamlThrows) {
  std::string path = write("bad.yaml", "volume:\n  dims: [1, 2\n  spacing: {a: \n");
  inputErrorOf([&] { loadScene(path, {}); });
  path = write("list.yaml", "- a\n- b\n");  // valid YAML, but not a map of keys
  inputErrorOf([&] { loadScene(path, {}); });
}

TEST_F(SceneFiles, MissingFileThrows) {
  std::string msg = inputErrorOf([&] { loadScene((dir_ / "does_not_exist.yaml").string(), {}); });
  EXPECT_NE(msg.find("does_not_exist.yaml"), std::string::npos) << msg;
}

TEST(Scene, InvalidValuesThrow) {
  inputErrorOf([] { loadScene("", {"image.width=0"}); });
  inputErrorOf([] { loadScene("", {"image.height=-3"}); });
  std::string msg = inputErrorOf([] { loadScene("", {"render.backend=vulkan"}); });
  EXPECT_NE(msg.find("vulkan"), std::string::npos) << msg;
  inputErrorOf([] { loadScene("", {"transfer.points=[[0,0,0,0],[1,1,1,1,1]]"}); });   // 4 entries
  inputErrorOf([] { loadScene("", {"transfer.points=[[0,0,0,0,0,0]]"}); });          // 6 entries
  inputErrorOf([] { loadScene("", {"volume.dims=[64,64]"}); });
  inputErrorOf([] { loadScene("", {"image.width=wide"}); });
  inputErrorOf([] { loadScene("", {"compositing.strategy=binary_swap"}); });
  inputErrorOf([] { loadScene("", {"image.width"}); });  // no '='
  // NaN fails every range (std::abs(NaN) > 90 let it through the elevation's: NaN cameras).
  EXPECT_EQ(inputErrorOf([] { loadScene("", {"camera.orbit.elevation=.nan", "camera.orbit.frames=4"}); }),
            "scene key 'camera.orbit.elevation': must be in [-90, 90] degrees");
}

TEST(Scene, CompositingStrategies) {
  for (const char* name : {"direct", "binary-swap", "radix-k"})
    EXPECT_EQ(loadScene("", {std::string("compositing.strategy=") + name}).strategy, name);
  EXPECT_EQ(loadScene("", {}).radix, std::stoi(tableDefault("compositing.radix")));
  EXPECT_EQ(loadScene("", {"compositing.radix=2"}).radix, 2);
  EXPECT_EQ(loadScene("", {"compositing.radix=7"}).radix, 7);
  std::string msg = inputErrorOf([] { loadScene("", {"compositing.strategy=tree"}); });
  EXPECT_NE(msg.find("compositing.strategy"), std::string::npos) << msg;
  EXPECT_NE(msg.find("tree"), std::string::npos) << msg;
  msg = inputErrorOf([] { loadScene("", {"compositing.radix=1"}); });
  EXPECT_NE(msg.find("compositing.radix"), std::string::npos) << msg;
  inputErrorOf([] { loadScene("", {"compositing.radix=two"}); });
}

TEST(Scene, Preintegration) {
  // `auto`: on where the opacity is steep (0.5 within 10 % of the range), where supported.
  EXPECT_EQ(tableDefault("transfer.preintegrated"), "auto");
  EXPECT_FALSE(loadScene("", {}).transfer.preintegrated);  // the default preset: slope 1.5
  EXPECT_FALSE(loadScene("", {"transfer.preset=ramp"}).transfer.preintegrated);
  EXPECT_TRUE(loadScene("", {"transfer.preset=sharp"}).transfer.preintegrated);  // slope 18
  EXPECT_FALSE(loadScene("", {"transfer.preset=sharp", "adaptive.tolerance=10"}).transfer.preintegrated);
  EXPECT_FALSE(loadScene("", {"transfer.preset=sharp", "render.sample_spacing=3"}).transfer.preintegrated);
  EXPECT_FALSE(loadScene("", {"transfer.preset=sharp", "transfer.preintegrated=false"}).transfer.preintegrated);
  EXPECT_TRUE(hasSteepOpacity({{0.0, 0, 0, 0, 0}, {0.09, 0, 0, 0, 0.5}}));
  EXPECT_FALSE(hasSteepOpacity({{0.0, 0, 0, 0, 0}, {0.11, 0, 0, 0, 0.5}}));
  EXPECT_TRUE(hasSteepOpacity({{0.0, 0, 0, 0, 0.9}, {0.05, 0, 0, 0, 0.0}}));  // falling too
  EXPECT_TRUE(loadScene("", {"transfer.preintegrated=true", "render.sample_spacing=2"}).transfer.preintegrated);
  // Refused: with adaptive sampling, and with steps whose segment ends pass the ghost layer.
  std::string msg = inputErrorOf([] { loadScene("", {"transfer.preintegrated=true", "adaptive.tolerance=10"}); });
  EXPECT_NE(msg.find("transfer.preintegrated"), std::string::npos) << msg;
  EXPECT_NE(msg.find("adaptive.tolerance"), std::string::npos) << msg;
  msg = inputErrorOf([] { loadScene("", {"transfer.preintegrated=true", "render.sample_spacing=2.01"}); });
  EXPECT_NE(msg.find("transfer.preintegrated"), std::string::npos) << msg;
  EXPECT_NE(msg.find("render.sample_spacing"), std::string::npos) << msg;
  inputErrorOf([] { loadScene("", {"transfer.preintegrated=maybe"}); });
}

TEST(Scene, VolumeMethod) {
  Scene s = loadScene("", {});
  EXPECT_EQ(s.volume_method, tableDefault("render.method"));
  EXPECT_DOUBLE_EQ(s.ert_threshold, std::stod(tableDefault("render.ert_threshold")));
  s = loadScene("", {"render.method=raycast", "render.ert_threshold=1"});
  EXPECT_EQ(s.volume_method, "raycast");
  EXPECT_EQ(s.ert_threshold, 1.0);
  std::string msg = inputErrorOf([] { loadScene("", {"render.method=splatting"}); });
  EXPECT_NE(msg.find("render.method"), std::string::npos) << msg;
  for (const char* bad : {"render.ert_threshold=0", "render.ert_threshold=1.5", "render.ert_threshold=-0.2"}) {
    msg = inputErrorOf([&] { loadScene("", {bad}); });
    EXPECT_NE(msg.find("render.ert_threshold"), std::string::npos) << msg;
  }
  s = loadScene("", {"render.adaptive_step=true", "render.adaptive_tolerance=0.1", "render.ray_block_cells=16"});
  EXPECT_TRUE(s.adaptive_step);
  EXPECT_EQ(s.adaptive_step_tolerance, 0.1);
  EXPECT_EQ(s.ray_block_cells, 16);
  EXPECT_TRUE(isFrameKey("render.adaptive_step"));
  EXPECT_TRUE(isFrameKey("render.adaptive_tolerance"));
  EXPECT_FALSE(isFrameKey("render.ray_block_cells"));  // the blocks are cut when bricks upload
  for (const char* bad : {"render.adaptive_tolerance=0", "render.adaptive_tolerance=1.5", "render.adaptive_step=maybe",
                          "render.ray_block_cells=0"}) {
    msg = inputErrorOf([&] { loadScene("", {bad}); });
    std::string key(bad);
    key = key.substr(0, key.find('='));
    EXPECT_NE(msg.find(key), std::string::npos) << msg;
  }
}

TEST_F(SceneFiles, InvalidValueInFileThrows) {
  std::string path = write("w0.yaml", "image:\n  width: 0\n");
  inputErrorOf([&] { loadScene(path, {}); });
  path = write("tf.yaml", "transfer:\n  points:\n    - [0, 0, 0, 0]\n");
  std::string msg = inputErrorOf([&] { loadScene(path, {}); });
  EXPECT_NE(msg.find("transfer.points"), std::string::npos) << msg;
}

TEST(Scene, KeysMarkdownListsEveryKey) {
  std::string md = sceneKeysMarkdown();
  ASSERT_FALSE(sceneKeys().empty());
  for (const SceneKey& k : sceneKeys())
    EXPECT_NE(md.find("`" + std::string(k.path) + "`"), std::string::npos) << k.path;
  // Every key can be set on the command line to its own default.
  for (const SceneKey& k : sceneKeys()) {
    std::string o = std::string(k.path) + "=" + k.default_yaml;
    EXPECT_NO_THROW(loadScene("", {o})) << o;
  }
}

}  // namespace
}  // namespace sortlast
