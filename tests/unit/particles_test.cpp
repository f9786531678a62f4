// Particles (io/particles.h): the file readers, the procedural sets, particlesNear, and the
// particles.* scene keys (with the volume made optional).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <unistd.h>
#include <vector>

#include "common/build_features.h"
#include "tests/unit/input_error_of.h"
#include "common/error.h"
#include "io/particles.h"
#include "scene/scene.h"

namespace sortlast {
namespace {

namespace fs = std::filesystem;

class ParticleFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    dir_ = fs::temp_directory_path() / ("sortlast_particles_test_" + std::to_string(::getpid()) +
                                        "_" + std::to_string(counter++));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string write(const std::string& name, const std::string& bytes) {
    fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p.string();
  }
  // Float32 x,y,z triples in the given byte order.
  static std::string floats(const std::vector<float>& v, bool big_endian = false) {
    std::string out;
    for (float f : v) {
      char b[4];
      std::memcpy(b, &f, 4);
      if (big_endian == (std::endian::native == std::endian::little)) std::reverse(b, b + 4);
      out.append(b, 4);
    }
    return out;
  }
  ParticleSet load(const std::string& file, const std::string& format = "auto",
                   long long count = -1) {
    ParticleDesc d;
    d.file = file;
    d.format = format;
    d.count = count;
    return loadParticles(d);
  }
  fs::path dir_;
};


bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

const std::vector<glm::vec3> kThree = {{0.f, 1.f, 2.f}, {-3.5f, 4.25f, 5.f}, {6.f, -7.f, 1e-3f}};

TEST_F(ParticleFiles, RawLittleEndianTriples) {
  std::string f = write("p.raw", floats({0, 1, 2, -3.5f, 4.25f, 5, 6, -7, 1e-3f}));
  EXPECT_EQ(load(f).positions, kThree);
  EXPECT_EQ(load(f, "raw", 3).positions, kThree);
  // Any extension but .vtk/.vtp/.vtu/.csv is raw.
  std::string g = write("p.bin", floats({1, 2, 3}));
  EXPECT_EQ(load(g).positions, std::vector<glm::vec3>{glm::vec3(1, 2, 3)});
}

TEST_F(ParticleFiles, RawSizeErrors) {
  std::string f = write("p.raw", floats({0, 1, 2, 3, 4, 5}) + "x");
  std::string msg = inputErrorOf([&] { load(f); });
  EXPECT_TRUE(has(msg, "25 bytes") && has(msg, "multiple of 12") && has(msg, "p.raw")) << msg;
  std::string g = write("q.raw", floats({0, 1, 2, 3, 4, 5}));
  msg = inputErrorOf([&] { load(g, "auto", 3); });
  EXPECT_TRUE(has(msg, "particles.count") && has(msg, "24 bytes") && has(msg, "36")) << msg;
  msg = inputErrorOf([&] { load((dir_ / "missing.raw").string()); });
  EXPECT_TRUE(has(msg, "missing.raw") && has(msg, "no such file")) << msg;
}

TEST_F(ParticleFiles, EmptyFileIsAnEmptySet) {
  ParticleSet s = load(write("empty.raw", ""));
  EXPECT_TRUE(s.positions.empty());
  Box3 b = s.bounds();
  EXPECT_GT(b.lo.x, b.hi.x);
  EXPECT_GT(b.lo.y, b.hi.y);
  EXPECT_GT(b.lo.z, b.hi.z);
  EXPECT_TRUE(load(write("empty.csv", "x,y,z\n# nothing\n")).positions.empty());
  EXPECT_TRUE(load(write("empty.raw", ""), "raw", 0).positions.empty());
}

TEST_F(ParticleFiles, NonFinitePositionNamesItsIndex) {
  float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  std::string msg = inputErrorOf([&] { load(write("n.raw", floats({0, 0, 0, 1, nan, 1}))); });
  EXPECT_TRUE(has(msg, "NaN") && has(msg, "particle 1")) << msg;
  msg = inputErrorOf([&] { load(write("i.raw", floats({0, 0, 0, 1, 1, 1, 2, 2, inf}))); });
  EXPECT_TRUE(has(msg, "infinite") && has(msg, "particle 2")) << msg;
  msg = inputErrorOf([&] { load(write("n.csv", "1,2,3\n4,nan,6\n")); });
  EXPECT_TRUE(has(msg, "line 2") && has(msg, "particle 1")) << msg;
  msg = inputErrorOf([&] { load(write("big.csv", "1,2,1e300\n")); });  // overflows float32
  EXPECT_TRUE(has(msg, "line 1")) << msg;
}

TEST_F(ParticleFiles, Csv) {
  std::string f = write("p.csv",
                        "# particles\n"
                        "x, y, z, id\n"
                        "\n"
                        "0,1,2,17\r\n"
                        "  -3.5 , 4.25,5   # trailing comment\n"
                        "6,-7,+1e-3\n");
  EXPECT_EQ(load(f).positions, kThree);
  // No header; format forced on another extension.
  std::string g = write("p.txt", "1,2,3\n");
  EXPECT_EQ(load(g, "csv").positions, std::vector<glm::vec3>{glm::vec3(1, 2, 3)});
  std::string msg = inputErrorOf([&] { load(g, "auto", 2); });  // raw by extension: 6 bytes
  EXPECT_TRUE(has(msg, "multiple of 12")) << msg;
  msg = inputErrorOf([&] { load(g, "csv", 2); });
  EXPECT_TRUE(has(msg, "holds 1") && has(msg, "particles.count is 2")) << msg;
}

TEST_F(ParticleFiles, MalformedCsvNamesTheLine) {
  std::string msg = inputErrorOf([&] { load(write("a.csv", "x,y,z\n1,2,3\n4,5\n")); });
  EXPECT_TRUE(has(msg, "a.csv") && has(msg, "line 3") && has(msg, "4,5")) << msg;
  msg = inputErrorOf([&] { load(write("b.csv", "1,2,3\n# c\n1,two,3\n")); });
  EXPECT_TRUE(has(msg, "line 3") && has(msg, "two")) << msg;
  // Only the first data line may be a header.
  msg = inputErrorOf([&] { load(write("c.csv", "x,y,z\nx,y,z\n")); });
  EXPECT_TRUE(has(msg, "line 2")) << msg;
  // A first line that starts with a number is data, not a header.
  msg = inputErrorOf([&] { load(write("d.csv", "1,2\n")); });
  EXPECT_TRUE(has(msg, "line 1")) << msg;
}

TEST_F(ParticleFiles, UnknownFormat) {
  std::string f = write("p.raw", floats({1, 2, 3}));
  std::string msg = inputErrorOf([&] { load(f, "xyz"); });
  EXPECT_TRUE(has(msg, "particles.format") && has(msg, "xyz")) << msg;
}

TEST_F(ParticleFiles, VtkLegacyAsciiPolyData) {
  if (!build::kVtk) GTEST_SKIP() << "this build has no VTK (SORTLAST_WITH_VTK)";
  std::string f = write("p.vtk",
                        "# vtk DataFile Version 3.0\nthree particles\nASCII\nDATASET POLYDATA\n"
                        "POINTS 3 float\n0 1 2\n-3.5 4.25 5\n6 -7 0.001\n"
                        "VERTICES 3 6\n1 0\n1 1\n1 2\n");
  EXPECT_EQ(load(f).positions, kThree);
  EXPECT_EQ(load(f, "vtk", 3).positions, kThree);
  std::string msg = inputErrorOf([&] { load(f, "vtk", 4); });
  EXPECT_TRUE(has(msg, "holds 3")) << msg;
}

// Like the dam-break file: binary, big-endian, an unstructured grid with point data after the
// points.
TEST_F(ParticleFiles, VtkLegacyBinaryUnstructuredGrid) {
  if (!build::kVtk) GTEST_SKIP() << "this build has no VTK (SORTLAST_WITH_VTK)";
  std::string f = write("p.vtk",
                        "# vtk DataFile Version 4.1\nSPH\nBINARY\nDATASET UNSTRUCTURED_GRID\n"
                        "POINTS 3 float\n" +
                            floats({0, 1, 2, -3.5f, 4.25f, 5, 6, -7, 1e-3f}, true) +
                            "\nPOINT_DATA 3\nSCALARS id float 1\nLOOKUP_TABLE default\n" +
                            floats({0, 1, 2}, true) + "\n");
  EXPECT_EQ(load(f).positions, kThree);
  // Zero particles is allowed.
  std::string g = write("none.vtk",
                        "# vtk DataFile Version 4.1\nSPH\nBINARY\nDATASET "
                        "UNSTRUCTURED_GRID\nPOINTS 0 float\n");
  EXPECT_TRUE(load(g).positions.empty());
}

TEST_F(ParticleFiles, VtkXml) {
  if (!build::kVtk) GTEST_SKIP() << "this build has no VTK (SORTLAST_WITH_VTK)";
  std::string vtp =
      write("p.vtp",
            "<?xml version=\"1.0\"?>\n"
            "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            " <PolyData>\n"
            "  <Piece NumberOfPoints=\"3\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
            "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n"
            "   <Points>\n"
            "    <DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">"
            "0 1 2 -3.5 4.25 5 6 -7 0.001</DataArray>\n"
            "   </Points>\n"
            "  </Piece>\n"
            " </PolyData>\n"
            "</VTKFile>\n");
  EXPECT_EQ(load(vtp).positions, kThree);
  std::string vtu =
      write("p.vtu",
            "<?xml version=\"1.0\"?>\n"
            "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            " <UnstructuredGrid>\n"
            "  <Piece NumberOfPoints=\"3\" NumberOfCells=\"0\">\n"
            "   <Points>\n"
            "    <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">"
            "0 1 2 -3.5 4.25 5 6 -7 0.001</DataArray>\n"
            "   </Points>\n"
            "   <Cells>\n"
            "    <DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\"></DataArray>\n"
            "    <DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\"></DataArray>\n"
            "    <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\"></DataArray>\n"
            "   </Cells>\n"
            "  </Piece>\n"
            " </UnstructuredGrid>\n"
            "</VTKFile>\n");
  EXPECT_EQ(load(vtu).positions, kThree);
}

TEST_F(ParticleFiles, VtkErrors) {
  if (!build::kVtk) GTEST_SKIP() << "this build has no VTK (SORTLAST_WITH_VTK)";
  std::string img = write("img.vtk",
                          "# vtk DataFile Version 3.0\nimage\nASCII\nDATASET STRUCTURED_POINTS\n"
                          "DIMENSIONS 2 1 1\nSPACING 1 1 1\nORIGIN 0 0 0\n"
                          "POINT_DATA 2\nSCALARS v float 1\nLOOKUP_TABLE default\n0 1\n");
  std::string msg = inputErrorOf([&] { load(img); });
  EXPECT_TRUE(has(msg, "img.vtk") && has(msg, "POLYDATA")) << msg;
  // Truncated points, binary and ASCII: VTK only warns (and returns the declared number of
  // points, some uninitialised); the warning becomes an InputError.
  std::string cut = write("cut.vtk",
                          "# vtk DataFile Version 4.1\nSPH\nBINARY\nDATASET "
                          "UNSTRUCTURED_GRID\nPOINTS 3 float\n" +
                              floats({0, 1, 2, 3}, true));
  msg = inputErrorOf([&] { load(cut); });
  EXPECT_TRUE(has(msg, "cut.vtk") && has(msg, "could not read")) << msg;
  std::string short_ascii = write("short.vtk",
                                  "# vtk DataFile Version 3.0\nshort\nASCII\nDATASET "
                                  "POLYDATA\nPOINTS 3 float\n0 1 2\n3 4\n");
  msg = inputErrorOf([&] { load(short_ascii); });
  EXPECT_TRUE(has(msg, "short.vtk") && has(msg, "could not read")) << msg;
  std::string junk = write("junk.vtp", "not xml at all\n");
  msg = inputErrorOf([&] { load(junk); });
  EXPECT_TRUE(has(msg, "junk.vtp")) << msg;
}

// The project's copy of the dam-break positions (tests/data), and, where the shared data folder is
// present, the original VTK file they were converted from.
TEST(Particles, DamBreak) {
  ParticleDesc raw;
  raw.file = std::string(SORTLAST_TEST_DATA) + "/dam_break_xyz_float32.raw";
  raw.count = 24389;
  ParticleSet r = loadParticles(raw);
  ASSERT_EQ(r.positions.size(), 24389u);
  Box3 b = r.bounds();
  EXPECT_TRUE(b.lo.x < b.hi.x && b.lo.y < b.hi.y && b.lo.z < b.hi.z);

  ParticleDesc vtk;
  vtk.file = "/work/shared/data/dam_break_frame_23_24389_particles.vtk";
  if (!fs::exists(vtk.file)) GTEST_SKIP() << vtk.file << " absent";
  ParticleSet v = loadParticles(vtk);
  ASSERT_EQ(v.positions.size(), 24389u);
  EXPECT_EQ(0, std::memcmp(v.positions.data(), r.positions.data(),
                           r.positions.size() * sizeof(glm::vec3)));
}

TEST(Particles, LayersAreThePapersLattice) {
  const double s = 0.3;
  ParticleSet p = proceduralParticles("layers", 1000, s);  // one full layer of 576, one partial
  ASSERT_EQ(p.positions.size(), 1000u);
  auto near = [](glm::vec3 a, glm::dvec3 b) { return glm::length(glm::dvec3(a) - b) < 1e-6; };
  EXPECT_TRUE(near(p.positions[1] - p.positions[0], {s, 0, 0}));
  EXPECT_TRUE(near(p.positions[24] - p.positions[0], {0, 0, s}));
  EXPECT_TRUE(near(p.positions[576] - p.positions[0], {0, s, 0}));
  Box3 b = p.bounds();
  EXPECT_LT(glm::length(b.centre()), 1e-6);
  EXPECT_NEAR(b.extent().x, 23 * s, 1e-6);
  EXPECT_NEAR(b.extent().z, 23 * s, 1e-6);
  EXPECT_NEAR(b.extent().y, s, 1e-6);  // two layers
  EXPECT_NEAR(proceduralParticles("layers", 4096, s).bounds().extent().y, 7 * s, 1e-6);  // 8 layers
  EXPECT_TRUE(proceduralParticles("layers", 0, s).positions.empty());
}

// Nearest-neighbour distances of a set, brute force (small sets only).
std::vector<double> nearestDistances(const std::vector<glm::vec3>& ps) {
  std::vector<double> d;
  for (size_t i = 0; i < ps.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < ps.size(); ++j)
      if (j != i) best = std::min(best, double(glm::length(ps[i] - ps[j])));
    d.push_back(best);
  }
  return d;
}

