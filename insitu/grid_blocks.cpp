#include "insitu/grid_blocks.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <glm/ext/vector_int3_sized.hpp>

#include "common/error.h"

namespace sortlast {

namespace {

constexpr int kShellTag = 301;

glm::ivec3 ivec(const std::array<int, 3>& a) { return {a[0], a[1], a[2]}; }
glm::dvec3 dvec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

glm::ivec3 ownedDims(const GridBlock& b) { return ivec(b.dims) - ivec(b.ghost_lo) - ivec(b.ghost_hi); }

bool emptyBox(const IndexBox& b) { return b.count() == 0; }

// Element strides of the block's array: as given, or dense x fastest.
glm::i64vec3 stridesOf(const GridBlock& b) {
  if (b.strides[0] == 0 && b.strides[1] == 0 && b.strides[2] == 0)
    return {1, b.dims[0], (long long)b.dims[0] * b.dims[1]};
  return {b.strides[0], b.strides[1], b.strides[2]};
}

int elementBytes(ElementType t) {
  switch (t) {
    case ElementType::kUint8: return 1;
    case ElementType::kUint16:
    case ElementType::kInt16: return 2;
    case ElementType::kFloat32: return 4;
    case ElementType::kFloat64: return 8;
  }
  return 0;
}

// Calls f(global index, value) over `box` (inside the rank's owned box), reading the array in place
// as T. The element type is resolved once per call, not per sample: the range scans of every
// execute() read each published sample about twice, and a switch per sample made them 40 % of
// execute()'s time (perf, the Gray-Scott example at 256^3).
template <class T, class F>
void forOwnedAs(const GridBlock& b, const IndexBox& owned, const IndexBox& box, F&& f) {
  const glm::i64vec3 s = stridesOf(b);
  const auto* base = static_cast<const unsigned char*>(b.data);
  const glm::ivec3 off = ivec(b.ghost_lo) - owned.lo;  // array index = global + off
  const long long step = (long long)sizeof(T) * s.x;
  for (int z = box.lo.z; z <= box.hi.z; ++z)
    for (int y = box.lo.y; y <= box.hi.y; ++y) {
      const unsigned char* p =
          base + (long long)sizeof(T) * ((long long)(y + off.y) * s.y + (long long)(z + off.z) * s.z +
                                         (long long)(box.lo.x + off.x) * s.x);
      for (int x = box.lo.x; x <= box.hi.x; ++x, p += step) {
        T v;
        std::memcpy(&v, p, sizeof v);  // the array need not be aligned for T
        f(glm::ivec3(x, y, z), float(v));
      }
    }
}

template <class F>
void forOwned(const GridBlock& b, const IndexBox& owned, const IndexBox& box, F&& f) {
  switch (b.type) {
    case ElementType::kUint8: return forOwnedAs<uint8_t>(b, owned, box, f);
    case ElementType::kUint16: return forOwnedAs<uint16_t>(b, owned, box, f);
    case ElementType::kInt16: return forOwnedAs<int16_t>(b, owned, box, f);
    case ElementType::kFloat32: return forOwnedAs<float>(b, owned, box, f);
    case ElementType::kFloat64: return forOwnedAs<double>(b, owned, box, f);
  }
}

std::string boxText(const IndexBox& b) {
  char t[160];
  std::snprintf(t, sizeof t, "[%d..%d] x [%d..%d] x [%d..%d]", b.lo.x, b.hi.x, b.lo.y, b.hi.y, b.lo.z, b.hi.z);
  return t;
}

}  // namespace

bool GridLayout::hasCells(int rank) const {
  const Brick& b = bricks[size_t(rank)];
  return b.domain.count() > 0 && glm::all(glm::greaterThan(b.domain.hi, b.domain.lo));
}

GridLayout gatherGridLayout(const GridBlock& mine, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const glm::ivec3 od = ownedDims(mine);
  const bool has = mine.dims[0] > 0 || mine.dims[1] > 0 || mine.dims[2] > 0;
  // Local checks first, so every rank's message names its own problem.
  std::string problem;
  if (has) {
    for (int a = 0; a < 3; ++a)
      if (mine.dims[a] < 1 || mine.ghost_lo[a] < 0 || mine.ghost_hi[a] < 0 || od[a] < 1)
        problem = "its block's dims and ghost layers leave no owned sample along an axis";
    if (!mine.data) problem = "its block has dims but a null data pointer";
    for (int a = 0; a < 3; ++a)
      if (!(mine.spacing[a] > 0.0) || !std::isfinite(mine.spacing[a]) || !std::isfinite(mine.origin[a]))
        problem = "its block's spacing must be finite and > 0 and its origin finite";
  }
  // Everything every rank needs to place every block: has, origin, spacing, owned dims.
  double msg[10] = {has && problem.empty() ? 1.0 : 0.0, mine.origin[0], mine.origin[1], mine.origin[2],
                    mine.spacing[0], mine.spacing[1], mine.spacing[2], double(od.x), double(od.y), double(od.z)};
  std::vector<double> all(size_t(size) * 10);
  MPI_Allgather(msg, 10, MPI_DOUBLE, all.data(), 10, MPI_DOUBLE, comm);
  if (!problem.empty()) throw InputError("rank " + std::to_string(rank) + ": " + problem);
  auto at = [&](int r, int i) { return all[size_t(r) * 10 + size_t(i)]; };
  GridLayout L;
  int first = -1;
  glm::dvec3 origin(std::numeric_limits<double>::infinity());
  for (int r = 0; r < size; ++r)
    if (at(r, 0) != 0.0) {
      if (first < 0) first = r;
      for (int a = 0; a < 3; ++a) origin[a] = std::min(origin[a], at(r, 1 + a));
    }
  if (first < 0) throw InputError("no rank published a grid block with samples");
  const glm::dvec3 spacing(at(first, 4), at(first, 5), at(first, 6));
  L.owned.assign(size_t(size), IndexBox{});
  glm::ivec3 dims(0);
  long long total = 0;
  for (int r = 0; r < size; ++r) {
    if (at(r, 0) == 0.0) continue;
    for (int a = 0; a < 3; ++a) {
      if (std::abs(at(r, 4 + a) - spacing[a]) > 1e-9 * spacing[a])
        throw InputError("rank " + std::to_string(r) + "'s grid spacing differs from rank " +
                         std::to_string(first) + "'s: every block must have the same spacing");
      double k = (at(r, 1 + a) - origin[a]) / spacing[a];
      if (std::abs(k - std::round(k)) > 1e-6)
        throw InputError("rank " + std::to_string(r) + "'s block origin is not on the grid of the others "
                         "(origin minus the smallest origin is not a whole number of spacings)");
      L.owned[size_t(r)].lo[a] = int(std::lround(k));
      L.owned[size_t(r)].hi[a] = L.owned[size_t(r)].lo[a] + int(at(r, 7 + a)) - 1;
    }
    dims = glm::max(dims, L.owned[size_t(r)].hi + 1);
    total += L.owned[size_t(r)].count();
  }
  for (int r = 0; r < size; ++r)
    for (int q = r + 1; q < size; ++q)
      if (!emptyBox(L.owned[size_t(r)]) && !emptyBox(L.owned[size_t(q)]) &&
          intersect(L.owned[size_t(r)], L.owned[size_t(q)]).count() > 0)
        throw InputError("the blocks of ranks " + std::to_string(r) + " and " + std::to_string(q) +
                         " overlap in their owned samples (" + boxText(intersect(L.owned[size_t(r)], L.owned[size_t(q)])) +
                         "): declare shared samples as ghost layers");
  if (total != 1LL * dims.x * dims.y * dims.z)
    throw InputError("the blocks do not tile a grid: they hold " + std::to_string(total) + " samples, their bounding grid " +
                     std::to_string(dims.x) + " x " + std::to_string(dims.y) + " x " + std::to_string(dims.z) +
                     " has " + std::to_string(1LL * dims.x * dims.y * dims.z) + " (a gap between blocks?)");
  if (glm::any(glm::lessThan(dims, glm::ivec3(2))))
    throw InputError("the grid must have at least 2 samples along every axis");
  L.grid.dims = dims;
  L.grid.spacing = spacing;
  L.shift = origin + 0.5 * glm::dvec3(dims - 1) * spacing;
  for (int r = 0; r < size; ++r) {
    Brick b;
    b.id = r;
    const IndexBox& o = L.owned[size_t(r)];
    if (!emptyBox(o)) {
      // Cells from the first owned sample to the upper neighbours' first; a ghost where the grid goes on.
      b.domain = {o.lo, glm::min(o.hi + 1, dims - 1)};
      b.stored = {glm::max(b.domain.lo - 1, glm::ivec3(0)), glm::min(b.domain.hi + 1, dims - 1)};
      b.world = L.grid.worldBoxOf(b.domain);
    } else {
      b.world = noBox();
    }
    L.bricks.push_back(b);
  }
  return L;
}

std::pair<double, double> ownedRange(const GridBlock& mine, const GridLayout& layout, int rank) {
  const IndexBox& o = layout.owned[size_t(rank)];
  double lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  if (emptyBox(o)) return {lo, hi};
  // The first non-finite sample is noted and the scan goes on: a throw inside the loop's lambda
  // kept it from being inlined (half the scan's time).
  bool bad = false;
  glm::ivec3 at(0);
  float bad_value = 0.0f;
  forOwned(mine, o, o, [&](const glm::ivec3& g, float v) {
    if (!std::isfinite(v)) {
      if (!bad) bad = true, at = g, bad_value = v;
      return;
    }
    lo = std::min(lo, double(v));
    hi = std::max(hi, double(v));
  });
  if (bad)
    throw InputError("rank " + std::to_string(rank) + ": the published field '" + mine.name + "' holds " +
                     (std::isnan(bad_value) ? "NaN" : "an infinite value") + " at global sample (" +
                     std::to_string(at.x) + ", " + std::to_string(at.y) + ", " + std::to_string(at.z) + ")");
  return {lo, hi};
}

SimulationSamples::SimulationSamples(const GridBlock& mine, const GridLayout& layout, MPI_Comm comm)
    : block_(mine) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  owned_ = layout.owned[size_t(rank)];
  // What each rank's brick needs of every other rank's block: its stored box cut by their block.
  std::vector<std::vector<float>> outgoing;
  std::vector<MPI_Request> requests;
  for (int q = 0; q < size; ++q) {
    if (q == rank || !layout.hasCells(q) || emptyBox(owned_)) continue;
    IndexBox cut = intersect(layout.bricks[size_t(q)].stored, owned_);
    if (emptyBox(cut)) continue;
    outgoing.emplace_back();
    outgoing.back().reserve(size_t(cut.count()));
    forOwned(mine, owned_, cut, [&](const glm::ivec3&, float v) { outgoing.back().push_back(v); });
    requests.emplace_back();
    MPI_Isend(outgoing.back().data(), int(outgoing.back().size()), MPI_FLOAT, q, kShellTag, comm, &requests.back());
  }
  if (layout.hasCells(rank)) {
    const IndexBox& stored = layout.bricks[size_t(rank)].stored;
    for (int r = 0; r < size; ++r) {
      if (r == rank || emptyBox(layout.owned[size_t(r)])) continue;
      IndexBox cut = intersect(stored, layout.owned[size_t(r)]);
      if (emptyBox(cut)) continue;
      shell_.push_back({cut, std::vector<float>(size_t(cut.count()))});
      requests.emplace_back();
      MPI_Irecv(shell_.back().values.data(), int(cut.count()), MPI_FLOAT, r, kShellTag, comm, &requests.back());
    }
  }
  MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
}

