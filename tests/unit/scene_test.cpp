// Scene loading (scene/scene.h): defaults, --set overrides, and rejection of bad input.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "tests/unit/input_error_of.h"
#include "common/error.h"
#include "scene/file_steps.h"
#include "scene/scene.h"

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
  EXPECT_EQ(s.bricks.per_axis, 2);
  EXPECT_EQ(nameOf(s.render.backend), "osmesa");
  EXPECT_EQ(nameOf(s.compositing.strategy), "direct");
  EXPECT_TRUE(s.camera_auto);
  EXPECT_EQ(s.orbit.frames, 0);
  EXPECT_EQ(s.camera.up, glm::dvec3(0.0, 1.0, 0.0));
  // Tunable numbers: whatever the key table says (it is also the documentation).
  EXPECT_DOUBLE_EQ(s.camera.fov_deg, std::stod(tableDefault("camera.fov")));
  EXPECT_EQ(tableDefault("render.sample_spacing"), "auto");
  EXPECT_TRUE(s.render.sample_spacing_auto);
  EXPECT_DOUBLE_EQ(s.render.sample_spacing, 0.5);  // until the session's probe chooses
  EXPECT_DOUBLE_EQ(s.reference.step, std::stod(tableDefault("reference.step")));
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
  EXPECT_EQ(s.orbit.frames, 8);
  EXPECT_EQ(s.frameCameras(s.volume.grid.worldBox()).size(), 8u);
  EXPECT_EQ(s.camera.width, 100);
  EXPECT_EQ(s.camera.height, 512);  // untouched keys keep their defaults
  EXPECT_EQ(nameOf(s.render.backend), "egl");
  EXPECT_EQ(s.bricks.per_axis, 3);
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
  EXPECT_EQ(s.orbit.frames, 3);
  EXPECT_EQ(s.bricks.per_axis, 4);
  EXPECT_EQ(nameOf(s.render.backend), "osmesa");

  Scene o = loadScene(path, {"image.width=100", "camera.orbit.frames=0"});
  EXPECT_EQ(o.camera.width, 100);
  EXPECT_EQ(o.camera.height, 48);
  EXPECT_EQ(o.orbit.frames, 0);
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

// Every enum a key takes reads back the name it was given, and every name the table lists is one
// the enum has (nameOf never answers "?" for a value the parser produced).
TEST(Scene, EnumKeysRoundTrip) {
  for (const char* name : {"slicing", "raycast"})
    EXPECT_EQ(nameOf(loadScene("", {std::string("render.method=") + name}).render.method), name);
  for (const char* name : {"float", "rgba8"})
    EXPECT_EQ(nameOf(loadScene("", {std::string("compositing.precision=") + name}).compositing.precision), name);
  for (const char* name : {"own", "fine"})
    EXPECT_EQ(nameOf(loadScene("", {std::string("adaptive.steps=") + name}).adaptive.steps), name);
  for (const char* name : {"original", "adaptive"})
    EXPECT_EQ(nameOf(loadScene("", {std::string("reference.field=") + name}).reference.field), name);
  EXPECT_EQ(sceneKeyValues(sceneKey("compositing.strategy")), "`direct`, `binary-swap`, `radix-k` or `auto`");
  EXPECT_EQ(inputErrorOf([] { loadScene("", {"render.backend=vulkan"}); }),
            "scene key 'render.backend': expected osmesa or egl, got 'vulkan'");
}

