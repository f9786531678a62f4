// Adaptive sampling (adaptive/adaptive_blocks.h): the block grid, lossless at tolerance 0, less data
// as the tolerance rises, no cracks between blocks at different levels, the GPU contract (atlas +
// table), and rejection of bad input.
#include "adaptive/adaptive_blocks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "common/brick.h"
#include "common/error.h"
#include "scene/scene.h"
#include "tests/unit/input_error_of.h"
#include "io/volume_source.h"

namespace sortlast {
namespace {

struct TestVolume {
  GridGeometry grid;
  std::vector<float> v;
};

TestVolume makeVolume(const glm::ivec3& dims, const std::function<float(const glm::ivec3&)>& f) {
  TestVolume t{{dims, {1.0, 1.0, 1.0}}, {}};
  t.v.reserve(size_t(t.grid.sampleCount()));
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) t.v.push_back(f({x, y, z}));
  return t;
}

// Integer ramp everywhere (reproduced exactly by every level away from the volume's faces, where
// the mirrored restriction bends it), with a ball of noise: blocks at every level, and blocks at
// level 0 next to coarse ones (so the stitching runs). Dims not of the form 2^k + 1, so the last
// blocks are padded.
TestVolume rampWithNoise() {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> noise(0, 200);
  return makeVolume({70, 45, 53}, [&](const glm::ivec3& p) {
    glm::dvec3 d = glm::dvec3(p) - glm::dvec3(30, 20, 30);
    if (glm::dot(d, d) < 36.0) return float(noise(rng));
    return float(p.x + 2 * p.y + 3 * p.z);
  });
}

// The sharp features of the crack test: a smooth background, a thin oblique sheet and a step, both
// crossing many block faces.
TestVolume sheetAndStep() {
  const glm::dvec3 n = glm::normalize(glm::dvec3(1.0, 0.7, 0.4));
  return makeVolume({65, 65, 65}, [&](const glm::ivec3& p) {
    glm::dvec3 q(p);
    double v = 0.2 + 0.1 * std::sin(q.x / 20.0) * std::cos(q.y / 25.0);
    if (std::abs(glm::dot(n, q - glm::dvec3(30.0, 28.0, 33.0))) < 0.8) v += 1.0;
    if (q.x > 40.3 && q.y < 30.0) v += 0.5;
    return float(v);
  });
}

TestVolume neghip() {
  VolumeDesc d;
  d.file = std::string(SORTLAST_TEST_DATA) + "/neghip_64x64x64_uint8.raw";
  d.grid.dims = {64, 64, 64};
  validateVolume(d);
  return {d.grid, readSamples(d, {{0, 0, 0}, d.grid.dims - 1})};
}

bool inGrid(const BlockGrid& g, const glm::ivec3& c) {
  return glm::all(glm::greaterThanEqual(c, glm::ivec3(0))) && glm::all(glm::lessThan(c, g.blocks));
}

// Blocks with a coarser block among their 26 neighbours: those whose face samples are stitched.
int stitchedBlocks(const AdaptiveVolume& a) {
  const BlockGrid& g = a.blocks;
  int n = 0;
  for (int id = 0; id < g.count(); ++id) {
    glm::ivec3 c = g.cellOf(id);
    bool coarser = false;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          glm::ivec3 q = c + glm::ivec3(dx, dy, dz);
          if (inGrid(g, q)) coarser |= a.table[g.id(q)].level > a.table[id].level;
        }
    n += coarser;
  }
  return n;
}


