#include "gray_scott.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace {

// Deterministic noise in [0, 1) from a sample's global index, so every decomposition starts from
// the same state (and computes the same numbers).
double noise(long long global_index, int field) {
  uint64_t z = uint64_t(global_index) * 2 + uint64_t(field) + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return double(z >> 11) * 0x1.0p-53;
}

}  // namespace

GrayScott::GrayScott(const GrayScottParams& p, MPI_Comm comm) : p_(p) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  int dims[3] = {0, 0, 0}, periods[3] = {1, 1, 1};
  MPI_Dims_create(size, 3, dims);
  for (int a = 0; a < 3; ++a)
    if (dims[a] > p.n)
      throw std::invalid_argument("--size " + std::to_string(p.n) + " is too small for " +
                                  std::to_string(size) + " ranks (" + std::to_string(dims[a]) +
                                  " along one axis)");
  MPI_Cart_create(comm, 3, dims, periods, 0, &cart_);
  int rank = 0;
  MPI_Comm_rank(cart_, &rank);
  MPI_Cart_coords(cart_, rank, 3, coords_.data());
  for (int a = 0; a < 3; ++a) {
    procs_[a] = dims[a];
    // Uneven splits: the first n % procs ranks along the axis get one sample more.
    const int base = p.n / dims[a], extra = p.n % dims[a];
    owned_[a] = base + (coords_[a] < extra ? 1 : 0);
    offset_[a] = coords_[a] * base + std::min(coords_[a], extra);
    MPI_Cart_shift(cart_, a, 1, &neighbours_[a][0], &neighbours_[a][1]);
  }
  sx_ = owned_[0] + 2, sy_ = owned_[1] + 2, sz_ = owned_[2] + 2;
  const size_t count = size_t(sx_) * size_t(sy_) * size_t(sz_);
  u_.assign(count, 1.0), v_.assign(count, 0.0), u2_ = u_, v2_ = v_;

  // Faces of the array (ghosts included along the other axes, so edges and corners fill too).
  const int sizes[3] = {sx_, sy_, sz_};
  for (int a = 0; a < 3; ++a) {
    const int at[4] = {1, owned_[a], 0, owned_[a] + 1};
    for (int f = 0; f < 4; ++f) {
      int sub[3] = {sx_, sy_, sz_}, start[3] = {0, 0, 0};
      sub[a] = 1, start[a] = at[f];
      MPI_Type_create_subarray(3, sizes, sub, start, MPI_ORDER_FORTRAN, MPI_DOUBLE, &faces_[a][f]);
      MPI_Type_commit(&faces_[a][f]);
    }
  }

  // U = 1, V = 0, but for a seeded cube in the middle (U = 0.25, V = 0.33, as in the classic
  // setups); noise on U everywhere and on V in the cube bends the fronts a little off the cube's
  // symmetry.
  const int lo = p.n / 2 - std::max(2, p.n / 10), hi = p.n / 2 + std::max(2, p.n / 10);
  for (int z = 1; z <= owned_[2]; ++z)
    for (int y = 1; y <= owned_[1]; ++y)
      for (int x = 1; x <= owned_[0]; ++x) {
        const int g[3] = {offset_[0] + x - 1, offset_[1] + y - 1, offset_[2] + z - 1};
        const long long gi = g[0] + (long long)p.n * (g[1] + (long long)p.n * g[2]);
        const long long i = index(x, y, z);
        u_[i] = 1.0 - 0.1 * noise(gi, 0);
        bool seeded = true;
        for (int a = 0; a < 3; ++a) seeded = seeded && g[a] >= lo && g[a] < hi;
        if (seeded) {
          u_[i] = 0.25 + 0.1 * (noise(gi, 0) - 0.5);
          v_[i] = 0.33 + 0.3 * (noise(gi, 1) - 0.5);
        }
      }
  exchange(u_);
  exchange(v_);
}

GrayScott::~GrayScott() {
  for (auto& axis : faces_)
    for (MPI_Datatype& t : axis)
      if (t != MPI_DATATYPE_NULL) MPI_Type_free(&t);
  if (cart_ != MPI_COMM_NULL) MPI_Comm_free(&cart_);
}