TEST(Particles, SplashIsDeterministicWithTheCountAsked) {
  for (long long n : {0LL, 1LL, 2LL, 7LL, 100LL, 4096LL, 20000LL}) {
    ParticleSet a = proceduralParticles("splash", n, 0.3);
    ParticleSet b = proceduralParticles("splash", n, 0.3);
    ASSERT_EQ(a.positions.size(), size_t(n)) << n;
    if (n == 0) continue;
    EXPECT_EQ(0, std::memcmp(a.positions.data(), b.positions.data(),
                             a.positions.size() * sizeof(glm::vec3)))
        << n;
    for (const glm::vec3& p : a.positions)
      ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << n;
    EXPECT_LT(glm::length(a.bounds().centre()), 1e-5) << n;
  }
}

TEST(Particles, SplashShape) {
  const double s = 0.3;
  ParticleSet p = proceduralParticles("splash", 4096, s);
  // Neighbours about `spacing` apart: the median nearest-neighbour distance is close to it.
  std::vector<double> d = nearestDistances(p.positions);
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  EXPECT_GT(d[d.size() / 2], 0.6 * s);
  EXPECT_LT(d[d.size() / 2], 1.2 * s);
  // A wide, shallow pool with a crown and droplets rising well above it.
  Box3 b = p.bounds();
  EXPECT_GT(b.extent().x, 20 * s);
  EXPECT_GT(b.extent().y, 10 * s);
  long long pool = std::count_if(p.positions.begin(), p.positions.end(),
                                 [&](glm::vec3 q) { return q.y < b.lo.y + 2.5 * s; });
  EXPECT_NEAR(double(pool) / 4096.0, 0.62, 0.02);
  // Spacing only scales the set.
  ParticleSet q = proceduralParticles("splash", 4096, 2 * s);
  for (size_t i = 0; i < p.positions.size(); i += 97)
    EXPECT_LT(glm::length(2.0f * p.positions[i] - q.positions[i]), 1e-4) << i;
}