TEST(AdaptiveBlocks, BlockGridFollowsThePaper) {
  // 256^3 samples (255 cells) in 8 blocks per axis: 32 cells each, the last padded by one.
  BlockGrid g = makeBlockGrid({256, 256, 256}, 8);
  EXPECT_EQ(g.block_cells, glm::ivec3(32));
  EXPECT_EQ(g.blocks, glm::ivec3(8));
  EXPECT_EQ(g.max_level, 5);
  EXPECT_EQ(g.samplesAt(2), glm::ivec3(9));
  g = makeBlockGrid({64, 64, 64}, 16);
  EXPECT_EQ(g.block_cells, glm::ivec3(4));
  EXPECT_EQ(g.blocks, glm::ivec3(16));
  // Anisotropic: per axis the smallest power of two that covers the axis in b blocks.
  g = makeBlockGrid({65, 33, 17}, 4);
  EXPECT_EQ(g.block_cells, glm::ivec3(16, 8, 4));
  EXPECT_EQ(g.blocks, glm::ivec3(4));
  EXPECT_EQ(g.max_level, 2);
  // 99 cells in at most 8 blocks: 16 cells each, 7 blocks.
  g = makeBlockGrid({100, 100, 100}, 8);
  EXPECT_EQ(g.block_cells, glm::ivec3(16));
  EXPECT_EQ(g.blocks, glm::ivec3(7));
  for (int id = 0; id < g.count(); ++id) EXPECT_EQ(g.id(g.cellOf(id)), id);
}

TEST(AdaptiveBlocks, RejectsBadInput) {
  TestVolume t = makeVolume({9, 9, 9}, [](const glm::ivec3& p) { return float(p.x); });
  for (int b : {0, -4, 3, 6, 12, 512})
    EXPECT_NE(inputErrorOf([&] {
                buildAdaptive(t.grid, t.v, {b, 0.1, 1});
              }).find("adaptive.blocks"),
              std::string::npos)
        << "b = " << b;
  for (double tol : {-0.1, std::nan(""), double(INFINITY)})
    EXPECT_NE(inputErrorOf([&] {
                buildAdaptive(t.grid, t.v, {4, tol, 1});
              }).find("adaptive.tolerance"),
              std::string::npos)
        << "tolerance = " << tol;
  std::vector<float> short_volume(t.v.begin(), t.v.end() - 1);
  EXPECT_NE(inputErrorOf([&] {
              buildAdaptive(t.grid, short_volume, {4, 0.1, 1});
            }).find("samples"),
            std::string::npos);
}

TEST(AdaptiveBlocks, SceneKeys) {
  Scene s = loadScene("", {});
  EXPECT_EQ(s.adaptive.tolerance, 0.0);  // off by default
  EXPECT_EQ(s.adaptive.blocks, 8);
  s = loadScene("", {"adaptive.tolerance=10", "adaptive.blocks=16"});
  EXPECT_DOUBLE_EQ(s.adaptive.tolerance, 0.1);  // percent in the scene, a fraction in the code
  EXPECT_EQ(s.adaptive.blocks, 16);
  for (const char* bad :
       {"adaptive.tolerance=-1", "adaptive.tolerance=101", "adaptive.tolerance=x"})
    EXPECT_NE(inputErrorOf([&] { loadScene("", {bad}); }).find("adaptive.tolerance"),
              std::string::npos)
        << bad;
  for (const char* bad : {"adaptive.blocks=0", "adaptive.blocks=6", "adaptive.blocks=512"})
    EXPECT_NE(inputErrorOf([&] { loadScene("", {bad}); }).find("adaptive.blocks"),
              std::string::npos)
        << bad;
}

