#include "adaptive/adaptive_blocks.h"

#include "common/trilinear.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <thread>

#include "common/error.h"

namespace sortlast {

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

bool isPowerOfTwo(int v) { return v > 0 && (v & (v - 1)) == 0; }
int log2Of(int v) {  // v a power of two
  int l = 0;
  while ((1 << l) < v) ++l;
  return l;
}
int resolveThreads(int threads) {
  if (threads > 0) return threads;
  return int(std::max(1u, std::thread::hardware_concurrency()));
}

// Runs f(i) for i in [0, n) on `threads` threads, handing out indices one at a time (blocks cost
// very different amounts: an empty one nothing, a detailed one all its levels).
template <class F>
void parallelFor(int n, int threads, F&& f) {
  threads = std::min(threads, n);
  if (threads <= 1) {
    for (int i = 0; i < n; ++i) f(i);
    return;
  }
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int i; (i = next++) < n;) f(i);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
}

size_t linear(const glm::ivec3& p, const glm::ivec3& d) {
  return size_t(p.x) + size_t(d.x) * (size_t(p.y) + size_t(d.y) * size_t(p.z));
}

// Splits [0, n) into one contiguous range per thread: f(begin, end).
template <class F>
void parallelRanges(int n, int threads, F&& f) {
  threads = std::max(1, std::min(threads, n));
  parallelFor(threads, threads, [&](int t) {
    f(int((long long)n * t / threads), int((long long)n * (t + 1) / threads));
  });
}

// The pyramid of the whole (padded) volume. Level 0 is the caller's array, read with the index
// clamped to the last sample (the padding repeats it); level l >= 1 is stored over the whole
// padded extent, (extent >> l) + 1 samples per axis.
class Pyramid {
 public:
  // `storage` holds the levels between calls (a builder reuses it for the next time step).
  Pyramid(const float* original, const glm::ivec3& dims, const glm::ivec3& extent_cells,
          int max_level, int threads, std::vector<std::vector<float>>& storage)
      : orig_(original), dims_(dims), levels_(storage), ldims_(size_t(max_level) + 1) {
    if (levels_.size() < ldims_.size()) levels_.resize(ldims_.size());
    ldims_[0] = extent_cells + 1;
    for (int l = 1; l <= max_level; ++l) {
      // Level 0 is stored only where the volume has samples; the rest is the clamp.
      const float* src = l == 1 ? orig_ : levels_[l - 1].data();
      glm::ivec3 sd = l == 1 ? dims_ : ldims_[l - 1];
      ldims_[l] = restrict(src, sd, extent_cells >> (l - 1), levels_[l], threads);
    }
  }

  glm::ivec3 dims(int level) const { return ldims_[level]; }
  float at(int level, glm::ivec3 p) const {
    if (level == 0) return orig_[linear(glm::min(p, dims_ - 1), dims_)];
    return levels_[level][linear(p, ldims_[level])];
  }
  const float* data(int level) const { return levels_[level].data(); }

 private:
  // The restriction of one axis: out[i] = (in[2i-1] + in[2i+1]) / 4 + in[2i] / 2, the vertex-
  // centred mean of the two cells around 2i, mirrored at both ends of the padded extent e
  // (in[-1] = in[1], in[e+1] = in[e-1]) and clamped to the `stored` samples that exist. Returns the
  // three input indices of each of the e / 2 + 1 outputs.
  struct Taps {
    std::vector<int> a, b, c;
  };
  static Taps tapsOf(int e, int stored) {
    Taps t;
    auto src = [&](int i) { return std::min(i < 0 ? -i : (i > e ? 2 * e - i : i), stored - 1); };
    for (int i = 0; i <= e / 2; ++i) {
      t.a.push_back(src(2 * i - 1));
      t.b.push_back(src(2 * i));
      t.c.push_back(src(2 * i + 1));
    }
    return t;
  }