TEST(Particles, ProceduralErrors) {
  std::string msg = inputErrorOf([] { proceduralParticles("fountain", 10, 0.3); });
  EXPECT_TRUE(has(msg, "particles.procedural") && has(msg, "fountain")) << msg;
  msg = inputErrorOf([] { proceduralParticles("layers", -5, 0.3); });
  EXPECT_TRUE(has(msg, "particles.count")) << msg;
  msg = inputErrorOf([] { proceduralParticles("splash", 10, 0.0); });
  EXPECT_TRUE(has(msg, "particles.spacing")) << msg;
}

TEST(Particles, LoadProceduralDefaultsTo4096) {
  ParticleDesc d;
  EXPECT_FALSE(d.enabled());
  EXPECT_TRUE(loadParticles(d).positions.empty());
  d.procedural = "layers";
  EXPECT_TRUE(d.enabled());
  EXPECT_EQ(loadParticles(d).positions.size(), 4096u);
  d.count = 10;
  EXPECT_EQ(loadParticles(d).positions.size(), 10u);
}

TEST(Particles, NearKeepsOrderAndIncludesTheMargin) {
  Box3 box{{0, 0, 0}, {1, 1, 1}};
  std::vector<glm::vec3> all = {
      {2.0f, 0.5f, 0.5f},    // 1.0 away: out at margin 0.5
      {1.5f, 0.5f, 0.5f},    // exactly 0.5 away: in
      {0.5f, 0.5f, 0.5f},    // inside
      {-0.5f, 0.5f, 0.5f},   // exactly 0.5 away: in
      {1.5f, 1.5f, 0.5f},    // corner, 0.707 away: out
      {1.25f, 1.25f, 0.5f},  // corner, 0.354 away: in
      {0.5f, 0.5f, 1.75f},   // 0.75 away: out
  };
  std::vector<glm::vec3> want = {all[1], all[2], all[3], all[5]};
  EXPECT_EQ(particlesNear(all, box, 0.5), want);
  EXPECT_EQ(particlesNear(all, box, 0.0), std::vector<glm::vec3>{all[2]});
  EXPECT_EQ(particlesNear(all, box, 10.0), all);
  EXPECT_TRUE(particlesNear({}, box, 1.0).empty());
}

