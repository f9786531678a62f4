#include "particle_sim.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace {

constexpr double kContact = 1.0;  // particles closer than one spacing push each other apart
constexpr int kFields = 6;        // x, y, z, vx, vy, vz per particle in every message

// Deterministic jitter in [-0.5, 0.5) per particle and axis: breaks the lattice's symmetry the
// same way on every rank count.
double jitter(long long i, int axis) {
  uint64_t z = uint64_t(i) * 3 + uint64_t(axis) + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return double(z >> 11) * 0x1.0p-53 - 0.5;
}

}  // namespace

ParticleSim::ParticleSim(const ParticleParams& p, MPI_Comm comm) : p_(p), comm_(comm) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &size_);
  if (p.count < 16) throw std::invalid_argument("--particles must be at least 16");
  // A square pool m x m holding about 60% of the particles, the rest in a cube above its middle,
  // dropped from a third of the pool's width above the surface.
  const long long m = std::max(4LL, std::llround(std::cbrt(2.0 * double(p.count))));
  const long long layers = std::max(1LL, (p.count * 3 / 5) / (m * m));
  const long long pool = std::min(p.count, layers * m * m), block = p.count - pool;
  const long long c = std::max(1LL, (long long)std::ceil(std::cbrt(double(block)) - 1e-9));
  const double block_x = 0.5 * double(m - c), block_y = double(layers) + 0.6 * double(m);
  drop_top_ = block_y + double((block + c * c - 1) / (c * c));
  box_[0] = box_[2] = double(m);
  box_[1] = drop_top_ + 1.0;
  if (box_[0] / size_ < kContact)
    throw std::invalid_argument("too many ranks for " + std::to_string(p.count) +
                                " particles: each slab must be at least one spacing wide");
  slab_lo_ = box_[0] * rank_ / size_;
  slab_hi_ = box_[0] * (rank_ + 1) / size_;
  for (long long i = 0; i < p.count; ++i) {
    double pos[3];
    if (i < pool) {  // x fastest, then z, then the layers upwards
      pos[0] = 0.5 + double(i % m), pos[2] = 0.5 + double((i / m) % m),
      pos[1] = 0.5 + double(i / (m * m));
    } else {
      const long long b = i - pool;
      pos[0] = block_x + 0.5 + double(b % c), pos[2] = block_x + 0.5 + double((b / c) % c);
      pos[1] = block_y + 0.5 + double(b / (c * c));
    }
    for (int a = 0; a < 3; ++a) pos[a] += 0.05 * jitter(i, a);
    if (ownerOf(pos[0]) != rank_) continue;
    x_.push_back(pos[0]), y_.push_back(pos[1]), z_.push_back(pos[2]);
    vx_.push_back(0.0), vy_.push_back(0.0), vz_.push_back(0.0);
  }
}

int ParticleSim::ownerOf(double x) const {
  return std::clamp(int(std::floor(x / box_[0] * size_)), 0, size_ - 1);
}

void ParticleSim::step() {
  exchangeGhosts();
  std::vector<double> fx, fy, fz;
  forces(fx, fy, fz);
  // Symplectic Euler, then walls, floor and ceiling half a spacing in (the particles' radius).
  const double dt = p_.dt, e = p_.restitution;
  std::array<std::vector<double>*, 3> pos{&x_, &y_, &z_}, vel{&vx_, &vy_, &vz_};
  for (size_t i = 0; i < x_.size(); ++i) {
    vx_[i] += dt * fx[i];
    vy_[i] += dt * (fy[i] - p_.gravity);
    vz_[i] += dt * fz[i];
    for (int a = 0; a < 3; ++a) {
      double& q = (*pos[a])[i];
      double& v = (*vel[a])[i];
      q += dt * v;
      if (q < 0.5) {
        q = 0.5;
        if (v < 0) v = -e * v;
      } else if (q > box_[a] - 0.5) {
        q = box_[a] - 0.5;
        if (v > 0) v = -e * v;
      }
    }
  }
  migrate();
}