  // One level from the one below: separable, x then y then z, fused per z plane so the input is
  // read once (a plane reduced in x and y is kept for the next output plane that needs it).
  // Written (a + c) * 0.25 + b * 0.5 so that a constant stays bit-exact at every level.
  static glm::ivec3 restrict(const float* in, const glm::ivec3& sd, const glm::ivec3& ext,
                             std::vector<float>& out, int threads) {
    const glm::ivec3 od = ext / 2 + 1;
    const Taps tx = tapsOf(ext.x, sd.x), ty = tapsOf(ext.y, sd.y), tz = tapsOf(ext.z, sd.z);
    out.resize(size_t(od.x) * od.y * od.z);
    const size_t plane = size_t(od.x) * od.y;
    parallelRanges(od.z, threads, [&](int z0, int z1) {
      std::vector<float> rows(size_t(od.x) * sd.y), pa(plane), pb(plane), pc(plane);
      // Input plane z reduced along x (into rows) and then y (into dst).
      auto reducePlane = [&](int z, std::vector<float>& dst) {
        const float* src = &in[size_t(sd.x) * sd.y * z];
        for (int y = 0; y < sd.y; ++y) {
          const float* r = &src[size_t(sd.x) * y];
          float* o = &rows[size_t(od.x) * y];
          for (int i = 0; i < od.x; ++i)
            o[i] = (r[tx.a[i]] + r[tx.c[i]]) * 0.25f + r[tx.b[i]] * 0.5f;
        }
        for (int j = 0; j < od.y; ++j) {
          const float *a = &rows[size_t(od.x) * ty.a[j]], *b = &rows[size_t(od.x) * ty.b[j]],
                      *c = &rows[size_t(od.x) * ty.c[j]];
          float* o = &dst[size_t(od.x) * j];
          for (int i = 0; i < od.x; ++i) o[i] = (a[i] + c[i]) * 0.25f + b[i] * 0.5f;
        }
      };
      int have = -1;  // the input plane held in pc from the previous output plane
      for (int k = z0; k < z1; ++k) {
        if (tz.a[k] == have)
          std::swap(pa, pc);
        else
          reducePlane(tz.a[k], pa);
        reducePlane(tz.b[k], pb);
        reducePlane(tz.c[k], pc);
        have = tz.c[k];
        float* o = &out[plane * k];
        for (size_t i = 0; i < plane; ++i) o[i] = (pa[i] + pc[i]) * 0.25f + pb[i] * 0.5f;
      }
    });
    return od;
  }

  const float* orig_;
  glm::ivec3 dims_;
  std::vector<std::vector<float>>& levels_;
  std::vector<glm::ivec3> ldims_;
};

// Per block, over the original samples of its closed box: what the level test needs.
struct BlockMoments {
  double sum_sq = 0;  // sum v^2: the tolerance's reference
  float lo = 0, hi = 0;
};

// The moments of every block, in one pass over the volume in memory order (reading block by block
// was twice as slow: short rows far apart). One task per layer of blocks along z; a sample on a
// block face counts in every block whose closed box holds it.
std::vector<BlockMoments> allMoments(const float* v, const BlockGrid& g, int threads) {
  BlockMoments empty;
  empty.lo = std::numeric_limits<float>::infinity();
  empty.hi = -empty.lo;
  std::vector<BlockMoments> out(size_t(g.count()), empty);
  const glm::ivec3 s = g.block_cells, d = g.dims;
  auto blocksHolding = [](int i, int cells, int count, int& first, int& last) {
    last = std::min(i / cells, count - 1);
    first = (i % cells == 0 && i > 0) ? i / cells - 1 : last;
  };
  parallelFor(g.blocks.z, threads, [&](int cz) {
    std::vector<BlockMoments> seg(size_t(g.blocks.x));
    for (int z = cz * s.z; z <= std::min((cz + 1) * s.z, d.z - 1); ++z)
      for (int y = 0; y < d.y; ++y) {
        const float* row = &v[linear({0, y, z}, d)];
        for (int cx = 0; cx < g.blocks.x; ++cx) {
          // Independent lanes so the compiler can vectorise (the order of the sums is free).
          constexpr int kLanes = 4;
          double acc[kLanes] = {};
          float lo[kLanes], hi[kLanes];
          std::fill(lo, lo + kLanes, empty.lo);
          std::fill(hi, hi + kLanes, empty.hi);
          const int x0 = cx * s.x, n = std::min((cx + 1) * s.x, d.x - 1) - x0 + 1;
          const float* r = row + x0;
          int x = 0;
          for (; x + kLanes <= n; x += kLanes)
            for (int k = 0; k < kLanes; ++k) {
              const float a = r[x + k];
              acc[k] += double(a) * a;
              lo[k] = a < lo[k] ? a : lo[k];
              hi[k] = a > hi[k] ? a : hi[k];
            }
          for (; x < n; ++x) {
            const float a = r[x];
            acc[0] += double(a) * a;
            lo[0] = a < lo[0] ? a : lo[0];
            hi[0] = a > hi[0] ? a : hi[0];
          }
          seg[cx].sum_sq = acc[0] + acc[1] + acc[2] + acc[3];
          seg[cx].lo = std::min({lo[0], lo[1], lo[2], lo[3]});
          seg[cx].hi = std::max({hi[0], hi[1], hi[2], hi[3]});
        }
        int y0, y1;
        blocksHolding(y, s.y, g.blocks.y, y0, y1);
        for (int cy = y0; cy <= y1; ++cy)
          for (int cx = 0; cx < g.blocks.x; ++cx) {
            BlockMoments& m = out[size_t(g.id({cx, cy, cz}))];
            m.sum_sq += seg[cx].sum_sq;
            m.lo = std::min(m.lo, seg[cx].lo);
            m.hi = std::max(m.hi, seg[cx].hi);
          }
      }
  });
  return out;
}

