// The in-situ library's CPU parts: the actions file (insitu/actions.h), triggers
// (insitu/trigger.h), output names (insitu/output_names.h) and the Cinema database
// (insitu/cinema.h).
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "insitu/actions.h"
#include "insitu/cinema.h"
#include "insitu/output_names.h"
#include "insitu/trigger.h"
#include "tests/unit/input_error_of.h"

namespace sortlast {
namespace {

namespace fs = std::filesystem;

// A private temporary directory, removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = fs::temp_directory_path() / ("sortlast_insitu_test_" + std::to_string(::getpid()) +
                                         "_" + std::to_string(counter++));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// ---- the actions file ----

const char* kGoodActions = R"(
on_error: abort
serve: 127.0.0.1:8090
renders:
  - name: volume
    output: images/v_{step}.png
    trigger: {every: 10}
    scene:
      image: {width: 256, height: 128}
      camera:
        position: [0, 0, 400]
        orbit: {frames: 4}
      transfer.points: [[0, 0, 0, 0, 0], [1, 1, 0.5, 0.25, 0.75]]
      render: {method: raycast}
  - name: splash-2
    output: out/{step}/p.exr
    trigger: {when: energy, crosses: 0.5, every: 100}
  - name: db
    cinema:
      directory: cinema/db
      phi: [0, 90, 180, 270]
      theta: [-30, 0, 30]
)";

bool hasOverride(const RenderAction& r, const std::string& o) {
  for (const std::string& x : r.overrides)
    if (x == o) return true;
  return false;
}

TEST(InsituActions, GoodFileParses) {
  Actions a = parseActions(kGoodActions, "good.yaml");
  EXPECT_TRUE(a.abort_on_error);
  EXPECT_EQ(a.serve, "127.0.0.1:8090");
  EXPECT_EQ(a.serve_token, "");
  ASSERT_EQ(a.renders.size(), 3u);

  const RenderAction& v = a.renders[0];
  EXPECT_EQ(v.name, "volume");
  EXPECT_EQ(v.output, "images/v_{step}.png");
  EXPECT_EQ(v.trigger.every, 10);
  EXPECT_TRUE(v.trigger.when.empty());
  EXPECT_FALSE(v.trigger.crosses.has_value());
  EXPECT_FALSE(v.cinema.has_value());
  EXPECT_EQ(v.overrides.size(), 6u);
  EXPECT_TRUE(hasOverride(v, "image.width=256")) << ::testing::PrintToString(v.overrides);
  EXPECT_TRUE(hasOverride(v, "camera.orbit.frames=4"));
  EXPECT_TRUE(hasOverride(v, "render.method=raycast"));

  const RenderAction& p = a.renders[1];
  EXPECT_EQ(p.name, "splash-2");
  EXPECT_EQ(p.trigger.every, 100);
  EXPECT_EQ(p.trigger.when, "energy");
  ASSERT_TRUE(p.trigger.crosses.has_value());
  EXPECT_DOUBLE_EQ(*p.trigger.crosses, 0.5);
  EXPECT_TRUE(p.overrides.empty());

  const RenderAction& c = a.renders[2];
  EXPECT_TRUE(c.output.empty());
  EXPECT_EQ(c.trigger.every, 1);  // no trigger: every step
  ASSERT_TRUE(c.cinema.has_value());
  EXPECT_EQ(c.cinema->directory, "cinema/db");
  EXPECT_EQ(c.cinema->phi, (std::vector<double>{0, 90, 180, 270}));
  EXPECT_EQ(c.cinema->theta, (std::vector<double>{-30, 0, 30}));
}

// The overrides are what a session request carries: the scene parser must read them back as the
// values the actions file gave.
TEST(InsituActions, OverridesReadBackByTheSceneParser) {
  Actions a = parseActions(kGoodActions, "good.yaml");
  Scene s = parseScene(SceneText{}, a.renders[0].overrides);
  EXPECT_EQ(s.camera.width, 256);
  EXPECT_EQ(s.camera.height, 128);
  EXPECT_FALSE(s.camera_auto);
  EXPECT_EQ(s.camera.position, glm::dvec3(0, 0, 400));
  EXPECT_EQ(s.orbit.frames, 4);
  EXPECT_EQ(s.render.method, RenderMethod::kRaycast);
  ASSERT_EQ(s.transfer.points.size(), 2u);
  EXPECT_DOUBLE_EQ(s.transfer.points[1].b, 0.25);
  for (const std::string& o : a.renders[0].overrides)
    EXPECT_TRUE(isFrameKey(o.substr(0, o.find('=')))) << o;
}