// Tolerance 0: the adaptive field equals the original at every original sample, bit for bit,
// while blocks still go coarse where that loses nothing.
TEST(AdaptiveBlocks, ToleranceZeroIsLossless) {
  struct Case {
    const char* name;
    TestVolume vol;
    int b;
  };
  std::vector<Case> cases;
  cases.push_back({"ramp with noise, b=8", rampWithNoise(), 8});
  cases.push_back({"ramp with noise, b=16", rampWithNoise(), 16});
  cases.push_back({"neghip, b=16", neghip(), 16});
  cases.push_back({"neghip, b=8", neghip(), 8});
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    AdaptiveVolume a = buildAdaptive(c.vol.grid, c.vol.v, {c.b, 0.0, 2});
    AdaptiveSummary s = summarise(a, c.vol.v, 2);
    // Not vacuous: some blocks went coarse, some stayed fine, and some were stitched.
    EXPECT_GT(s.blocks_per_level[0], 0);
    EXPECT_LT(s.blocks_per_level[0], a.blocks.count());
    EXPECT_GT(stitchedBlocks(a), 0);
    EXPECT_EQ(s.max_error, 0.0);
    EXPECT_EQ(s.blocks_over_tolerance, 0);
    const glm::ivec3 d = c.vol.grid.dims;
    long long wrong = 0;
    for (int z = 0; z < d.z; ++z)
      for (int y = 0; y < d.y; ++y)
        for (int x = 0; x < d.x; ++x) {
          double got = sampleIndex(a, glm::dvec3(x, y, z));
          double want = c.vol.v[size_t(x) + size_t(d.x) * (y + size_t(d.y) * z)];
          if (got != want && wrong++ < 5)
            ADD_FAILURE() << "sample (" << x << "," << y << "," << z << "): " << got
                          << " != " << want;
        }
    EXPECT_EQ(wrong, 0);
  }
}

// Rising tolerance: no block gets finer, so the data left never grows (and does shrink).
TEST(AdaptiveBlocks, RisingToleranceNeverAddsData) {
  for (const TestVolume& t : {sheetAndStep(), neghip()}) {
    for (int b : {4, 8, 16}) {
      SCOPED_TRACE("b = " + std::to_string(b));
      std::vector<AdaptiveBlock> prev;
      double prev_left = INFINITY, first_left = 0, last_left = 0;
      for (double tol : {0.0, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.4, 0.8}) {
        AdaptiveVolume a = buildAdaptive(t.grid, t.v, {b, tol, 2});
        double left = summarise(a, t.v, 2).data_left;
        EXPECT_LE(left, prev_left) << "tolerance " << tol;
        for (size_t i = 0; i < prev.size(); ++i)
          ASSERT_GE(a.table[i].level, prev[i].level) << "block " << i << " at tolerance " << tol;
        if (tol == 0.0) first_left = left;
        prev = a.table, prev_left = last_left = left;
      }
      EXPECT_LT(last_left, first_left);
    }
  }
}

// Face-adjacent block pairs whose levels differ: (lower block, upper block, axis).
struct FacePair {
  glm::ivec3 lo;
  int axis;
};
std::vector<FacePair> pairsAtDifferentLevels(const AdaptiveVolume& a, int* max_difference) {
  const BlockGrid& g = a.blocks;
  std::vector<FacePair> pairs;
  *max_difference = 0;
  for (int id = 0; id < g.count(); ++id)
    for (int axis = 0; axis < 3; ++axis) {
      glm::ivec3 c = g.cellOf(id), n = c;
      n[axis] += 1;
      if (!inGrid(g, n)) continue;
      int diff = std::abs(a.table[id].level - a.table[g.id(n)].level);
      if (diff == 0) continue;
      pairs.push_back({c, axis});
      *max_difference = std::max(*max_difference, diff);
    }
  return pairs;
}