// The block's original samples, clipped to the volume (the padding is never sampled).
IndexBox realSamplesOf(const BlockGrid& g, const glm::ivec3& c) {
  IndexBox b = g.samplesOf(c);
  b.hi = glm::min(b.hi, g.dims - 1);
  return b;
}

// Interpolation weights of one axis: fine sample `x` (block-local) on a lattice of spacing 2^l
// with m cells: the cell and the fraction, computed exactly as sampleIndex() does.
struct Tap {
  int cell;
  double f;
};
Tap tapOf(int x, int level, int m) {
  double local = std::ldexp(double(x), -level);
  int i = std::min(int(local), m - 1);
  return {i, local - i};
}

// E_l of eq. 3: the squared error of block c at `level` (its level-l pyramid samples, trilinear,
// before any stitching) against the original at every original sample of its closed box.
// Separable (x, then y, then z) with exactly the arithmetic of sampleIndex(), so E = 0 means the
// sampler returns every original sample unchanged. Stops early (returning a sum > budget) once
// the sum exceeds `budget`: only the comparison matters.
double levelError(const Pyramid& pyr, const float* orig, const BlockGrid& g, const glm::ivec3& c,
                  int level, double budget, std::vector<double>& ax, std::vector<double>& axy) {
  const glm::ivec3 m = g.block_cells >> level;  // lattice cells per axis
  const glm::ivec3 lat0 = c * m;                // first lattice sample in pyramid level coordinates
  const IndexBox real = realSamplesOf(g, c);
  const glm::ivec3 n = real.size();            // fine samples per axis
  const glm::ivec3 first = c * g.block_cells;  // block-local origin
  const glm::ivec3 ld = pyr.dims(level);
  const float* p = pyr.data(level);
  std::vector<Tap> tx(size_t(n.x)), ty(size_t(n.y));
  for (int x = 0; x < n.x; ++x) tx[x] = tapOf(real.lo.x + x - first.x, level, m.x);
  for (int y = 0; y < n.y; ++y) ty[y] = tapOf(real.lo.y + y - first.y, level, m.y);
  // ax[x, ly, lz]: along x at every lattice row; axy[x, y, lz]: then along y.
  const int ly = m.y + 1, lz = m.z + 1;
  ax.resize(size_t(n.x) * ly * lz);
  axy.resize(size_t(n.x) * n.y * lz);
  for (int z = 0; z < lz; ++z)
    for (int y = 0; y < ly; ++y) {
      const float* row = &p[linear(lat0 + glm::ivec3(0, y, z), ld)];
      double* o = &ax[size_t(n.x) * (y + size_t(ly) * z)];
      for (int x = 0; x < n.x; ++x) {
        const Tap t = tx[x];
        o[x] = double(row[t.cell]) * (1 - t.f) + double(row[t.cell + 1]) * t.f;
      }
    }
  for (int z = 0; z < lz; ++z)
    for (int y = 0; y < n.y; ++y) {
      const Tap t = ty[y];
      const double* a = &ax[size_t(n.x) * (t.cell + size_t(ly) * z)];
      const double* b = a + n.x;
      double* o = &axy[size_t(n.x) * (y + size_t(n.y) * z)];
      for (int x = 0; x < n.x; ++x) o[x] = a[x] * (1 - t.f) + b[x] * t.f;
    }
  // Independent lanes so the compiler can vectorise; E = 0 exactly iff every difference is 0,
  // whatever the order of the sums.
  constexpr int kLanes = 4;
  double acc[kLanes] = {};
  double total = 0;
  for (int z = 0; z < n.z; ++z) {
    const Tap t = tapOf(real.lo.z + z - first.z, level, m.z);
    const double w0 = 1 - t.f, w1 = t.f;  // the sampler's (1 - f) and f
    for (int y = 0; y < n.y; ++y) {
      const double* a = &axy[size_t(n.x) * (y + size_t(n.y) * t.cell)];
      const double* b = &axy[size_t(n.x) * (y + size_t(n.y) * (t.cell + 1))];
      const float* v = &orig[linear({real.lo.x, real.lo.y + y, real.lo.z + z}, g.dims)];
      int x = 0;
      for (; x + kLanes <= n.x; x += kLanes)
        for (int k = 0; k < kLanes; ++k) {
          const double d = double(v[x + k]) - (a[x + k] * w0 + b[x + k] * w1);
          acc[k] += d * d;
        }
      for (; x < n.x; ++x) {
        const double d = double(v[x]) - (a[x] * w0 + b[x] * w1);
        acc[0] += d * d;
      }
    }
    total = acc[0] + acc[1] + acc[2] + acc[3];
    if (total > budget) break;
  }
  return total;
}

