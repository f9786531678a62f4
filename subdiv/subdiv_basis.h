#pragma once
// Stam's eigenstructure of the Catmull-Clark subdivision matrix for one valence (Stam 1998, "Exact
// evaluation of Catmull-Clark subdivision surfaces at arbitrary parameter values"), built
// numerically with Eigen instead of from Stam's closed forms.
//
// The 2N + 8 control points of a patch whose corner (u, v) = (0, 0) is a vertex of valence N are
// labelled on a grid whose unit is the patch side, the patch being the cell [0,1]^2:
//   0            the extraordinary vertex, grid (0, 0)
//   2i - 1       e_i, its i-th edge neighbour, counter-clockwise: e_1 = (1, 0), e_2 = (0, 1), ...
//   2i           f_i, the far corner of the i-th face round it: f_1 = (1, 1), f_2 = (-1, 1), ...
//                (e_N = (0, -1), f_N = (1, -1); for N = 4 also e_3 = (-1, 0), f_3 = (-1, -1))
//   2N+1..2N+7   (2,-1), (2,0), (2,1), (2,2), (1,2), (0,2), (-1,2)
// One subdivision step maps these points to the same labels at half the scale: C1 = A C0 with the
// (2N+8)^2 subdivision matrix A. The three sub-patches k = 1, 2, 3 of the patch that no longer
// touch the extraordinary vertex (k = 1: u in [1/2,1], v in [0,1/2]; k = 2: both in [1/2,1];
// k = 3: u in [0,1/2], v in [1/2,1]) are uniform bicubic B-spline patches whose 16 control points
// are Pick_k C0 (Stam's picking matrix times his extended matrix A-bar, in one 16 x (2N+8) matrix).
// After n steps: control points of sub-patch k at level n = Pick_k A^(n-1) C0
//                                                         = X_k Lambda^(n-1) V^-1 C0,
// with A = V Lambda V^-1 and X_k = Pick_k V: Stam's eigenbasis, the paper's equation (8).
#include <Eigen/Dense>

#include <array>

namespace sortlast {

struct ValenceBasis {
  int valence = 0;
  int size = 0;                 // 2N + 8
  Eigen::MatrixXd A;            // subdivision matrix
  std::array<Eigen::MatrixXd, 3> pick;  // Pick_k, 16 x size; row b * 4 + a is grid (i0 + a, j0 + b)
  Eigen::VectorXd lambda;       // eigenvalues (real for Catmull-Clark), largest (1) first
  Eigen::MatrixXd V, Vinv;      // eigenvectors as columns, and the inverse
  std::array<Eigen::MatrixXd, 3> X;     // Pick_k V
  double reconstruction_error = 0;       // max |V Lambda V^-1 - A|

  explicit ValenceBasis(int n);  // throws std::runtime_error if A is not diagonalisable in reals
  // Label of grid point (i, j) in the layout above, or -1 where the layout has none.
  static int label(int valence, int i, int j);
};

// Grid origin (i0, j0) of sub-patch k's 4 x 4 control points, and of its cell's lower corner
// minus one (the cell is [i0 + 1, i0 + 2] x [j0 + 1, j0 + 2] at the sub-patch's level).
constexpr std::array<std::array<int, 2>, 3> kSubPatchOrigin = {{{0, -1}, {0, 0}, {-1, 0}}};

}  // namespace sortlast