TEST(InsituActions, DefaultsAndCounts) {
  Actions a = parseActions(R"(
renders:
  - name: a
    output: a_{step}.png
  - name: b
    cinema: {directory: db, phi: {count: 4}, theta: {count: 3}}
  - name: c
    cinema: {directory: db2}
)",
                           "d.yaml");
  EXPECT_FALSE(a.abort_on_error);
  EXPECT_TRUE(a.serve.empty());
  EXPECT_EQ(a.renders[0].trigger.every, 1);
  EXPECT_EQ(a.renders[1].cinema->phi, (std::vector<double>{0, 90, 180, 270}));
  EXPECT_EQ(a.renders[1].cinema->theta, (std::vector<double>{-45, 0, 45}));
  EXPECT_EQ(a.renders[2].cinema->phi.size(), 8u);
  EXPECT_EQ(a.renders[2].cinema->theta, (std::vector<double>{0}));
  // A remote address with a token is fine.
  Actions r = parseActions(
      "serve: 0.0.0.0:9000\nserve_token: s3cret\nrenders: [{name: a, output: "
      "'a_{step}.png'}]\n",
      "r.yaml");
  EXPECT_EQ(r.serve_token, "s3cret");
}

struct BadCase {
  const char* what;
  std::string yaml;
  std::vector<std::string> expected;  // each must appear in the message
};

// One render around a fragment of its map (the fragment indented like `name:`).
std::string oneRender(const std::string& fragment) { return "renders:\n  - name: v\n" + fragment; }

// A simulation on GPU nodes: the session's backend and device (docs/cluster.md).
TEST(InsituActions, BackendAndDeviceAreTheSessions) {
  Actions a = parseActions("backend: egl\ndevice: auto\n" + oneRender("    output: v_{step}.png\n"), "a.yaml");
  EXPECT_EQ(a.session_overrides, (std::vector<std::string>{"render.backend=egl", "render.device=auto"}));
  EXPECT_TRUE(parseActions(oneRender("    output: v_{step}.png\n"), "a.yaml").session_overrides.empty());
}