// The level of the skeleton element (face, edge or block-grid vertex) that holds sample p (level-0
// coordinates on the padded extent): the coarsest level among the blocks whose closed boxes hold
// p. On a block face only the two blocks sharing it count, on an edge the four, at a corner eight.
int elementLevel(const BlockGrid& g, const std::vector<AdaptiveBlock>& table, const glm::ivec3& p) {
  int lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    int c = p[a] / g.block_cells[a];
    bool on_plane = p[a] % g.block_cells[a] == 0;
    lo[a] = std::clamp(on_plane ? c - 1 : c, 0, g.blocks[a] - 1);
    hi[a] = std::clamp(c, 0, g.blocks[a] - 1);
  }
  int level = 0;
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y)
      for (int x = lo[0]; x <= hi[0]; ++x) level = std::max(level, table[g.id({x, y, z})].level);
  return level;
}

// The stitched value at a sample p that lies on a block face: the field of the element that holds
// it, i.e. the element's level-L samples interpolated (multi-)linearly along the element's free
// axes; lattice points on the element's own boundary take the lower-dimensional element's value
// (recursively, at most 3 deep). p is on some block's lattice, so it is a multiple of that
// block's spacing, which divides the element's.
double skeletonValue(const Pyramid& pyr, const BlockGrid& g,
                     const std::vector<AdaptiveBlock>& table, const glm::ivec3& p) {
  const int level = elementLevel(g, table, p);
  const int h = 1 << level;
  int free_axes[3], nf = 0;
  for (int a = 0; a < 3; ++a)
    if (p[a] % g.block_cells[a] != 0 && p[a] % h != 0) free_axes[nf++] = a;
  if (nf == 0) return pyr.at(level, p >> level);
  // Corners of the lattice cell around p along the free axes (the others are on the lattice).
  double value = 0;
  for (int corner = 0; corner < (1 << nf); ++corner) {
    glm::ivec3 q = p;
    double w = 1;
    for (int k = 0; k < nf; ++k) {
      int a = free_axes[k];
      int below = p[a] - p[a] % h;
      double f = double(p[a] - below) / h;
      bool up = (corner >> k) & 1;
      q[a] = up ? below + h : below;
      w *= up ? f : 1 - f;
    }
    // A corner may fall on a block plane of a free axis: a lower-dimensional element.
    bool lower = false;
    for (int k = 0; k < nf; ++k) lower |= q[free_axes[k]] % g.block_cells[free_axes[k]] == 0;
    value += w * (lower ? skeletonValue(pyr, g, table, q) : double(pyr.at(level, q >> level)));
  }
  return value;
}

}  // namespace