std::pair<float, float> SimulationSamples::range(const IndexBox& box) const {
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  IndexBox own = intersect(box, owned_);
  if (!emptyBox(own))
    forOwned(block_, owned_, own, [&](const glm::ivec3&, float v) { lo = std::min(lo, v), hi = std::max(hi, v); });
  for (const Piece& p : shell_) {
    IndexBox cut = intersect(box, p.box);
    if (emptyBox(cut)) continue;
    const glm::ivec3 n = p.box.size();
    for (int z = cut.lo.z; z <= cut.hi.z; ++z)
      for (int y = cut.lo.y; y <= cut.hi.y; ++y)
        for (int x = cut.lo.x; x <= cut.hi.x; ++x) {
          float v = p.values[size_t(x - p.box.lo.x) + size_t(n.x) * (size_t(y - p.box.lo.y) + size_t(n.y) * (z - p.box.lo.z))];
          lo = std::min(lo, v), hi = std::max(hi, v);
        }
  }
  return {lo, hi};
}

void SimulationSamples::upload(const GlApi& gl, const IndexBox& stored) const {
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  IndexBox own = intersect(stored, owned_);
  if (!emptyBox(own)) {
    const glm::ivec3 n = own.size(), at = own.lo - stored.lo;
    const glm::i64vec3 s = stridesOf(block_);
    if (block_.type == ElementType::kFloat32 && s.x == 1 && s.y > 0 && s.z % s.y == 0) {
      // Straight from the simulation's array: GL walks its rows and slices by the unpack lengths.
      const glm::ivec3 a = own.lo - owned_.lo + ivec(block_.ghost_lo);
      const float* first = static_cast<const float*>(block_.data) + (a.x + a.y * s.y + a.z * s.z);
      gl.PixelStorei(GL_UNPACK_ROW_LENGTH, int(s.y));
      gl.PixelStorei(GL_UNPACK_IMAGE_HEIGHT, int(s.z / s.y));
      gl.TexSubImage3D(GL_TEXTURE_3D, 0, at.x, at.y, at.z, n.x, n.y, n.z, GL_RED, GL_FLOAT, first);
      gl.PixelStorei(GL_UNPACK_ROW_LENGTH, 0);
      gl.PixelStorei(GL_UNPACK_IMAGE_HEIGHT, 0);
    } else {
      // Other types and layouts: converted to float a few slices at a time (about 4 MiB).
      const long long slice = 1LL * n.x * n.y;
      const int slices = int(std::max(1LL, (4LL << 20) / (4 * slice)));
      std::vector<float> chunk(size_t(slice) * size_t(std::min(slices, n.z)));
      chunk_bytes_ = std::max(chunk_bytes_, chunk.size() * sizeof(float));
      for (int z0 = own.lo.z; z0 <= own.hi.z; z0 += slices) {
        IndexBox part{{own.lo.x, own.lo.y, z0}, {own.hi.x, own.hi.y, std::min(own.hi.z, z0 + slices - 1)}};
        size_t i = 0;
        forOwned(block_, owned_, part, [&](const glm::ivec3&, float v) { chunk[i++] = v; });
        gl.TexSubImage3D(GL_TEXTURE_3D, 0, at.x, at.y, z0 - stored.lo.z, n.x, n.y, part.size().z, GL_RED,
                         GL_FLOAT, chunk.data());
      }
    }
  }
  for (const Piece& p : shell_) {
    const glm::ivec3 n = p.box.size(), at = p.box.lo - stored.lo;
    gl.TexSubImage3D(GL_TEXTURE_3D, 0, at.x, at.y, at.z, n.x, n.y, n.z, GL_RED, GL_FLOAT, p.values.data());
  }
}