TEST(InsituActions, BadActionsNameTheKeyAndTheFile) {
  const std::vector<BadCase> cases = {
      {"invalid YAML", "renders: [", {"bad.yaml", "not valid YAML"}},
      {"not a map", "- a\n- b\n", {"bad.yaml", "renders"}},
      {"unknown top key",
       "colour: red\n" + oneRender("    output: v_{step}.png\n"),
       {"bad.yaml:1:", "key 'colour'", "unknown"}},
      {"missing renders", "on_error: abort\n", {"key 'renders'", "required"}},
      {"empty renders", "renders: []\n", {"key 'renders'"}},
      {"bad on_error",
       "on_error: ignore\n" + oneRender("    output: v_{step}.png\n"),
       {"key 'on_error'", "ignore"}},
      {"bad backend",
       "backend: vulkan\n" + oneRender("    output: v_{step}.png\n"),
       {"key 'backend'", "vulkan"}},
      {"a device without the EGL backend",
       "device: 1\n" + oneRender("    output: v_{step}.png\n"),
       {"key 'device'", "render.backend is osmesa"}},
      {"unknown render key",
       oneRender("    outptu: v_{step}.png\n"),
       {"bad.yaml:3:", "render 'v'", "key 'outptu'"}},
      {"missing name", "renders:\n  - output: v_{step}.png\n", {"renders[0]", "key 'name'"}},
      {"bad name",
       "renders:\n  - name: my render\n    output: v_{step}.png\n",
       {"key 'name'", "my render"}},
      {"duplicate name",
       "renders:\n  - name: v\n    output: a_{step}.png\n  - name: v\n    output: b_{step}.png\n",
       {"bad.yaml:4:", "render 'v'", "key 'name'"}},
      {"duplicate key",
       oneRender("    output: v_{step}.png\n    output: w_{step}.png\n"),
       {"key 'output'", "twice"}},
      {"neither output nor cinema", oneRender("    trigger: {every: 2}\n"), {"key 'output'"}},
      {"output without step",
       oneRender("    output: v.png\n"),
       {"bad.yaml:3:", "key 'output'", "{step}"}},
      {"output bad extension", oneRender("    output: v_{step}.jpg\n"), {"key 'output'", ".jpg"}},
      {"output unknown placeholder",
       oneRender("    output: v_{step}_{frame}.png\n"),
       {"key 'output'", "placeholder"}},
      {"same output twice",
       "renders:\n  - name: a\n    output: x_{step}.png\n  - name: b\n    output: x_{step}.png\n",
       {"render 'b'", "key 'output'", "render 'a'"}},
      {"every 0",
       oneRender("    output: v_{step}.png\n    trigger: {every: 0}\n"),
       {"bad.yaml:4:", "key 'trigger.every'", ">= 1"}},
      {"every negative",
       oneRender("    output: v_{step}.png\n    trigger: {every: -3}\n"),
       {"key 'trigger.every'"}},
      {"every fractional",
       oneRender("    output: v_{step}.png\n    trigger: {every: 2.5}\n"),
       {"key 'trigger.every'", "integer"}},
      {"crosses without when",
       oneRender("    output: v_{step}.png\n    trigger: {crosses: 1}\n"),
       {"key 'trigger.crosses'", "when"}},
      {"when without crosses",
       oneRender("    output: v_{step}.png\n    trigger: {when: energy}\n"),
       {"key 'trigger.when'", "crosses"}},
      {"crosses not a number",
       oneRender("    output: v_{step}.png\n    trigger: {when: e, crosses: high}\n"),
       {"key 'trigger.crosses'", "number"}},
      {"empty trigger",
       oneRender("    output: v_{step}.png\n    trigger: {}\n"),
       {"key 'trigger'"}},
      {"unknown trigger key",
       oneRender("    output: v_{step}.png\n    trigger: {above: 1}\n"),
       {"key 'trigger.above'"}},
      {"data key in scene",
       oneRender("    output: v_{step}.png\n    scene:\n      volume: {file: a.raw}\n"),
       {"bad.yaml:5:", "key 'scene.volume.file'", "simulation"}},
      {"layout key in scene",
       oneRender("    output: v_{step}.png\n    scene: {bricks.per_axis: 4}\n"),
       {"key 'scene.bricks.per_axis'", "simulation"}},
      {"time step in scene",
       oneRender("    output: v_{step}.png\n    scene: {time: {step: 3}}\n"),
       {"key 'scene.time.step'", "simulation"}},
      {"unknown scene key",
       oneRender("    output: v_{step}.png\n    scene: {image: {widht: 3}}\n"),
       {"key 'scene.image.widht'", "unknown"}},
      {"scene prefix not a map",
       oneRender("    output: v_{step}.png\n    scene: {image: 64}\n"),
       {"key 'scene.image'", "map"}},
      {"bad scene value",
       oneRender("    output: v_{step}.png\n    scene: {image: {width: 0}}\n"),
       {"render 'v'", "key 'scene'", "image.width"}},
      {"bad scene value type",
       oneRender("    output: v_{step}.png\n    scene: {render: {method: fast}}\n"),
       {"render 'v'", "render.method", "fast"}},
      {"unknown colour map",
       oneRender("    output: v_{step}.png\n    scene: {transfer: {colormap: virdis}}\n"),
       {"render 'v'", "transfer.colormap", "unknown colour map 'virdis'"}},
      {"cinema without directory",
       oneRender("    cinema: {phi: [0]}\n"),
       {"key 'cinema.directory'"}},
      {"cinema theta 90",
       oneRender("    cinema: {directory: db, theta: [0, 90]}\n"),
       {"bad.yaml:3:", "key 'cinema.theta'", "(-90, 90)"}},
      {"cinema phi 360",
       oneRender("    cinema: {directory: db, phi: [0, 360]}\n"),
       {"key 'cinema.phi'", "[0, 360)"}},
      {"cinema phi negative",
       oneRender("    cinema: {directory: db, phi: [-10]}\n"),
       {"key 'cinema.phi'"}},
      {"cinema phi twice",
       oneRender("    cinema: {directory: db, phi: [10, 10]}\n"),
       {"key 'cinema.phi'", "twice"}},
      {"cinema count 0",
       oneRender("    cinema: {directory: db, phi: {count: 0}}\n"),
       {"key 'cinema.phi.count'"}},
      {"cinema unknown key",
       oneRender("    cinema: {directory: db, psi: [0]}\n"),
       {"key 'cinema.psi'"}},
      {"cinema with orbit",
       oneRender("    cinema: {directory: db}\n    scene: {camera: {orbit: {frames: 8}}}\n"),
       {"key 'cinema'", "orbit"}},
      {"cinema directory twice",
       "renders:\n  - name: a\n    cinema: {directory: db}\n  - name: b\n    cinema: {directory: "
       "./db}\n",
       {"render 'b'", "key 'cinema.directory'", "render 'a'"}},
      {"serve bad port",
       "serve: 127.0.0.1:http\n" + oneRender("    output: v_{step}.png\n"),
       {"bad.yaml:1:", "key 'serve'"}},
      {"serve remote without token",
       "serve: 0.0.0.0:8080\n" + oneRender("    output: v_{step}.png\n"),
       {"key 'serve_token'", "0.0.0.0"}},
      {"token without serve",
       "serve_token: x\n" + oneRender("    output: v_{step}.png\n"),
       {"key 'serve_token'", "serve"}},
  };
  for (const BadCase& c : cases) {
    std::string msg = inputErrorOf([&] { parseActions(c.yaml, "bad.yaml"); });
    EXPECT_EQ(msg.rfind("bad.yaml", 0), 0u) << c.what << ": " << msg;
    for (const std::string& e : c.expected)
      EXPECT_NE(msg.find(e), std::string::npos) << c.what << ": '" << e << "' not in: " << msg;
  }
}