// Places blocks in the atlas: the blocks of each level (all the same size) on a regular grid of
// slots, one region per level, regions stacked along z. Regions are about as wide as the cube
// root of the total, so the atlas stays roughly cubic (3D textures are limited per axis).
glm::ivec3 packAtlas(const BlockGrid& g, std::vector<AdaptiveBlock>& table) {
  std::vector<std::vector<int>> by_level(size_t(g.max_level) + 1);
  for (int id = 0; id < int(table.size()); ++id) by_level[table[id].level].push_back(id);
  double total = 0;
  for (int l = 0; l <= g.max_level; ++l) {
    glm::dvec3 s(g.samplesAt(l));
    total += double(by_level[l].size()) * s.x * s.y * s.z;
  }
  const int side = std::max(1, int(std::ceil(std::cbrt(total))));
  glm::ivec3 dims{1, 1, 0};
  for (int l = 0; l <= g.max_level; ++l) {
    const int count = int(by_level[l].size());
    if (count == 0) continue;
    const glm::ivec3 s = g.samplesAt(l);
    int gx = std::clamp(side / s.x, 1, count);
    int gy = std::clamp(side / s.y, 1, (count + gx - 1) / gx);
    int gz = (count + gx * gy - 1) / (gx * gy);
    for (int k = 0; k < count; ++k)
      table[by_level[l][k]].atlas_offset =
          glm::ivec3(k % gx, (k / gx) % gy, k / (gx * gy)) * s + glm::ivec3(0, 0, dims.z);
    dims.x = std::max(dims.x, gx * s.x);
    dims.y = std::max(dims.y, gy * s.y);
    dims.z += gz * s.z;
  }
  return dims;
}

BlockGrid makeBlockGrid(const glm::ivec3& dims, int b) {
  if (!isPowerOfTwo(b) || b > 256)
    throw InputError("adaptive.blocks: must be a power of two in [1, 256] (blocks per axis), got " +
                     std::to_string(b));
  BlockGrid g;
  g.dims = dims;
  for (int a = 0; a < 3; ++a) {
    if (dims[a] < 2) throw InputError("adaptive sampling: the volume needs >= 2 samples per axis");
    int cells = dims[a] - 1, s = 1;
    while ((long long)s * b < cells) s *= 2;
    g.block_cells[a] = s;
    g.blocks[a] = (cells + s - 1) / s;
  }
  g.max_level = log2Of(std::min({g.block_cells.x, g.block_cells.y, g.block_cells.z}));
  return g;
}

std::vector<int> blocksOverlapping(const BlockGrid& g, const IndexBox& samples) {
  std::vector<int> ids;
  if (samples.count() == 0) return ids;
  glm::ivec3 lo, hi;
  for (int a = 0; a < 3; ++a) {
    // Cells [samples.lo, samples.hi - 1]; a box one sample thick still touches its block.
    int c0 = samples.lo[a], c1 = std::max(samples.lo[a], samples.hi[a] - 1);
    lo[a] = std::clamp(c0 / g.block_cells[a], 0, g.blocks[a] - 1);
    hi[a] = std::clamp(c1 / g.block_cells[a], 0, g.blocks[a] - 1);
  }
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) ids.push_back(g.id({x, y, z}));
  return ids;
}

std::vector<float> tableTexels(const std::vector<AdaptiveBlock>& table) {
  std::vector<float> t;
  t.reserve(table.size() * 4);
  for (const AdaptiveBlock& b : table) {
    t.push_back(float(b.atlas_offset.x));
    t.push_back(float(b.atlas_offset.y));
    t.push_back(float(b.atlas_offset.z));
    t.push_back(std::ldexp(1.0f, -b.level));
  }
  return t;
}