std::vector<float> SimulationSamples::read(const IndexBox& stored) const {
  std::vector<float> out(size_t(stored.count()), std::numeric_limits<float>::quiet_NaN());
  const glm::ivec3 n = stored.size();
  auto at = [&](const glm::ivec3& g) -> float& {
    return out[size_t(g.x - stored.lo.x) + size_t(n.x) * (size_t(g.y - stored.lo.y) + size_t(n.y) * size_t(g.z - stored.lo.z))];
  };
  const IndexBox own = intersect(stored, owned_);
  if (!emptyBox(own)) forOwned(block_, owned_, own, [&](const glm::ivec3& g, float v) { at(g) = v; });
  for (const Piece& p : shell_) {
    const IndexBox cut = intersect(stored, p.box);
    if (emptyBox(cut)) continue;
    const glm::ivec3 m = p.box.size();
    for (int z = cut.lo.z; z <= cut.hi.z; ++z)
      for (int y = cut.lo.y; y <= cut.hi.y; ++y)
        for (int x = cut.lo.x; x <= cut.hi.x; ++x)
          at({x, y, z}) = p.values[size_t(x - p.box.lo.x) + size_t(m.x) * (size_t(y - p.box.lo.y) + size_t(m.y) * size_t(z - p.box.lo.z))];
  }
  return out;
}

double SimulationSamples::bytesHeld() const {
  double bytes = double(chunk_bytes_);
  for (const Piece& p : shell_) bytes += double(p.values.size()) * sizeof(float);
  return bytes;
}

}  // namespace sortlast