// The field is continuous across every block face, also where the blocks on the two sides (and
// the four around an edge) are at different levels: sampled just below and just above each face
// (and in the four quadrants around each edge), the values agree to float rounding, while the
// feature makes the field jump by up to ~1 across a cell.
TEST(AdaptiveBlocks, NoCracksBetweenLevels) {
  const TestVolume t = sheetAndStep();
  for (int b : {8, 16}) {
    for (double tol : {0.02, 0.1}) {
      SCOPED_TRACE("b = " + std::to_string(b) + ", tolerance " + std::to_string(tol));
      AdaptiveVolume a = buildAdaptive(t.grid, t.v, {b, tol, 2});
      const BlockGrid& g = a.blocks;
      int max_diff = 0;
      std::vector<FacePair> pairs = pairsAtDifferentLevels(a, &max_diff);
      // Not vacuous: many faces between levels, some two or more levels apart.
      ASSERT_GT(pairs.size(), 20u);
      ASSERT_GE(max_diff, 2);
      const double eps = 1e-7, bound = 1e-5;  // field values are O(1)
      std::mt19937 rng(11);
      std::uniform_real_distribution<double> unit(0.0, 1.0);
      double worst_face = 0;
      long long cracks = 0;  // every one is a failure; the first few are described
      for (const FacePair& p : pairs) {
        const int a0 = p.axis, a1 = (p.axis + 1) % 3, a2 = (p.axis + 2) % 3;
        glm::dvec3 base(p.lo * g.block_cells);
        base[a0] += g.block_cells[a0];
        // Points on the face: a quarter-cell lattice (holding every level's samples and the cell
        // midpoints between them) and random points.
        std::vector<glm::dvec2> uv;
        for (double u = 0; u <= g.block_cells[a1]; u += 0.25)
          for (double v = 0; v <= g.block_cells[a2]; v += 0.25) uv.push_back({u, v});
        for (int k = 0; k < 64; ++k)
          uv.push_back({unit(rng) * g.block_cells[a1], unit(rng) * g.block_cells[a2]});
        for (const glm::dvec2& w : uv) {
          glm::dvec3 q = base;
          q[a1] += w.x, q[a2] += w.y;
          if (q[a1] > t.grid.dims[a1] - 1 || q[a2] > t.grid.dims[a2] - 1 ||
              q[a0] > t.grid.dims[a0] - 1)
            continue;  // padding: not part of the field
          glm::dvec3 below = q, above = q;
          below[a0] -= eps, above[a0] += eps;
          double jump = std::abs(sampleIndex(a, below) - sampleIndex(a, above));
          worst_face = std::max(worst_face, jump);
          if (jump > bound && cracks++ < 5)
            ADD_FAILURE() << "crack of " << jump << " at (" << q.x << "," << q.y << "," << q.z
                          << ") between block (" << p.lo.x << "," << p.lo.y << "," << p.lo.z
                          << ") and its neighbour along axis " << a0;
        }
      }
      // Edges: every block-grid edge inside the volume, in its four quadrants.
      double worst_edge = 0;
      int edges_between_levels = 0;
      for (int axis = 0; axis < 3; ++axis) {
        const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
        for (int i = 1; i < g.blocks[a1]; ++i)
          for (int j = 1; j < g.blocks[a2]; ++j)
            for (double s = 0; s <= t.grid.dims[axis] - 1; s += 0.25) {
              glm::dvec3 q(0.0);
              q[axis] = s, q[a1] = i * g.block_cells[a1], q[a2] = j * g.block_cells[a2];
              double v[4];
              for (int k = 0; k < 4; ++k) {
                glm::dvec3 r = q;
                r[a1] += (k & 1) ? eps : -eps;
                r[a2] += (k & 2) ? eps : -eps;
                v[k] = sampleIndex(a, r);
              }
              double spread = *std::max_element(v, v + 4) - *std::min_element(v, v + 4);
              glm::ivec3 c(0);
              c[axis] = std::min(int(s) / g.block_cells[axis], g.blocks[axis] - 1);
              c[a1] = i, c[a2] = j;
              glm::ivec3 c2 = c;
              c2[a1] -= 1, c2[a2] -= 1;
              edges_between_levels += a.table[g.id(c)].level != a.table[g.id(c2)].level;
              worst_edge = std::max(worst_edge, spread);
              if (spread > bound && cracks++ < 10)
                ADD_FAILURE() << "crack of " << spread << " around the edge at (" << q.x << ","
                              << q.y << "," << q.z << ")";
            }
      }
      EXPECT_GT(edges_between_levels, 0);
      EXPECT_EQ(cracks, 0) << "worst jump across a face " << worst_face << ", around an edge "
                           << worst_edge;
      // Lines through the volume: between two samples h apart the field may change by at most
      // its gradient bound times h (trilinear in each block, samples within the value range, a
      // cell at least 1 wide); a crack would show as a larger step.
      auto [lo, hi] = std::minmax_element(a.atlas.begin(), a.atlas.end());
      const double range = double(*hi) - double(*lo), h = 1e-3;
      const double step_bound = std::sqrt(3.0) * range * h + 1e-6;
      double worst_step = 0;
      for (int line = 0; line < 60; ++line) {
        glm::dvec3 from(unit(rng), unit(rng), unit(rng)), to(unit(rng), unit(rng), unit(rng));
        from *= glm::dvec3(t.grid.dims - 1), to *= glm::dvec3(t.grid.dims - 1);
        const double len = glm::length(to - from);
        const glm::dvec3 dir = (to - from) / len;
        double prev = sampleIndex(a, from);
        for (double s = h; s <= len; s += h) {
          double v = sampleIndex(a, from + s * dir);
          worst_step = std::max(worst_step, std::abs(v - prev));
          prev = v;
        }
      }
      EXPECT_LE(worst_step, step_bound);
    }
  }
}