// ---- triggers ----

RenderAction renderWith(Trigger t, const std::string& name = "r") {
  RenderAction r;
  r.name = name;
  r.trigger = std::move(t);
  return r;
}

std::vector<long long> firedSteps(TriggerState& state, const RenderAction& r,
                                  const std::vector<double>& values) {
  std::vector<long long> fired;
  for (size_t i = 0; i < values.size(); ++i)
    if (state.fires(r, (long long)i, {{"q", values[i]}})) fired.push_back((long long)i);
  return fired;
}

TEST(InsituTrigger, EveryThreeSteps) {
  TriggerState state;
  RenderAction r = renderWith({3, "", std::nullopt});
  std::vector<long long> fired;
  for (long long step = 0; step <= 10; ++step)
    if (state.fires(r, step, {})) fired.push_back(step);
  EXPECT_EQ(fired, (std::vector<long long>{0, 3, 6, 9}));
}

TEST(InsituTrigger, NoTriggerFiresEveryStep) {
  TriggerState state;
  for (const RenderAction& r : {renderWith({}), renderWith({1, "", std::nullopt})})
    for (long long step = 5; step < 9; ++step) EXPECT_TRUE(state.fires(r, step, {}));
}

TEST(InsituTrigger, CrossesUpAndDown) {
  TriggerState state;
  RenderAction r = renderWith({0, "q", 0.5});
  // 0: the first call only records; 2: down through 0.5; 4: up; 6: down onto 0.5 exactly;
  // 7: stays there; 8: leaves it downwards, which is no new crossing (step 6 reached it).
  std::vector<double> q = {0.7, 0.6, 0.4, 0.45, 0.55, 0.9, 0.5, 0.5, 0.2};
  EXPECT_EQ(firedSteps(state, r, q), (std::vector<long long>{2, 4, 6}));
}

TEST(InsituTrigger, CrossesUpOntoTheValue) {
  TriggerState state;
  RenderAction r = renderWith({0, "q", 0.5});
  EXPECT_EQ(firedSteps(state, r, {0.1, 0.5, 0.5, 0.6, 0.5, 0.4}), (std::vector<long long>{1, 4}));
}

TEST(InsituTrigger, EveryOrCrossingAndStatePerRender) {
  TriggerState state;
  RenderAction both = renderWith({4, "q", 0.0}, "both");
  RenderAction cross = renderWith({0, "q", 0.0}, "cross");
  std::vector<double> q = {-1, -1, 1, 1, 1, -1, -1, -1, -1};
  std::vector<long long> fired_both, fired_cross;
  for (size_t i = 0; i < q.size(); ++i) {
    if (state.fires(both, (long long)i, {{"q", q[i]}})) fired_both.push_back((long long)i);
    if (state.fires(cross, (long long)i, {{"q", q[i]}})) fired_cross.push_back((long long)i);
  }
  EXPECT_EQ(fired_both, (std::vector<long long>{0, 2, 4, 5, 8}));
  EXPECT_EQ(fired_cross, (std::vector<long long>{2, 5}));
}