// camera.orbit.start turns the whole orbit about camera.up: frame i of a start of 360/N degrees
// is frame i + 1 of no start, and the default is the orbit as before.
TEST(Scene, OrbitStart) {
  const Box3 box{{0, 0, 0}, {1, 1, 1}};
  const auto plain = loadScene("", {"camera.orbit.frames=4"}).frameCameras(box);
  const auto turned = loadScene("", {"camera.orbit.frames=4", "camera.orbit.start=90"}).frameCameras(box);
  ASSERT_EQ(plain.size(), 4u);
  ASSERT_EQ(turned.size(), 4u);
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(turned[i].position[a], plain[i + 1].position[a], 1e-9) << i;
  EXPECT_EQ(loadScene("", {}).orbit.start, std::stod(tableDefault("camera.orbit.start")));
  EXPECT_EQ(inputErrorOf([] { loadScene("", {"camera.orbit.start=400"}); }),
            "scene key 'camera.orbit.start': must be in [-360, 360] degrees");
}

// Parsing reads no data file: a NetCDF volume's steps (its records) are counted, and time.step
// checked against them, when the scene is loaded (resolveFileSteps), not when it is parsed.
TEST(Scene, ParsingReadsNoDataFile) {
  const std::string missing = "/nonexistent/sortlast-test/volume.nc";
  Scene s = loadScene("", {"volume.file=" + missing, "time.step=5"});
  EXPECT_TRUE(hasFileSteps(s));
  const std::string msg = inputErrorOf([&] { resolveFileSteps(s); });
  EXPECT_NE(msg.find(missing), std::string::npos) << msg;
  // A scene without steps in a file is resolved as parsed, and time.step is checked at once.
  Scene plain = loadScene("", {});
  EXPECT_FALSE(hasFileSteps(plain));
  resolveFileSteps(plain);
  EXPECT_EQ(plain.time.steps, 1);
  EXPECT_NE(inputErrorOf([] { loadScene("", {"time.step=1"}); }).find("time.step"), std::string::npos);
  // What needs no file is still refused by the parser: {step} in the dataset of a file that is not HDF5.
  EXPECT_NE(inputErrorOf([] { loadScene("", {"volume.file=x.raw", "volume.dataset=/s{step}/d"}); })
                .find("needs an HDF5 volume.file"),
            std::string::npos);
}

