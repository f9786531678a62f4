#pragma once
// A 3D Gray-Scott reaction-diffusion on an MPI Cartesian decomposition:
//   dU/dt = Du lap(U) - U V^2 + F (1 - U)
//   dV/dt = Dv lap(V) + U V^2 - (F + k) V
// forward Euler with dt = 1; lap is the mean of the six neighbours minus the centre (the 7-point
// stencil over 6, as in the ADIOS2 Gray-Scott tutorial). With the plain stencil, Du = 0.16 and
// dt = 1 sit on the explicit stability limit (the checkerboard mode's factor 1 - 12 Du dt - F - V^2
// passes -1 where the reaction runs) and U grows a checkerboard that then drives the pattern.
// F = 0.022, k = 0.051: a front that fills the domain with a labyrinth of sheets (F = 0.04,
// k = 0.06 settles into one stable spot). PERIODIC boundaries: the Cartesian communicator wraps
// around, so the halo exchange is the boundary condition too.
// Each rank holds its block of the global N^3 grid (uneven where N does not divide) with ONE ghost
// layer on every face, x fastest; after every step the ghosts hold the neighbours' current values.
#include <mpi.h>

#include <array>
#include <vector>

struct GrayScottParams {
  int n = 64;  // global samples per axis
  double F = 0.022, k = 0.051, Du = 0.16, Dv = 0.08, dt = 1.0;
};

class GrayScott {
 public:
  // Collective over `comm`: builds the Cartesian communicator and the initial state.
  GrayScott(const GrayScottParams& p, MPI_Comm comm);
  ~GrayScott();
  GrayScott(const GrayScott&) = delete;
  GrayScott& operator=(const GrayScott&) = delete;

  void step();  // collective: one Euler step, then the halo exchange

  // This rank's V array: (owned + 2)^3 samples with ghosts, x fastest.
  const std::vector<double>& v() const { return v_; }
  std::array<int, 3> owned() const { return owned_; }    // owned samples per axis
  std::array<int, 3> offset() const { return offset_; }  // global index of the first owned sample
  std::array<int, 3> procs() const { return procs_; }    // ranks per axis (MPI_Dims_create)
  long long index(int x, int y, int z) const {           // array index; owned samples are 1..owned
    return x + sx_ * (y + (long long)sy_ * z);
  }

  // Collective: V's owned samples of every rank as float32, x fastest, N^3 on rank 0 (empty
  // elsewhere).
  std::vector<float> gatherV() const;

 private:
  void exchange(std::vector<double>& a);
  GrayScottParams p_;
  MPI_Comm cart_ = MPI_COMM_NULL;
  std::array<int, 3> procs_{0, 0, 0}, coords_{0, 0, 0}, owned_{0, 0, 0}, offset_{0, 0, 0};
  int sx_ = 0, sy_ = 0, sz_ = 0;  // array sizes with ghosts
  std::vector<double> u_, v_, u2_, v2_;
  // Halo datatypes per axis: [0] first owned layer, [1] last owned, [2] low ghost, [3] high ghost.
  std::array<std::array<MPI_Datatype, 4>, 3> faces_{};
  std::array<std::array<int, 2>, 3> neighbours_{};  // per axis: lower, upper rank
};