TEST(Particles, InfluenceRadius) {
  ParticleDesc d;
  EXPECT_NEAR(d.influenceRadius(), 0.61, 0.001);  // the paper's h
  d.influence = 2.0;
  EXPECT_EQ(d.influenceRadius(), 2.0);
}

// --- scene keys ---

TEST(ParticleScene, DefaultSceneHasAVolumeAndNoParticles) {
  Scene s = loadScene("", {});
  EXPECT_TRUE(s.hasVolume());
  EXPECT_FALSE(s.particles.enabled());
  ParticleDesc defaults;
  EXPECT_EQ(s.particles.count, -1);
  EXPECT_EQ(s.particles.format, "auto");
  EXPECT_EQ(s.particles.spacing, defaults.spacing);
  EXPECT_EQ(s.particles.radius, defaults.radius);
  EXPECT_FALSE(s.particles.influence.has_value());
  EXPECT_EQ(s.particles.threshold, defaults.threshold);
  EXPECT_EQ(s.particles.colour, defaults.colour);
  EXPECT_EQ(s.particles.step, defaults.step);
  EXPECT_EQ(s.particles.max_samples, defaults.max_samples);
  EXPECT_EQ(s.particles.refine_iterations, defaults.refine_iterations);
  EXPECT_EQ(s.particles.cull, defaults.cull);
}