TEST(Scene, CompositingStrategies) {
  for (const char* name : {"direct", "binary-swap", "radix-k", "auto"})
    EXPECT_EQ(nameOf(loadScene("", {std::string("compositing.strategy=") + name}).compositing.strategy), name);
  EXPECT_EQ(loadScene("", {}).compositing.radix, std::stoi(tableDefault("compositing.radix")));
  EXPECT_EQ(loadScene("", {"compositing.radix=2"}).compositing.radix, 2);
  EXPECT_EQ(loadScene("", {"compositing.radix=7"}).compositing.radix, 7);
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
  EXPECT_EQ(nameOf(s.render.method), tableDefault("render.method"));
  EXPECT_DOUBLE_EQ(s.render.ert_threshold, std::stod(tableDefault("render.ert_threshold")));
  s = loadScene("", {"render.method=raycast", "render.ert_threshold=1"});
  EXPECT_EQ(nameOf(s.render.method), "raycast");
  EXPECT_EQ(s.render.ert_threshold, 1.0);
  std::string msg = inputErrorOf([] { loadScene("", {"render.method=splatting"}); });
  EXPECT_NE(msg.find("render.method"), std::string::npos) << msg;
  for (const char* bad : {"render.ert_threshold=0", "render.ert_threshold=1.5", "render.ert_threshold=-0.2"}) {
    msg = inputErrorOf([&] { loadScene("", {bad}); });
    EXPECT_NE(msg.find("render.ert_threshold"), std::string::npos) << msg;
  }
  s = loadScene("", {"render.adaptive_step=true", "render.adaptive_tolerance=0.1", "render.ray_block_cells=16"});
  EXPECT_TRUE(s.render.adaptive_step);
  EXPECT_EQ(s.render.adaptive_step_tolerance, 0.1);
  EXPECT_EQ(s.render.ray_block_cells, 16);
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

// --- The key table (scene/scene_keys.h) ---

// A key's field in `s`, through its row (none for a Structured key).
template <class F>
void forEachField(const SceneKey& k, F f) {
  std::visit(
      [&](const auto& type) {
        if constexpr (requires { type.field; }) f(type.field);
      },
      k.type);
}

// Scene{}'s initialisers (scene.h, particles.h, camera.h, ...) are the table's defaults, which
// the parser reads: for every key with a field, a default-constructed Scene, the built-in scene
// and the key set to its own default agree.
TEST(SceneKeys, StructDefaultsAreTheTableDefaults) {
  Scene constructed, parsed = loadScene("", {});
  int fields = 0;
  for (const SceneKey& k : sceneKeys()) {
    Scene set = loadScene("", {std::string(k.path) + "=" + k.default_yaml});
    forEachField(k, [&](auto field) {
      EXPECT_EQ(field(constructed), field(parsed)) << k.path << " = " << k.default_yaml;
      EXPECT_EQ(field(set), field(parsed)) << k.path << " = " << k.default_yaml;
      ++fields;
    });
  }
  EXPECT_GE(fields, 70);
  // The structured keys' defaults: none of each.
  EXPECT_FALSE(parsed.transfer.range.has_value());
  EXPECT_TRUE(parsed.transfer.colormap.empty());
  EXPECT_FALSE(parsed.glow.box.has_value());
  EXPECT_TRUE(parsed.glow.emitters.empty());
  EXPECT_TRUE(parsed.surfaces.empty());
  EXPECT_TRUE(parsed.time.volume_files.empty() && parsed.time.particle_files.empty());
  EXPECT_EQ(parsed.transfer.points.size(),
            TransferFunction::preset(tableDefault("transfer.preset")).size());
}

// Every message a single bad key gave before the table (tests/mpi/bad_input.sh, the service's and
// in situ's tests pin some of them), each key's wording as it was.
TEST(SceneKeys, ErrorsKeepTheirWording) {
  const std::pair<const char*, const char*> cases[] = {
      {"volume.dims=[1,2,3]", "scene key 'volume.dims': entries must be integers in [2, 2^20]"},
      {"volume.type=auto",
       "volume.type: unknown type 'auto' (known: uint8, uint16, int16, float32, float64)"},
      {"volume.spacing=[0,0,0]",
       "scene key 'volume.spacing': 0 is outside [1e-12, 1e18], the lengths float math on the GPU can hold"},
      {"volume.byte_order=auto",
       "scene key 'volume.byte_order': expected little or big, got 'auto'"},
      {"volume.header_bytes=-1", "scene key 'volume.header_bytes': must be >= 0"},
      {"particles.procedural=auto",
       "scene key 'particles.procedural': expected none, layers or splash, got 'auto'"},
      {"particles.format=abc",
       "scene key 'particles.format': expected auto, vtk, raw, csv or hdf5, got 'abc'"},
      {"particles.count=-1",
       "scene key 'particles.count': must be auto or in [0, 2147483648], got -1"},
      {"particles.spacing=0", "scene key 'particles.spacing': must be a finite number > 0"},
      {"particles.spacing=1e-13",
       "scene key 'particles.spacing': 1e-13 is outside [1e-12, 1e18], the lengths float math on the GPU can hold"},
      {"particles.radius=0", "scene key 'particles.radius': must be a finite number > 0"},
      {"particles.radius=1e-13",
       "scene key 'particles.radius': 1e-13 is outside [1e-12, 1e18], the lengths float math on the GPU can hold"},
      {"particles.influence=0", "scene key 'particles.influence': must be a finite number > 0"},
      {"particles.influence=1e-13",
       "scene key 'particles.influence': 1e-13 is outside [1e-12, 1e18], the lengths float math on the GPU can hold"},
      {"particles.threshold=0", "scene key 'particles.threshold': must be in (0, 1)"},
      {"particles.color=[1,2,3]", "scene key 'particles.color': entries must be in [0, 1]"},
      {"particles.method=auto",
       "scene key 'particles.method': expected billboards, grid or slices, got 'auto'"},
      {"particles.slice_spacing=0",
       "scene key 'particles.slice_spacing': must be in [0.05, 1] (units of h), got 0"},
      {"particles.slice_spacing=.nan",
       "scene key 'particles.slice_spacing': must be in [0.05, 1] (units of h), got .nan"},
      {"particles.step=0", "scene key 'particles.step': must be a finite number > 0"},
      {"particles.max_samples=0", "scene key 'particles.max_samples': must be >= 1"},
      {"particles.refine_iterations=-1", "scene key 'particles.refine_iterations': must be >= 0"},
      {"particles.samples_per_pass=0", "scene key 'particles.samples_per_pass': must be 4 or 8"},
      {"particles.smoothing=bumpy",
       "scene key 'particles.smoothing': expected none, anisotropic or auto, got 'bumpy'"},
      {"particles.anisotropic.splash_scale=0",
       "scene key 'particles.anisotropic.splash_scale': must be in [1/64, 8] (units of h), got 0"},
      {"particles.anisotropic.splash_scale=.nan",
       "scene key 'particles.anisotropic.splash_scale': must be in [1/64, 8] (units of h), got nan"},
      {"particles.anisotropic.surface_scale=0",
       "scene key 'particles.anisotropic.surface_scale': must be in [1/64, 8] (units of h), got 0"},
      {"particles.anisotropic.rho_splash=-1",
       "scene key 'particles.anisotropic.rho_splash': must be in [0, 1e9], got -1"},
      {"particles.anisotropic.rho_splash=6",
       "scene key 'particles.anisotropic.rho_surface': must be above particles.anisotropic.rho_splash (6), got 6"},
      {"particles.anisotropic.rho_surface=0",
       "scene key 'particles.anisotropic.rho_surface': must be above particles.anisotropic.rho_splash (3), got 0"},
      {"particles.anisotropic.rho_surface=-1",
       "scene key 'particles.anisotropic.rho_surface': must be in [0, 1e9], got -1"},
      {"particles.anisotropic.neighbourhood=0",
       "scene key 'particles.anisotropic.neighbourhood': must be in [1e-6, 8] (units of h), got 0"},
      {"particles.anisotropic.max_axis_ratio=0",
       "scene key 'particles.anisotropic.max_axis_ratio': must be in [1, 100], got 0"},
      {"transfer.preset=auto",
       "transfer.preset: unknown preset 'auto' (known: ramp, default, sharp)"},
      {"transfer.range=[1,1]", "scene key 'transfer.range': needs lo < hi"},
      {"transfer.unit_length=0",
       "scene key 'transfer.unit_length': 0 is outside [1e-12, 1e18], the lengths float math on the GPU can hold"},
      {"transfer.unit_length=.nan",
       "scene key 'transfer.unit_length': nan is outside [1e-12, 1e18], the lengths float math on the GPU can hold"},
      {"transfer.table_size=0", "scene key 'transfer.table_size': must be in [2, 16384]"},
      {"image.width=0", "image size 0 x 512: image.width and image.height must be in [1, 32768]"},
      {"image.height=0", "image size 512 x 0: image.width and image.height must be in [1, 32768]"},
      {"camera.position=[0,0,0]", "camera.position equals camera.look_at: no view direction"},
      {"camera.position=[2e18,0,0]",
       "scene key 'camera.position': 2e+18 is beyond +-1e18, which float math on the GPU cannot hold (it squares distances)"},
      {"camera.position=[0,1,0]", "camera.up is parallel to the view direction"},
      {"camera.look_at=[2e18,0,0]",
       "scene key 'camera.look_at': 2e+18 is beyond +-1e18, which float math on the GPU cannot hold (it squares distances)"},
      {"camera.up=[0,0,0]",
       "scene key 'camera.up': must not be zero (its length must be at least 1e-12)"},
      {"camera.up=[2e18,0,0]",
       "scene key 'camera.up': 2e+18 is beyond +-1e18, which float math on the GPU cannot hold (it squares distances)"},
      {"camera.fov=0", "scene key 'camera.fov': must be in (0, 180) degrees"},
      {"camera.orbit.frames=-1", "scene key 'camera.orbit.frames': must be >= 0"},
      {"camera.orbit.elevation=1e9",
       "scene key 'camera.orbit.elevation': must be in [-90, 90] degrees"},
      {"camera.orbit.radius=0", "scene key 'camera.orbit.radius': must be > 0"},
      {"camera.orbit.radius=1e-13",
       "scene key 'camera.orbit.radius': 1e-13 is outside [1e-12, 1e18], the lengths float math on the GPU can hold"},
      {"camera.orbit.radius=.nan", "scene key 'camera.orbit.radius': must be > 0"},
      {"camera.orbit.radius=.inf",
       "scene key 'camera.orbit.radius': inf is outside [1e-12, 1e18], the lengths float math on the GPU can hold"},
      {"bricks.per_axis=0", "scene key 'bricks.per_axis': must be in [1, 64]"},
      {"render.backend=auto", "scene key 'render.backend': expected osmesa or egl, got 'auto'"},
      {"render.sample_spacing=0",
       "scene key 'render.sample_spacing': must be in [0.01, 100] voxels"},
      {"render.block_cells=0", "scene key 'render.block_cells': must be >= 1"},
      {"render.ray_block_cells=0", "scene key 'render.ray_block_cells': must be >= 1"},
      {"render.method=auto", "scene key 'render.method': expected slicing or raycast, got 'auto'"},
      {"render.ert_threshold=0",
       "scene key 'render.ert_threshold': must be in (0, 1] (1: no early termination)"},
      {"render.shading_ambient=-1", "scene key 'render.shading_ambient': must be in [0, 100]"},
      {"render.shading_diffuse=-1", "scene key 'render.shading_diffuse': must be in [0, 100]"},
      {"render.shading_specular=-1", "scene key 'render.shading_specular': must be in [0, 100]"},
      {"render.shading_shininess=0", "scene key 'render.shading_shininess': must be in [1, 1000]"},
      {"render.adaptive_tolerance=0", "scene key 'render.adaptive_tolerance': must be in (0, 1]"},
      {"adaptive.tolerance=-1", "scene key 'adaptive.tolerance': must be in [0, 100] percent"},
      {"adaptive.blocks=0",
       "scene key 'adaptive.blocks': must be a power of two in [1, 256], got 0"},
      {"adaptive.steps=auto", "scene key 'adaptive.steps': expected own or fine, got 'auto'"},
      {"compositing.strategy=fastest",
       "scene key 'compositing.strategy': expected direct, binary-swap, radix-k or auto, got 'fastest'"},
      {"compositing.bandwidth_gbps=0",
       "scene key 'compositing.bandwidth_gbps': must be in [0.001, 1e5] Gbit/s"},
      {"compositing.radix=0", "scene key 'compositing.radix': must be >= 2"},
      {"compositing.precision=auto",
       "scene key 'compositing.precision': expected float or rgba8, got 'auto'"},
      {"time.step=1",
       "scene key 'time.step': 1 is out of range: the scene has 1 time step(s), 0 ... 0"},
      {"time.cache_mib=-1", "scene key 'time.cache_mib': must be in [0, 1e9] MiB"},
      {"limits.memory_mib=0", "scene key 'limits.memory_mib': must be auto or in (0, 1e12] MiB"},
      {"glow.core_radius=0",
       "scene key 'glow.core_radius': 0 is outside [1e-12, 1e18], the lengths float math on the GPU can hold"},
      {"glow.intensity=-1", "scene key 'glow.intensity': must be in [0, 1e30]"},
      {"glow.tone_map=auto", "scene key 'glow.tone_map': expected none or exponential, got 'auto'"},
      {"glow.exposure=0", "scene key 'glow.exposure': must be in (0, 1e30]"},
      {"glow.box=abc",
       "scene key 'glow.box': expected auto or [[x0, y0, z0], [x1, y1, z1]] (line 1)"},
      {"glow.box=[[0,0,0],[0,1,1]]",
       "scene key 'glow.box': needs lo < hi on every axis (by at least 1e-12) (line 1)"},
      {"reference.step=0", "scene key 'reference.step': must be in (0, 1] voxels"},
      {"reference.field=auto",
       "scene key 'reference.field': expected original or adaptive, got 'auto'"},
      {"glow.box=[[2e18,0,0],[3e18,1,1]]",
       "scene key 'glow.box': 2e+18 is beyond +-1e18, which float math on the GPU cannot hold (it squares distances)"},
      {"transfer.range=[0,1e39]",
       "scene key 'transfer.range': 1e+39 is beyond float's range (+-3.4e38)"},
      {"volume.spacing=[1e16,1,1]",
       "scene key 'volume.spacing (times volume.dims - 1: the volume's extent)': 1.27e+18 is outside [1e-12, 1e18], the lengths float math on the GPU can hold"},
      {"particles.samples_per_pass=5", "scene key 'particles.samples_per_pass': must be 4 or 8"},
      {"adaptive.blocks=3",
       "scene key 'adaptive.blocks': must be a power of two in [1, 256], got 3"},
      {"particles.count=2147483649",
       "scene key 'particles.count': must be auto or in [0, 2147483648], got 2147483649"},
      {"particles.color=[0.5,-0.1,0]", "scene key 'particles.color': entries must be in [0, 1]"},
      {"volume.dims=[16,2.5,16]", "scene key 'volume.dims': entries must be integers in [2, 2^20]"},
      {"limits.memory_mib=1e13", "scene key 'limits.memory_mib': must be auto or in (0, 1e12] MiB"},
      {"particles.step=.inf", "scene key 'particles.step': must be a finite number > 0"},
      {"particles.slice_spacing=1e-9",
       "scene key 'particles.slice_spacing': must be in [0.05, 1] (units of h), got 1e-9"},
      {"camera.fov=180", "scene key 'camera.fov': must be in (0, 180) degrees"},
      {"particles.threshold=1", "scene key 'particles.threshold': must be in (0, 1)"},
  };
  // (The pair by name, not a structured binding: clang 14, the sanitizer build's compiler, cannot
  // capture a binding in a lambda.)
  for (const auto& c : cases)
    EXPECT_EQ(inputErrorOf([&] { loadScene("", {c.first}); }), c.second) << c.first;
}

// Values each check of a key refuses (its bounds from outside, a list's neighbours, a non-integer
// or a non-power of two inside the interval); `integral`: the key is read as an integer.
std::vector<double> refusedBy(const Allowed& a, bool integral) {
  if (a.isList()) return {a.list().back() + 1, a.list().front() + 1};
  auto beyond = [&](double bound, double dir) {
    return integral ? bound + dir : bound + dir * (bound == 0 ? 0.5 : std::abs(bound) * 0.5);
  };
  std::vector<double> out;
  if (std::isfinite(a.lo())) out.push_back(a.loOpen() ? a.lo() : beyond(a.lo(), -1));
  if (std::isfinite(a.hi()))
    out.push_back(a.hiOpen() ? a.hi() : beyond(a.hi(), 1));
  else if (a.hiOpen())
    out.push_back(INFINITY);
  if (std::isfinite(a.lo()) && std::isfinite(a.hi())) {
    const double mid = std::floor((a.lo() + a.hi()) / 2) + 1;
    out.push_back(integral ? mid : mid + 0.25);
  }
  return out;
}

std::string yamlNumber(double v) {
  if (std::isinf(v)) return v > 0 ? ".inf" : "-.inf";
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

std::string shortNumber(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

// The first of `checks` that refuses `value` (entries, or the length, of a list), with its
// message; nullptr if none does.
const Check* firstRefusing(const std::vector<Check>& checks, const std::vector<double>& value,
                           std::string& shown) {
  for (const Check& c : checks) {
    if (c.of_length) {
      const double length =
          std::sqrt(value[0] * value[0] + value[1] * value[1] + value[2] * value[2]);
      if (!c.allowed.admits(length)) return shown = shortNumber(length), &c;
    } else {
      for (double v : value)
        if (!c.allowed.admits(v)) return shown = shortNumber(v), &c;
    }
  }
  return nullptr;
}

// A value one of a key's checks refuses fails with the message of the first of the key's checks
// that refuses it, worded by the row: the parser applies each row's checks, in the row's order.
TEST(SceneKeys, RangeErrorsAreTheTablesMessages) {
  int tested = 0;
  for (const SceneKey& k : sceneKeys()) {
    std::visit(
        [&](const auto& type) {
          using Type = std::decay_t<decltype(type)>;
          if constexpr (std::is_same_v<Type, Vector<glm::dvec3>> ||
                        std::is_same_v<Type, Vector<glm::ivec3>>) {
            // One entry refused, the others the default's or 1 (the length: a vector along x).
            const YAML::Node d = YAML::Load(k.default_yaml);
            auto other = [&](int i) { return d.IsSequence() ? d[i].as<double>() : 1.0; };
            for (const Check& c : type.checks)
              for (double v : refusedBy(c.allowed, false)) {
                std::vector<double> value = {v, other(1), other(2)};
                if (c.of_length) value = {v, 0, 0};
                std::string shown;
                const Check* refusing = firstRefusing(type.checks, value, shown);
                if (!refusing) continue;
                const std::string set = std::string(k.path) + "=[" + yamlNumber(value[0]) + ", " +
                                        yamlNumber(value[1]) + ", " + yamlNumber(value[2]) + "]";
                EXPECT_EQ(inputErrorOf([&] { loadScene("", {set}); }),
                          refusing->error(k.path, shown, ""))
                    << set;
                ++tested;
              }
          } else if constexpr (requires { type.checks; } && !std::is_same_v<Type, Structured>) {
            using T = std::decay_t<decltype(type.field(std::declval<Scene&>()))>;
            constexpr bool integral = std::is_integral_v<T>;
            for (const Check& c : type.checks)
              for (double v : refusedBy(c.allowed, integral)) {
                std::string shown;
                const Check* refusing = firstRefusing(type.checks, {v, v, v}, shown);
                if (!refusing || !refusing->says) continue;  // image size: its own message
                const std::string text = integral ? std::to_string((long long)v) : yamlNumber(v);
                if (integral) shown = text;
                const std::string set = std::string(k.path) + "=" + text;
                EXPECT_EQ(inputErrorOf([&] { loadScene("", {set}); }),
                          refusing->error(k.path, shown, text))
                    << set;
                ++tested;
              }
          }
        },
        k.type);
  }
  EXPECT_GE(tested, 100);
}

TEST(SceneKeys, AllowedValues) {
  const Allowed half_open("in (0, 1]");
  EXPECT_FALSE(half_open.admits(0));
  EXPECT_TRUE(half_open.admits(1e-300));
  EXPECT_TRUE(half_open.admits(1));
  EXPECT_FALSE(half_open.admits(NAN));
  EXPECT_EQ(half_open.range(), "(0, 1]");
  const Allowed fraction("in [1/64, 8]");
  EXPECT_TRUE(fraction.admits(1.0 / 64));
  EXPECT_FALSE(fraction.admits(0.0156));
  EXPECT_EQ(fraction.describe(), "in [1/64, 8]");
  const Allowed integers("integers in [2, 2^20]");
  EXPECT_TRUE(integers.admits(1 << 20));
  EXPECT_FALSE(integers.admits((1 << 20) + 1));
  EXPECT_FALSE(integers.admits(2.5));
  const Allowed powers("a power of two in [1, 256]");
  for (double v : {1, 2, 64, 256}) EXPECT_TRUE(powers.admits(v)) << v;
  for (double v : {0, 3, 96, 512}) EXPECT_FALSE(powers.admits(v)) << v;
  EXPECT_EQ(powers.describe(), "power of two in [1, 256]");
  const Allowed listed("4 or 8");
  EXPECT_TRUE(listed.admits(4) && listed.admits(8));
  EXPECT_FALSE(listed.admits(6));
  EXPECT_TRUE(Allowed("> 0").admits(INFINITY));                   // a half-line holds +inf ...
  EXPECT_FALSE(Allowed("a finite number > 0").admits(INFINITY));  // ... unless it says finite
  EXPECT_FALSE(Allowed(">= 1").admits(0.5));
  EXPECT_EQ(Allowed("a finite number > 0").within(Allowed("in [1e-12, 1e18]")).describe(),
            "in [1e-12, 1e18]");
  for (const char* bad : {"in [1, 0]", "in [0 1]", "4", "between 0 and 1", "in [0, 1]x", ">= x"})
    EXPECT_THROW(Allowed{bad}, std::logic_error) << bad;
  // The table's float limits are common/box.h's.
  const Allowed& length = sceneKeyChecks("volume.spacing").front().allowed;
  EXPECT_EQ(length.lo(), kMinLength);
  EXPECT_EQ(length.hi(), kMaxCoordinate);
  const Allowed& coordinate = sceneKeyChecks("camera.position").front().allowed;
  EXPECT_EQ(coordinate.lo(), -kMaxCoordinate);
  EXPECT_EQ(coordinate.hi(), kMaxCoordinate);
}

// Every row's messages fill in (no unknown {name}), and the docs say what every key takes.
TEST(SceneKeys, EveryRowRendersItsMessagesAndValues) {
  for (const SceneKey& k : sceneKeys()) {
    for (const Check& c : sceneKeyChecks(k.path))
      EXPECT_NO_THROW(c.error(k.path, "1", "1")) << k.path;
    std::visit(
        [&](const auto& type) {
          if constexpr (requires {
                          type.names;
                          type.says;
                        })
            EXPECT_NO_THROW(choiceError(k.path, type.says, {"a", "b"}, "c")) << k.path;
        },
        k.type);
    const std::string values = sceneKeyValues(k);
    EXPECT_FALSE(values.empty()) << k.path;
    EXPECT_NE(sceneKeysMarkdown().find("| `" + std::string(k.path) + "` | `" + k.default_yaml +
                                       "` | " + values + " | "),
              std::string::npos)
        << k.path;
  }
  EXPECT_EQ(sceneKeyValues(sceneKey("render.ert_threshold")), "number in (0, 1]");
  EXPECT_EQ(sceneKeyValues(sceneKey("particles.spacing")), "number in [1e-12, 1e18]");
  EXPECT_EQ(sceneKeyValues(sceneKey("bricks.per_axis")), "`auto` or integer in [1, 64]");
  EXPECT_EQ(sceneKeyValues(sceneKey("particles.samples_per_pass")), "4 or 8");
  EXPECT_EQ(sceneKeyValues(sceneKey("adaptive.blocks")), "power of two in [1, 256]");
  EXPECT_EQ(sceneKeyValues(sceneKey("camera.up")), "3 numbers in [-1e18, 1e18], length >= 1e-12");
  EXPECT_EQ(sceneKeyValues(sceneKey("render.method")), "`slicing` or `raycast`");
  EXPECT_EQ(sceneKeyValues(sceneKey("transfer.preintegrated")), "`auto`, `true` or `false`");
}

}  // namespace
}  // namespace sortlast