const AdaptiveVolume& AdaptiveBuilder::build(const GridGeometry& grid,
                                             const std::vector<float>& samples,
                                             const AdaptiveOptions& options) {
  if (!(options.tolerance >= 0.0) || !std::isfinite(options.tolerance))
    throw InputError("adaptive.tolerance: must be a finite number >= 0");
  if ((long long)samples.size() != grid.sampleCount())
    throw InputError("adaptive sampling: " + std::to_string(samples.size()) +
                     " samples for a grid of " + std::to_string(grid.sampleCount()));
  const int threads = resolveThreads(options.threads);
  AdaptiveVolume& out = out_;
  out.grid = grid;
  out.tolerance = options.tolerance;
  const BlockGrid g = makeBlockGrid(grid.dims, options.blocks_per_axis);
  out.blocks = g;
  const float* orig = samples.data();

  auto t0 = Clock::now();
  const Pyramid pyr(orig, g.dims, g.blocks * g.block_cells, g.max_level, threads, pyramid_);
  out.timings.pyramid_s = secondsSince(t0);

  // Levels: per block, the moments of its original samples, then levels 1, 2, ... while the
  // error stays within the tolerance.
  t0 = Clock::now();
  const int nb = g.count();
  const std::vector<BlockMoments> moments = allMoments(orig, g, threads);
  out.table.assign(size_t(nb), AdaptiveBlock{});
  parallelFor(nb, threads, [&](int id) {
    const glm::ivec3 c = g.cellOf(id);
    // A block whose samples and its neighbours' are all one value is that value at every level:
    // the restriction of level l reads at most 2^l - 1 < s samples beyond the block, i.e. only
    // the 26 neighbours. Skip the error sums there (most of a CT volume is such air).
    float lo = moments[id].lo, hi = moments[id].hi;
    for (int dz = -1; dz <= 1 && lo == hi; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          glm::ivec3 q = c + glm::ivec3(dx, dy, dz);
          if (glm::any(glm::lessThan(q, glm::ivec3(0))) ||
              glm::any(glm::greaterThanEqual(q, g.blocks)))
            continue;
          lo = std::min(lo, moments[g.id(q)].lo);
          hi = std::max(hi, moments[g.id(q)].hi);
        }
    if (lo == hi) {
      out.table[id].level = g.max_level;
      return;
    }
    thread_local std::vector<double> ax, axy;
    // eq. 3 <= tolerance^2 * sum v^2: RMS error <= tolerance * RMS value.
    const double budget = options.tolerance * options.tolerance * moments[id].sum_sq;
    int level = 0;
    while (level < g.max_level && levelError(pyr, orig, g, c, level + 1, budget, ax, axy) <= budget)
      ++level;
    out.table[id].level = level;
  });
  out.timings.levels_s = secondsSince(t0);

  // Pack: place the blocks, then copy each block's samples at its level, its face samples
  // stitched to the coarsest neighbour that shares them.
  t0 = Clock::now();
  out.atlas_dims = packAtlas(g, out.table);
  out.atlas.assign(size_t(out.atlasTexels()), 0.0f);
  parallelFor(nb, threads, [&](int id) {
    const glm::ivec3 c = g.cellOf(id);
    AdaptiveBlock& blk = out.table[id];
    const int l = blk.level;
    const glm::ivec3 m = g.block_cells >> l, ns = m + 1, lat0 = c * m;
    auto row = [&](int y, int z) {
      return &out.atlas[linear(blk.atlas_offset + glm::ivec3(0, y, z), out.atlas_dims)];
    };
    // The block's level-l samples, row by row (level 0: the original, the padding repeating the
    // last sample of each axis).
    for (int z = 0; z < ns.z; ++z)
      for (int y = 0; y < ns.y; ++y) {
        float* dst = row(y, z);
        if (l == 0) {
          const glm::ivec3 q = glm::min(lat0 + glm::ivec3(0, y, z), g.dims - 1);
          const float* src = &orig[linear({0, q.y, q.z}, g.dims)];
          const int real = std::min(ns.x, g.dims.x - lat0.x);
          std::copy(src + lat0.x, src + lat0.x + real, dst);
          std::fill(dst + real, dst + ns.x, src[g.dims.x - 1]);
        } else {
          const float* src = &pyr.data(l)[linear(lat0 + glm::ivec3(0, y, z), pyr.dims(l))];
          std::copy(src, src + ns.x, dst);
        }
      }
    // Stitching. A face sample belongs to the face, edge or corner element given by which of its
    // coordinates are at 0 or m (t = -1 / +1 per axis, 0 inside); its value changes only if a
    // block sharing that element is coarser than this one. Mark those of the 26 kinds first.
    auto kindOf = [](int j, int m_axis) { return j == 0 ? 0 : (j == m_axis ? 2 : 1); };
    bool stitch[27] = {};
    bool any_stitch = false;
    for (int k = 0; k < 27; ++k) {
      const glm::ivec3 t(k % 3 - 1, (k / 3) % 3 - 1, k / 9 - 1);
      for (int o = 1; o < 8; ++o) {  // the other blocks around the element: c + (0 or t) per axis
        glm::ivec3 d((o & 1) ? t.x : 0, (o & 2) ? t.y : 0, (o & 4) ? t.z : 0);
        if (d == glm::ivec3(0)) continue;
        glm::ivec3 q = c + d;
        if (glm::any(glm::lessThan(q, glm::ivec3(0))) ||
            glm::any(glm::greaterThanEqual(q, g.blocks)))
          continue;
        stitch[k] |= out.table[g.id(q)].level > l;
      }
      any_stitch |= stitch[k];
    }
    // Face interiors (most of the samples) a face at a time: the face element's own samples at
    // its level L, then bilinear to this block's lattice, with the arithmetic of skeletonValue()
    // (which found it much slower sample by sample).
    for (int k = 0; any_stitch && k < 27; ++k) {
      const glm::ivec3 t(k % 3 - 1, (k / 3) % 3 - 1, k / 9 - 1);
      if (!stitch[k] || std::abs(t.x) + std::abs(t.y) + std::abs(t.z) != 1) continue;
      const int a = t.x ? 0 : t.y ? 1 : 2, u = a == 0 ? 1 : 0, v = a == 2 ? 1 : 2;  // u < v
      glm::ivec3 face0 = c * g.block_cells;  // level-0 coordinates of the face's first corner
      if (t[a] > 0) face0[a] += g.block_cells[a];
      glm::ivec3 nb = c;
      nb[a] += t[a];
      const int L = std::max(l, out.table[g.id(nb)].level), r = 1 << (L - l);
      const int mu = g.block_cells[u] >> L, mv = g.block_cells[v] >> L;
      thread_local std::vector<double> coarse;
      coarse.resize(size_t(mu + 1) * (mv + 1));
      for (int iv = 0; iv <= mv; ++iv)
        for (int iu = 0; iu <= mu; ++iu) {
          glm::ivec3 p = face0;
          p[u] += iu << L, p[v] += iv << L;
          const bool rim = iu == 0 || iu == mu || iv == 0 || iv == mv;
          coarse[size_t(iu) + size_t(mu + 1) * iv] =
              rim ? skeletonValue(pyr, g, out.table, p) : double(pyr.at(L, p >> L));
        }
      for (int jv = 1; jv < m[v]; ++jv)
        for (int ju = 1; ju < m[u]; ++ju) {
          const int cu = ju / r, cv = jv / r;
          const double fu = double(ju % r) / r, fv = double(jv % r) / r;
          const double* c0 = &coarse[size_t(cu) + size_t(mu + 1) * cv];
          const double* c1 = c0 + (mu + 1);
          // Corners in skeletonValue's order (bit 0: u up, bit 1: v up); a zero weight adds 0.
          double value = 0;
          value += (1 - fu) * (1 - fv) * c0[0];
          value += fu * (1 - fv) * c0[1];
          value += (1 - fu) * fv * c1[0];
          value += fu * fv * c1[1];
          glm::ivec3 j(0);
          j[a] = t[a] > 0 ? m[a] : 0, j[u] = ju, j[v] = jv;
          row(j.y, j.z)[j.x] = float(value);
        }
    }
    // Edges and corners sample by sample.
    if (any_stitch)
      for (int z = 0; z < ns.z; ++z)
        for (int y = 0; y < ns.y; ++y) {
          float* dst = row(y, z);
          const int ky = kindOf(y, m.y), kz = kindOf(z, m.z);
          const int on_yz = (ky != 1) + (kz != 1);
          if (on_yz == 0) {  // only x = 0 and x = m.x could be on an edge: they are not
            continue;
          }
          for (int x = 0; x < ns.x; ++x) {
            const int kx = kindOf(x, m.x);
            if (on_yz + (kx != 1) < 2 || !stitch[kx + 3 * ky + 9 * kz]) continue;
            dst[x] = float(skeletonValue(pyr, g, out.table, (lat0 + glm::ivec3(x, y, z)) << l));
          }
        }
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (int z = 0; z < ns.z; ++z)
      for (int y = 0; y < ns.y; ++y) {
        const float* v = row(y, z);
        for (int x = 0; x < ns.x; ++x) lo = std::min(lo, v[x]), hi = std::max(hi, v[x]);
      }
    blk.vmin = lo, blk.vmax = hi;
  });
  out.timings.pack_s = secondsSince(t0);
  return out;
}