TEST(ParticleScene, KeysParse) {
  Scene s = loadScene(
      "", {"particles.procedural=splash", "particles.count=1000", "particles.spacing=0.5",
           "particles.radius=0.2", "particles.influence=0.9", "particles.threshold=0.5",
           "particles.color=[1, 0.5, 0]", "particles.step=0.25", "particles.max_samples=32",
           "particles.refine_iterations=0", "particles.cull=false"});
  const ParticleDesc& p = s.particles;
  EXPECT_EQ(p.procedural, "splash");
  EXPECT_EQ(p.count, 1000);
  EXPECT_EQ(p.spacing, 0.5);
  EXPECT_EQ(p.radius, 0.2);
  ASSERT_TRUE(p.influence.has_value());
  EXPECT_EQ(p.influenceRadius(), 0.9);
  EXPECT_EQ(p.threshold, 0.5);
  EXPECT_EQ(p.colour, glm::dvec3(1.0, 0.5, 0.0));
  EXPECT_EQ(p.step, 0.25);
  EXPECT_EQ(p.max_samples, 32);
  EXPECT_EQ(p.refine_iterations, 0);
  EXPECT_FALSE(p.cull);
  // count auto: 4096 for a procedural set.
  EXPECT_EQ(loadScene("", {"particles.procedural=layers"}).particles.count, 4096);
}