void ParticleSim::exchangeGhosts() {
  gx_.clear(), gy_.clear(), gz_.clear(), gvx_.clear(), gvy_.clear(), gvz_.clear();
  const int lower = rank_ > 0 ? rank_ - 1 : MPI_PROC_NULL;
  const int upper = rank_ + 1 < size_ ? rank_ + 1 : MPI_PROC_NULL;
  // Those within one contact distance of a slab face, to the neighbour behind it.
  for (int side = 0; side < 2; ++side) {
    const int to = side == 0 ? lower : upper, from = side == 0 ? upper : lower;
    std::vector<double> out, in;
    for (size_t i = 0; i < x_.size(); ++i)
      if (to != MPI_PROC_NULL &&
          (side == 0 ? x_[i] < slab_lo_ + kContact : x_[i] >= slab_hi_ - kContact))
        out.insert(out.end(), {x_[i], y_[i], z_[i], vx_[i], vy_[i], vz_[i]});
    int n_out = int(out.size()), n_in = 0;
    MPI_Sendrecv(&n_out, 1, MPI_INT, to, 10 + side, &n_in, 1, MPI_INT, from, 10 + side, comm_,
                 MPI_STATUS_IGNORE);
    in.resize(size_t(n_in));
    MPI_Sendrecv(out.data(), n_out, MPI_DOUBLE, to, 20 + side, in.data(), n_in, MPI_DOUBLE, from,
                 20 + side, comm_, MPI_STATUS_IGNORE);
    for (size_t k = 0; k < in.size(); k += kFields) {
      gx_.push_back(in[k]), gy_.push_back(in[k + 1]), gz_.push_back(in[k + 2]);
      gvx_.push_back(in[k + 3]), gvy_.push_back(in[k + 4]), gvz_.push_back(in[k + 5]);
    }
  }
}