TEST(InsituTrigger, MissingOrNanQuantityIsNamed) {
  TriggerState state;
  RenderAction r = renderWith({0, "energy", 1.0}, "vol");
  EXPECT_FALSE(state.fires(r, 0, {{"energy", 0.0}}));
  std::string msg = inputErrorOf([&] { state.fires(r, 1, {{"mass", 2.0}}); });
  EXPECT_NE(msg.find("'energy'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("render 'vol'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("mass"), std::string::npos) << msg;  // what was published instead
  msg = inputErrorOf([&] { state.fires(r, 2, {{"energy", std::nan("")}}); });
  EXPECT_NE(msg.find("'energy'"), std::string::npos) << msg;
  // A failed call leaves the remembered value alone: 0 -> 2 still crosses 1.
  EXPECT_TRUE(state.fires(r, 3, {{"energy", 2.0}}));
}

// ---- output names ----

TEST(InsituOutputName, StepAndFrame) {
  EXPECT_EQ(outputName("images/v_{step}.png", 20, 0, 1), "images/v_000020.png");
  EXPECT_EQ(outputName("images/v_{step}.png", 1234567, 0, 1), "images/v_1234567.png");
  EXPECT_EQ(outputName("images/v_{step}.png", 20, 2, 8), "images/v_000020_0002.png");
  EXPECT_EQ(outputName("s{step}/v_{step}.exr", 7, 0, 1), "s000007/v_000007.exr");
  EXPECT_EQ(stepLabel(10), "000010");
}

TEST(InsituOutputName, CreatesParentDirectories) {
  TempDir tmp;
  std::string file = (tmp.path() / "a" / "b" / "v_000001.png").string();
  createParentDirectories(file);
  EXPECT_TRUE(fs::is_directory(tmp.path() / "a" / "b"));
  createParentDirectories(file);  // again: nothing to do
  createParentDirectories("plain.png");
  // A file where a folder should be.
  std::ofstream(tmp.path() / "f") << "x";
  std::string msg =
      inputErrorOf([&] { createParentDirectories((tmp.path() / "f" / "g.png").string()); });
  EXPECT_NE(msg.find("folder"), std::string::npos) << msg;
}

// ---- Cinema ----

TEST(InsituCinema, PositionsKeepTheDistance) {
  const glm::dvec3 look_at(1, 1, 1), base(3, 4, 5), up(0, 2, 0);
  const double r = glm::length(base - look_at);
  for (double phi : {0.0, 45.0, 90.0, 200.0, 359.0})
    for (double theta : {-89.0, -30.0, 0.0, 30.0, 89.0}) {
      glm::dvec3 p = cinemaPosition(look_at, base, up, phi, theta);
      EXPECT_NEAR(glm::length(p - look_at), r, 1e-12 * r) << phi << " " << theta;
      // Theta is the elevation above the plane perpendicular to up.
      EXPECT_NEAR((p - look_at).y / r, std::sin(theta * std::numbers::pi / 180.0), 1e-12)
          << phi << " " << theta;
    }
}

TEST(InsituCinema, PhiZeroThetaZeroIsTheBaseDirectionProjected) {
  const glm::dvec3 look_at(1, 1, 1), base(3, 4, 5), up(0, 1, 0);
  const double r = glm::length(base - look_at);
  glm::dvec3 p = cinemaPosition(look_at, base, up, 0.0, 0.0);
  glm::dvec3 expected = look_at + r * glm::normalize(glm::dvec3(2, 0, 4));
  EXPECT_NEAR(glm::length(p - expected), 0.0, 1e-12);
  // Phi turns right-handed around up: from +z a quarter turn around +y goes to +x.
  glm::dvec3 q = cinemaPosition(glm::dvec3(0), glm::dvec3(0, 0, 5), up, 90.0, 0.0);
  EXPECT_NEAR(glm::length(q - glm::dvec3(5, 0, 0)), 0.0, 1e-12);
  // A base camera straight above look_at still gives views at its distance.
  glm::dvec3 s = cinemaPosition(glm::dvec3(0), glm::dvec3(0, 7, 0), up, 30.0, 10.0);
  EXPECT_NEAR(glm::length(s), 7.0, 1e-12);
}

TEST(InsituCinema, PolesAndDegenerateCamerasAreRejected) {
  const glm::dvec3 o(0), base(0, 0, 5), up(0, 1, 0);
  EXPECT_NE(inputErrorOf([&] { cinemaPosition(o, base, up, 0, 90); }).find("theta"),
            std::string::npos);
  EXPECT_NE(inputErrorOf([&] { cinemaPosition(o, base, up, 0, -90); }).find("theta"),
            std::string::npos);
  inputErrorOf([&] { cinemaPosition(o, o, up, 0, 0); });
  inputErrorOf([&] { cinemaPosition(o, base, glm::dvec3(0), 0, 0); });
}

TEST(InsituCinema, ImagePaths) {
  CinemaIndex index({"db", {0, 22.5}, {-30, 0}});
  EXPECT_EQ(index.imagePath(10, 0, -30), "000010/0_-30.png");
  EXPECT_EQ(index.imagePath(10, 22.5, 0), "000010/22.5_0.png");
  EXPECT_EQ(index.imagePath(3, -0.0, -0.0), "000003/0_0.png");
}

TEST(InsituCinema, InfoJsonListsExactlyTheImagesAdded) {
  TempDir tmp;
  CinemaSpec spec{(tmp.path() / "db").string(), {0, 90, 22.5}, {-30, 0}};
  CinemaIndex index(spec);
  auto all = [&](long long step) {
    std::vector<std::string> images;
    for (double phi : spec.phi)
      for (double theta : spec.theta) images.push_back(index.imagePath(step, phi, theta));
    return images;
  };
  index.write();  // before any step: an empty index
  auto read = [&] {
    std::ifstream in(tmp.path() / "db" / "info.json");
    return nlohmann::json::parse(in);
  };
  EXPECT_TRUE(read()["steps"].empty());
  EXPECT_TRUE(read()["parameter_list"]["time"]["values"].empty());

  index.addStep(20, 2.0, all(20));
  index.addStep(10, 1.0, {"stale.png"});
  index.addStep(10, 1.5, all(10));  // the same step again replaces its entry
  index.write();
  nlohmann::json j = read();
  EXPECT_EQ(j["type"], "simple");
  EXPECT_EQ(j["version"], "1.1");
  EXPECT_EQ(j["metadata"]["type"], "parametric-image-stack");
  EXPECT_EQ(j["name_pattern"], "{time}/{phi}_{theta}.png");
  const nlohmann::json& params = j["parameter_list"];
  EXPECT_EQ(params["time"]["values"], nlohmann::json({"000010", "000020"}));
  EXPECT_EQ(params["time"]["default"], "000010");
  EXPECT_EQ(params["phi"]["values"].dump(), "[0,90,22.5]");  // whole angles as integers
  EXPECT_EQ(params["theta"]["values"].dump(), "[-30,0]");
  EXPECT_EQ(params["theta"]["default"], 0);
  ASSERT_EQ(j["steps"].size(), 2u);
  EXPECT_EQ(j["steps"][0]["step"], 10);
  EXPECT_EQ(j["steps"][0]["time"], 1.5);
  EXPECT_EQ(j["steps"][0]["images"].get<std::vector<std::string>>(), all(10));
  EXPECT_EQ(j["steps"][1]["images"].get<std::vector<std::string>>(), all(20));
  // Each listed image is the name pattern filled with the listed parameter values.
  for (const auto& st : j["steps"]) {
    std::vector<std::string> from_pattern;
    for (const auto& phi : params["phi"]["values"])
      for (const auto& theta : params["theta"]["values"])
        from_pattern.push_back(stepLabel(st["step"].get<long long>()) + "/" + phi.dump() + "_" +
                               theta.dump() + ".png");
    EXPECT_EQ(st["images"].get<std::vector<std::string>>(), from_pattern);
  }
  EXPECT_FALSE(fs::exists(tmp.path() / "db" / "info.json.tmp"));
}

}  // namespace
}  // namespace sortlast