TEST_F(ParticleFiles, SceneFilePathsAreRelativeToTheScene) {
  fs::create_directories(dir_ / "scenes");
  std::string scene = write("scenes/p.yaml",
                            "volume:\n  procedural: none\nparticles:\n  file: ../p.csv\n"
                            "  format: csv\n");
  Scene s = loadScene(scene, {});
  EXPECT_FALSE(s.hasVolume());
  EXPECT_TRUE(s.particles.enabled());
  EXPECT_EQ(fs::weakly_canonical(s.particles.file), fs::weakly_canonical(dir_ / "p.csv"));
  EXPECT_EQ(s.particles.format, "csv");
  EXPECT_EQ(s.particles.count, -1);  // a file: whatever it holds
  // From --set, the path is the user's, as given.
  EXPECT_EQ(loadScene(scene, {"particles.file=q.raw"}).particles.file, "q.raw");
}

TEST(ParticleScene, BadValuesNameTheKey) {
  struct Case {
    const char* set;
    const char* key;
  } cases[] = {
      {"particles.procedural=fountain", "particles.procedural"},
      {"particles.format=xyz", "particles.format"},
      {"particles.count=-1", "particles.count"},
      {"particles.count=many", "particles.count"},
      {"particles.spacing=0", "particles.spacing"},
      {"particles.radius=0", "particles.radius"},
      {"particles.radius=-1", "particles.radius"},
      {"particles.influence=0", "particles.influence"},
      {"particles.threshold=0", "particles.threshold"},
      {"particles.threshold=1", "particles.threshold"},
      {"particles.color=[1, 2, 0]", "particles.color"},
      {"particles.color=[1, 1]", "particles.color"},
      {"particles.step=0", "particles.step"},
      {"particles.max_samples=0", "particles.max_samples"},
      {"particles.refine_iterations=-1", "particles.refine_iterations"},
      {"particles.cull=maybe", "particles.cull"},
  };
  for (const Case& c : cases) {
    std::string msg = inputErrorOf([&] { loadScene("", {"particles.procedural=layers", c.set}); });
    EXPECT_TRUE(has(msg, c.key)) << c.set << ": " << msg;
  }
  std::string msg = inputErrorOf([] {
    loadScene("", {"particles.procedural=layers", "particles.file=p.raw"});
  });
  EXPECT_TRUE(has(msg, "particles.file") && has(msg, "particles.procedural")) << msg;
}

TEST(ParticleScene, NeitherVolumeNorParticlesIsAnError) {
  std::string msg = inputErrorOf([] { loadScene("", {"volume.procedural=none"}); });
  EXPECT_TRUE(has(msg, "volume.procedural") && has(msg, "particles")) << msg;
  Scene s = loadScene("", {"volume.procedural=none", "particles.procedural=layers"});
  EXPECT_FALSE(s.hasVolume());
  EXPECT_TRUE(s.particles.enabled());
  // A file still makes a volume.
  EXPECT_TRUE(loadScene("", {"volume.procedural=none", "volume.file=v.raw"}).hasVolume());
}

