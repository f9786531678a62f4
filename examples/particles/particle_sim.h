#pragma once
// A block of particles dropped into a pool, in a box: gravity along -y, soft pairwise repulsion
// with a dashpot between particles closer than one spacing (a cell list finds them), walls and
// floor that reflect with damping. Units: the initial spacing is 1, the mass 1.
//
// Distributed by slabs along x: rank r owns the particles with x in [r, r + 1) * width / ranks.
// Every step each rank fetches copies of its neighbours' particles within one spacing of its slab
// (ghosts), moves its own, and hands those that left its slab to their new owner.
#include <mpi.h>

#include <vector>

struct ParticleParams {
  long long count = 8000;    // particles in all
  double gravity = 2.0;      // acceleration along -y
  double stiffness = 100.0;  // repulsion per unit of overlap
  double damping = 1.5;      // dashpot on the approach speed (about 0.1 of critical)
  double restitution = 0.5;  // walls and floor: share of the normal speed kept
  double dt = 0.025;
};

class ParticleSim {
 public:
  ParticleSim(const ParticleParams& p, MPI_Comm comm);  // collective; deterministic initial state
  void step();                                          // collective

  // This rank's particles (positions; stride 1).
  const std::vector<double>& x() const { return x_; }
  const std::vector<double>& y() const { return y_; }
  const std::vector<double>& z() const { return z_; }
  long long count() const { return (long long)x_.size(); }
  // The box the particles live in: [0, size[0]] x [0, size[1]] x [0, size[2]].
  const double* box() const { return box_; }
  double dropTop() const { return drop_top_; }  // top of the falling block at the start

  // Collective: every particle as float32 x, y, z triples on rank 0, rank after rank, then in each
  // rank's own order (the order sortlast sums them in); empty elsewhere.
  std::vector<float> gather() const;

 private:
  void exchangeGhosts();
  void forces(std::vector<double>& fx, std::vector<double>& fy, std::vector<double>& fz) const;
  void migrate();
  int ownerOf(double x) const;

  ParticleParams p_;
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  double box_[3] = {0, 0, 0}, slab_lo_ = 0, slab_hi_ = 0, drop_top_ = 0;
  std::vector<double> x_, y_, z_, vx_, vy_, vz_;        // owned
  std::vector<double> gx_, gy_, gz_, gvx_, gvy_, gvz_;  // ghosts (neighbours' copies)
};