// What a GL sampler does with the atlas and the table (tableTexels): texture() with GL_LINEAR at
// (offset + local + 0.5) / atlas_dims, emulated here, equals sampleIndex everywhere.
TEST(AdaptiveBlocks, AtlasAndTableGiveTheSameFieldAsTheSampler) {
  const TestVolume t = sheetAndStep();
  AdaptiveVolume a = buildAdaptive(t.grid, t.v, {8, 0.05, 2});
  const BlockGrid& g = a.blocks;
  const std::vector<float> table = a.tableTexels();
  ASSERT_EQ(table.size(), size_t(4 * g.count()));
  auto texel = [&](glm::ivec3 p) {  // GL_CLAMP_TO_EDGE
    p = glm::clamp(p, glm::ivec3(0), a.atlas_dims - 1);
    return double(
        a.atlas[size_t(p.x) + size_t(a.atlas_dims.x) * (p.y + size_t(a.atlas_dims.y) * p.z)]);
  };
  auto gl = [&](const glm::dvec3& u_in) {
    glm::dvec3 u = glm::clamp(u_in, glm::dvec3(0.0), glm::dvec3(t.grid.dims - 1));
    glm::ivec3 c = glm::min(glm::ivec3(glm::floor(u / glm::dvec3(g.block_cells))), g.blocks - 1);
    const float* e = &table[4 * size_t(g.id(c))];
    glm::dvec3 local = (u - glm::dvec3(c * g.block_cells)) * double(e[3]);
    // Texel space of texture(): coordinate * size - 0.5.
    glm::dvec3 tc = glm::dvec3(e[0], e[1], e[2]) + local;
    glm::ivec3 i0 = glm::ivec3(glm::floor(tc));
    glm::dvec3 f = tc - glm::dvec3(i0);
    double v = 0;
    for (int k = 0; k < 8; ++k) {
      glm::ivec3 o(k & 1, (k >> 1) & 1, (k >> 2) & 1);
      double w = (o.x ? f.x : 1 - f.x) * (o.y ? f.y : 1 - f.y) * (o.z ? f.z : 1 - f.z);
      v += w * texel(i0 + o);
    }
    return v;
  };
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0;
  for (int k = 0; k < 20000; ++k) {
    glm::dvec3 u = glm::dvec3(unit(rng), unit(rng), unit(rng)) * glm::dvec3(t.grid.dims - 1);
    if (k % 4 == 0) u = glm::round(u);         // sample points (block faces among them)
    if (k % 4 == 1) u.x = 8.0 * int(u.x / 8);  // block faces
    worst = std::max(worst, std::abs(gl(u) - sampleIndex(a, u)));
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(AdaptiveBlocks, AtlasSlotsAreDisjointAndBoundTheField) {
  const TestVolume t = sheetAndStep();
  AdaptiveVolume a = buildAdaptive(t.grid, t.v, {16, 0.05, 2});
  const BlockGrid& g = a.blocks;
  std::vector<int> owner(size_t(a.atlasTexels()), -1);
  for (int id = 0; id < g.count(); ++id) {
    const AdaptiveBlock& b = a.table[id];
    glm::ivec3 n = g.samplesAt(b.level);
    ASSERT_TRUE(glm::all(glm::greaterThanEqual(b.atlas_offset, glm::ivec3(0))));
    ASSERT_TRUE(glm::all(glm::lessThanEqual(b.atlas_offset + n, a.atlas_dims))) << "block " << id;
    for (int z = 0; z < n.z; ++z)
      for (int y = 0; y < n.y; ++y)
        for (int x = 0; x < n.x; ++x) {
          glm::ivec3 p = b.atlas_offset + glm::ivec3(x, y, z);
          int& o =
              owner[size_t(p.x) + size_t(a.atlas_dims.x) * (p.y + size_t(a.atlas_dims.y) * p.z)];
          ASSERT_EQ(o, -1) << "blocks " << o << " and " << id << " share a texel";
          o = id;
        }
  }
  // vmin / vmax bound the field inside each block (what empty-space skipping will rely on).
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 20000; ++k) {
    glm::dvec3 u = glm::dvec3(unit(rng), unit(rng), unit(rng)) * glm::dvec3(t.grid.dims - 1);
    glm::ivec3 c = glm::min(glm::ivec3(u / glm::dvec3(g.block_cells)), g.blocks - 1);
    const AdaptiveBlock& b = a.table[g.id(c)];
    double v = sampleIndex(a, u);
    ASSERT_GE(v, b.vmin - 1e-6);
    ASSERT_LE(v, b.vmax + 1e-6);
  }
}

// Threads and a reused builder change nothing: the result is a function of the volume alone.
TEST(AdaptiveBlocks, SameResultWithAnyThreadsAndAReusedBuilder) {
  const TestVolume sheet = sheetAndStep(), other = rampWithNoise();
  AdaptiveVolume one = buildAdaptive(sheet.grid, sheet.v, {8, 0.05, 1});
  AdaptiveVolume three = buildAdaptive(sheet.grid, sheet.v, {8, 0.05, 3});
  AdaptiveBuilder builder;
  builder.build(other.grid, other.v, {4, 0.2, 2});  // leaves other data in its buffers
  const AdaptiveVolume& reused = builder.build(sheet.grid, sheet.v, {8, 0.05, 2});
  for (const AdaptiveVolume* a : {static_cast<const AdaptiveVolume*>(&three), &reused}) {
    EXPECT_EQ(a->atlas_dims, one.atlas_dims);
    EXPECT_TRUE(a->atlas == one.atlas);
    ASSERT_EQ(a->table.size(), one.table.size());
    for (size_t i = 0; i < one.table.size(); ++i) {
      EXPECT_EQ(a->table[i].level, one.table[i].level);
      EXPECT_EQ(a->table[i].atlas_offset, one.table[i].atlas_offset);
    }
  }
}

// The blocks a brick draws: exactly those whose cells meet the brick's cells, and together the
// bricks draw every block (blocks need not align with bricks).
TEST(AdaptiveBlocks, BlocksOverlappingBricks) {
  const GridGeometry grid{{65, 50, 37}, {1.0, 1.0, 1.0}};
  for (int b : {4, 8}) {
    BlockGrid g = makeBlockGrid(grid.dims, b);
    for (int d : {1, 2, 3}) {
      std::set<int> all;
      for (const Brick& brick : makeBricks(grid, d)) {
        std::vector<int> got = blocksOverlapping(g, brick.domain);
        std::set<int> want;
        for (int id = 0; id < g.count(); ++id) {
          glm::ivec3 c = g.cellOf(id);
          bool meets = true;
          for (int a = 0; a < 3; ++a)
            meets &= c[a] * g.block_cells[a] <= brick.domain.hi[a] - 1 &&
                     (c[a] + 1) * g.block_cells[a] - 1 >= brick.domain.lo[a];
          if (meets) want.insert(id);
        }
        EXPECT_EQ(std::set<int>(got.begin(), got.end()), want) << "b " << b << " d " << d;
        all.insert(got.begin(), got.end());
      }
      EXPECT_EQ(int(all.size()), g.count());
    }
  }
}

}  // namespace
}  // namespace sortlast