TEST(ParticleScene, FrameCamerasFollowTheBounds) {
  Scene s = loadScene("", {});
  Box3 vol = s.volume.grid.worldBox();
  // The automatic camera: the bounds' bounding sphere (radius r) fits the field of view with 2%
  // to spare, at distance 1.02 r / sin(fov / 2) for a square image (fov 35 degrees).
  const double k = 1.02 / std::sin(17.5 * M_PI / 180.0);
  Camera c = s.frameCameras(vol)[0];
  EXPECT_EQ(c.look_at, glm::dvec3(0.0));
  EXPECT_NEAR(glm::length(c.position), k * 0.5 * 127.0 * std::sqrt(3.0), 1e-9);
  EXPECT_NEAR(
      glm::distance(glm::normalize(c.position), glm::normalize(glm::dvec3(0.55, 0.35, 1.0))), 0.0,
      1e-12);
  // A box off the origin: looked at from its centre.
  Box3 b{{10, 0, 0}, {14, 2, 1}};
  c = s.frameCameras(b)[0];
  EXPECT_EQ(c.look_at, glm::dvec3(12, 1, 0.5));
  EXPECT_NEAR(glm::length(c.position - c.look_at), k * 0.5 * std::sqrt(21.0), 1e-12);
  // A fixed look_at stays; the sphere about it then holds the box's sphere.
  c = loadScene("", {"camera.look_at=[1,2,3]"}).frameCameras(b)[0];
  EXPECT_EQ(c.look_at, glm::dvec3(1, 2, 3));
  EXPECT_NEAR(glm::length(c.position - c.look_at),
              k * (0.5 * std::sqrt(21.0) + glm::length(glm::dvec3(11, -1, -2.5))), 1e-9);
  // Orbit radius: the paper's R, 2 x the largest extent (kept for the benchmark protocol).
  auto orbit = loadScene("", {"camera.orbit.frames=4"}).frameCameras(b);
  ASSERT_EQ(orbit.size(), 4u);
  for (const Camera& o : orbit) EXPECT_NEAR(glm::length(o.position - o.look_at), 8.0, 1e-9);
  // An empty box (no particles, no volume): the unit box about the origin.
  constexpr double inf = std::numeric_limits<double>::infinity();
  c = s.frameCameras(Box3{glm::dvec3(inf), glm::dvec3(-inf)})[0];
  EXPECT_EQ(c.look_at, glm::dvec3(0.0));
  EXPECT_NEAR(glm::length(c.position), k * 0.5 * std::sqrt(3.0), 1e-12);
}

// Twice the largest extent cropped a flat 3 x 1 x 3 pool. Every corner of wide, flat,
// long and thin boxes now projects inside the image, for square, wide and tall images, with at
// least one pixel to spare.
TEST(ParticleScene, AutomaticCameraFramesEveryShape) {
  const Box3 boxes[] = {{{-1.5, -0.5, -1.5}, {1.5, 0.5, 1.5}},
                        {{-0.5, -0.5, -10}, {0.5, 0.5, 10}},
                        {{-20, -0.1, -0.1}, {20, 0.1, 0.1}},
                        {{0, 0, 0}, {1, 30, 1}}};
  const char* sizes[][2] = {{"image.width=256", "image.height=256"},
                            {"image.width=400", "image.height=100"},
                            {"image.width=100", "image.height=400"}};
  for (const char* fov : {"camera.fov=35", "camera.fov=10", "camera.fov=120"})
    for (const auto& size : sizes) {
      Scene s = loadScene("", {size[0], size[1], fov});
      for (const Box3& b : boxes) {
        Camera c = s.frameCameras(b)[0];
        for (int i = 0; i < 8; ++i) {
          auto p = c.project(b.corner(i));
          ASSERT_TRUE(p.has_value());
          EXPECT_GT(p->x, 1.0) << size[0] << " " << fov;
          EXPECT_LT(p->x, c.width - 1.0) << size[0] << " " << fov;
          EXPECT_GT(p->y, 1.0) << size[1] << " " << fov;
          EXPECT_LT(p->y, c.height - 1.0) << size[1] << " " << fov;
        }
      }
    }
}

}  // namespace
}  // namespace sortlast