AdaptiveVolume buildAdaptive(const GridGeometry& grid, const std::vector<float>& samples,
                             const AdaptiveOptions& options) {
  // Missing samples (NaN: a NetCDF _FillValue) would spread through the blocks' fits and error
  // bounds; adaptive sampling keeps every block's error within the tolerance, which a hole has none.
  if (std::any_of(samples.begin(), samples.end(), [](float v) { return std::isnan(v); }))
    throw InputError("render.adaptive: the volume has missing samples (its _FillValue or "
                     "missing_value), which adaptive sampling cannot fit: render without it");
  AdaptiveBuilder builder;
  builder.build(grid, samples, options);
  return builder.take();
}

double sampleIndex(const AdaptiveVolume& vol, const glm::dvec3& u) {
  const BlockGrid& g = vol.blocks;
  double x[3];
  glm::ivec3 c;
  for (int a = 0; a < 3; ++a) {
    x[a] = std::clamp(u[a], 0.0, double(g.dims[a] - 1));
    c[a] = std::min(int(x[a] / g.block_cells[a]), g.blocks[a] - 1);
  }
  const AdaptiveBlock& b = vol.table[g.id(c)];
  int i[3];
  double f[3];
  for (int a = 0; a < 3; ++a) {
    const int m = g.block_cells[a] >> b.level;
    double local = std::ldexp(x[a] - double(c[a] * g.block_cells[a]), -b.level);
    i[a] = std::min(int(local), m - 1);
    f[a] = local - i[a];
  }
  const glm::ivec3 d = vol.atlas_dims;
  const glm::ivec3 o = b.atlas_offset + glm::ivec3(i[0], i[1], i[2]);
  auto s = [&](int dx, int dy, int dz) {
    return double(vol.atlas[linear(o + glm::ivec3(dx, dy, dz), d)]);
  };
  return trilinear(s, f);
}