void ParticleSim::forces(std::vector<double>& fx, std::vector<double>& fy,
                         std::vector<double>& fz) const {
  const size_t n = x_.size(), all = n + gx_.size();
  auto X = [&](size_t i) { return i < n ? x_[i] : gx_[i - n]; };
  auto Y = [&](size_t i) { return i < n ? y_[i] : gy_[i - n]; };
  auto Z = [&](size_t i) { return i < n ? z_[i] : gz_[i - n]; };
  auto VX = [&](size_t i) { return i < n ? vx_[i] : gvx_[i - n]; };
  auto VY = [&](size_t i) { return i < n ? vy_[i] : gvy_[i - n]; };
  auto VZ = [&](size_t i) { return i < n ? vz_[i] : gvz_[i - n]; };
  // Cell list: cells one contact distance wide over the slab and one cell beyond each face.
  const double x0 = slab_lo_ - kContact;
  const int cx = int(std::ceil((slab_hi_ - x0 + kContact) / kContact)) + 1;
  const int cy = int(std::ceil(box_[1] / kContact)) + 1,
            cz = int(std::ceil(box_[2] / kContact)) + 1;
  auto cellOf = [&](size_t i, int& ix, int& iy, int& iz) {
    ix = std::clamp(int((X(i) - x0) / kContact), 0, cx - 1);
    iy = std::clamp(int(Y(i) / kContact), 0, cy - 1);
    iz = std::clamp(int(Z(i) / kContact), 0, cz - 1);
    return ix + cx * (iy + cy * iz);
  };
  std::vector<int> start(size_t(cx) * cy * cz + 1, 0), sorted(all), cell(all);
  for (size_t i = 0; i < all; ++i) {
    int a, b, c;
    cell[i] = cellOf(i, a, b, c);
    ++start[size_t(cell[i]) + 1];
  }
  for (size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (size_t i = 0; i < all; ++i) sorted[size_t(fill[size_t(cell[i])]++)] = int(i);

  fx.assign(n, 0.0), fy.assign(n, 0.0), fz.assign(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    int ix, iy, iz;
    cellOf(i, ix, iy, iz);
    for (int dz = std::max(0, iz - 1); dz <= std::min(cz - 1, iz + 1); ++dz)
      for (int dy = std::max(0, iy - 1); dy <= std::min(cy - 1, iy + 1); ++dy)
        for (int dx = std::max(0, ix - 1); dx <= std::min(cx - 1, ix + 1); ++dx) {
          const int c = dx + cx * (dy + cy * dz);
          for (int s = start[size_t(c)]; s < start[size_t(c) + 1]; ++s) {
            const size_t j = size_t(sorted[size_t(s)]);
            if (j == i) continue;
            const double rx = x_[i] - X(j), ry = y_[i] - Y(j), rz = z_[i] - Z(j);
            const double r2 = rx * rx + ry * ry + rz * rz;
            if (r2 >= kContact * kContact || r2 < 1e-12) continue;
            // Spring on the overlap minus a dashpot on the approach speed, never pulling.
            const double r = std::sqrt(r2), nx = rx / r, ny = ry / r, nz = rz / r;
            const double vn = (vx_[i] - VX(j)) * nx + (vy_[i] - VY(j)) * ny + (vz_[i] - VZ(j)) * nz;
            const double f = std::max(0.0, p_.stiffness * (kContact - r) - p_.damping * vn);
            fx[i] += f * nx, fy[i] += f * ny, fz[i] += f * nz;
          }
        }
  }
}

void ParticleSim::migrate() {
  std::vector<std::vector<double>> out(static_cast<size_t>(size_));
  size_t kept = 0;
  for (size_t i = 0; i < x_.size(); ++i) {
    const int o = ownerOf(x_[i]);
    if (o == rank_) {
      x_[kept] = x_[i], y_[kept] = y_[i], z_[kept] = z_[i];
      vx_[kept] = vx_[i], vy_[kept] = vy_[i], vz_[kept] = vz_[i];
      ++kept;
    } else {
      out[size_t(o)].insert(out[size_t(o)].end(), {x_[i], y_[i], z_[i], vx_[i], vy_[i], vz_[i]});
    }
  }
  for (auto* v : {&x_, &y_, &z_, &vx_, &vy_, &vz_}) v->resize(kept);
  std::vector<int> send_n(static_cast<size_t>(size_)), recv_n(static_cast<size_t>(size_)),
      send_at(static_cast<size_t>(size_)), recv_at(static_cast<size_t>(size_));
  std::vector<double> send;
  for (int r = 0; r < size_; ++r) {
    send_at[size_t(r)] = int(send.size());
    send_n[size_t(r)] = int(out[size_t(r)].size());
    send.insert(send.end(), out[size_t(r)].begin(), out[size_t(r)].end());
  }
  MPI_Alltoall(send_n.data(), 1, MPI_INT, recv_n.data(), 1, MPI_INT, comm_);
  int total = 0;
  for (int r = 0; r < size_; ++r) recv_at[size_t(r)] = total, total += recv_n[size_t(r)];
  std::vector<double> in(static_cast<size_t>(total));
  MPI_Alltoallv(send.data(), send_n.data(), send_at.data(), MPI_DOUBLE, in.data(), recv_n.data(),
                recv_at.data(), MPI_DOUBLE, comm_);
  for (size_t k = 0; k < in.size(); k += kFields) {
    x_.push_back(in[k]), y_.push_back(in[k + 1]), z_.push_back(in[k + 2]);
    vx_.push_back(in[k + 3]), vy_.push_back(in[k + 4]), vz_.push_back(in[k + 5]);
  }
}

std::vector<float> ParticleSim::gather() const {
  std::vector<float> mine;
  mine.reserve(3 * x_.size());
  for (size_t i = 0; i < x_.size(); ++i)
    mine.insert(mine.end(), {float(x_[i]), float(y_[i]), float(z_[i])});
  int n = int(mine.size());
  std::vector<int> counts(static_cast<size_t>(size_)), displs(static_cast<size_t>(size_));
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm_);
  int total = 0;
  for (int r = 0; r < size_; ++r) displs[size_t(r)] = total, total += counts[size_t(r)];
  std::vector<float> all(rank_ == 0 ? size_t(total) : 0);
  MPI_Gatherv(mine.data(), n, MPI_FLOAT, all.data(), counts.data(), displs.data(), MPI_FLOAT, 0,
              comm_);
  return all;
}