void GrayScott::exchange(std::vector<double>& a) {
  for (int axis = 0; axis < 3; ++axis) {
    const int lower = neighbours_[axis][0], upper = neighbours_[axis][1];
    // First owned layer down, the upper neighbour's into the high ghost; then the other way.
    MPI_Sendrecv(a.data(), 1, faces_[axis][0], lower, 2 * axis, a.data(), 1, faces_[axis][3], upper,
                 2 * axis, cart_, MPI_STATUS_IGNORE);
    MPI_Sendrecv(a.data(), 1, faces_[axis][1], upper, 2 * axis + 1, a.data(), 1, faces_[axis][2],
                 lower, 2 * axis + 1, cart_, MPI_STATUS_IGNORE);
  }
}

void GrayScott::step() {
  const long long dy = sx_, dz = (long long)sx_ * sy_;
  const double F = p_.F, k = p_.k, Du = p_.Du, Dv = p_.Dv, dt = p_.dt;
  const double* u = u_.data();
  const double* v = v_.data();
  for (int z = 1; z <= owned_[2]; ++z)
    for (int y = 1; y <= owned_[1]; ++y) {
      const long long row = index(0, y, z);
      for (long long i = row + 1; i <= row + owned_[0]; ++i) {
        const double lu =
            (u[i - 1] + u[i + 1] + u[i - dy] + u[i + dy] + u[i - dz] + u[i + dz]) / 6.0 - u[i];
        const double lv =
            (v[i - 1] + v[i + 1] + v[i - dy] + v[i + dy] + v[i - dz] + v[i + dz]) / 6.0 - v[i];
        const double uvv = u[i] * v[i] * v[i];
        u2_[i] = u[i] + dt * (Du * lu - uvv + F * (1.0 - u[i]));
        v2_[i] = v[i] + dt * (Dv * lv + uvv - (F + k) * v[i]);
      }
    }
  u_.swap(u2_);
  v_.swap(v2_);
  exchange(u_);
  exchange(v_);
}

std::vector<float> GrayScott::gatherV() const {
  int rank = 0, size = 1;
  MPI_Comm_rank(cart_, &rank);
  MPI_Comm_size(cart_, &size);
  std::vector<float> mine;
  mine.reserve(size_t(owned_[0]) * owned_[1] * owned_[2]);
  for (int z = 1; z <= owned_[2]; ++z)
    for (int y = 1; y <= owned_[1]; ++y)
      for (int x = 1; x <= owned_[0]; ++x) mine.push_back(float(v_[index(x, y, z)]));
  const int box[6] = {offset_[0], offset_[1], offset_[2], owned_[0], owned_[1], owned_[2]};
  std::vector<int> boxes(static_cast<size_t>(size) * 6), counts(static_cast<size_t>(size)),
      displs(counts);
  MPI_Gather(box, 6, MPI_INT, boxes.data(), 6, MPI_INT, 0, cart_);
  int total = 0;
  for (int r = 0; r < size; ++r) {
    counts[r] = boxes[6 * r + 3] * boxes[6 * r + 4] * boxes[6 * r + 5];
    displs[r] = total;
    total += counts[r];
  }
  std::vector<float> all(rank == 0 ? size_t(total) : 0);
  MPI_Gatherv(mine.data(), int(mine.size()), MPI_FLOAT, all.data(), counts.data(), displs.data(),
              MPI_FLOAT, 0, cart_);
  if (rank != 0) return {};
  const long long n = p_.n;
  std::vector<float> grid(size_t(n * n * n));
  for (int r = 0; r < size; ++r) {
    const int* b = &boxes[6 * r];
    const float* src = all.data() + displs[r];
    for (int z = 0; z < b[5]; ++z)
      for (int y = 0; y < b[4]; ++y)
        for (int x = 0; x < b[3]; ++x)
          grid[size_t(b[0] + x + n * (b[1] + y + n * (b[2] + z)))] = *src++;
  }
  return grid;
}