double dataLeft(const AdaptiveVolume& vol) {
  const BlockGrid& g = vol.blocks;
  const glm::dvec3 full(g.blocks * g.block_cells);  // cells of all blocks at full resolution
  double left = 0;
  for (const AdaptiveBlock& b : vol.table) {
    glm::dvec3 m(g.block_cells >> b.level);
    left += m.x * m.y * m.z / (full.x * full.y * full.z);
  }
  return left;
}

AdaptiveSummary summarise(const AdaptiveVolume& vol, const std::vector<float>& original,
                          int threads) {
  const BlockGrid& g = vol.blocks;
  AdaptiveSummary s;
  s.blocks_per_level.assign(size_t(g.max_level) + 1, 0);
  const double n = double(vol.grid.sampleCount());
  s.data_left = dataLeft(vol);
  for (const AdaptiveBlock& b : vol.table) {
    ++s.blocks_per_level[b.level];
    glm::dvec3 m(g.block_cells >> b.level);
    s.stored_fraction += (m.x + 1) * (m.y + 1) * (m.z + 1) / n;
  }
  const glm::ivec3 d = vol.grid.dims;
  if ((long long)original.size() != vol.grid.sampleCount())
    throw InputError("adaptive summary: original has the wrong number of samples");
  std::vector<double> sq(size_t(d.z), 0.0), mx(size_t(d.z), 0.0);
  parallelFor(d.z, resolveThreads(threads), [&](int z) {
    double e2 = 0, e = 0;
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        double diff = sampleIndex(vol, glm::dvec3(x, y, z)) - original[linear({x, y, z}, d)];
        e2 += diff * diff;
        e = std::max(e, std::abs(diff));
      }
    sq[z] = e2, mx[z] = e;
  });
  double total = 0;
  for (int z = 0; z < d.z; ++z) total += sq[z], s.max_error = std::max(s.max_error, mx[z]);
  s.rms_error = std::sqrt(total / n);
  // Per block, over its closed box, as the tolerance is defined.
  std::vector<double> rel(size_t(g.count()), 0.0);
  std::vector<char> over(size_t(g.count()), 0);
  parallelFor(g.count(), resolveThreads(threads), [&](int id) {
    const IndexBox box = realSamplesOf(g, g.cellOf(id));
    double e2 = 0, v2 = 0;
    for (int z = box.lo.z; z <= box.hi.z; ++z)
      for (int y = box.lo.y; y <= box.hi.y; ++y)
        for (int x = box.lo.x; x <= box.hi.x; ++x) {
          const double v = original[linear({x, y, z}, d)];
          const double diff = sampleIndex(vol, glm::dvec3(x, y, z)) - v;
          e2 += diff * diff, v2 += v * v;
        }
    // A little slack: these sums run in another order than the preprocessing's.
    over[id] = e2 > vol.tolerance * vol.tolerance * v2 * (1 + 1e-9);
    rel[id] = v2 > 0 ? std::sqrt(e2 / v2) : (e2 > 0 ? INFINITY : 0.0);
  });
  for (int id = 0; id < g.count(); ++id) {
    s.blocks_over_tolerance += over[id];
    s.worst_block_relative_error = std::max(s.worst_block_relative_error, rel[id]);
  }
  return s;
}

}  // namespace sortlast
