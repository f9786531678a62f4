#include "subdiv/subdiv_basis.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace sortlast {

namespace {

using Row = Eigen::RowVectorXd;

// The local control net as quads of labels, and the Catmull-Clark rules on it as weight rows over
// the 2N + 8 labels. The rules are only asked for where the net holds the whole neighbourhood.
struct LabelNet {
  int size;
  std::vector<std::array<int, 4>> faces;

  Row unit(int label) const {
    Row r = Row::Zero(size);
    r[label] = 1;
    return r;
  }
  Row facePoint(const std::array<int, 4>& f) const {
    Row r = Row::Zero(size);
    for (int c : f) r[c] += 0.25;
    return r;
  }
  Row edgePoint(int a, int b) const {
    Row r = 0.25 * (unit(a) + unit(b));
    int found = 0;
    for (const auto& f : faces)
      for (int c = 0; c < 4; ++c)
        if ((f[c] == a && f[(c + 1) % 4] == b) || (f[c] == b && f[(c + 1) % 4] == a)) {
          r += 0.25 * facePoint(f);
          ++found;
        }
    if (found != 2) throw std::logic_error("ValenceBasis: edge point outside the local net");
    return r;
  }
  Row vertexPoint(int v, int valence) const {
    Row q = Row::Zero(size), r = Row::Zero(size);
    int n = 0;
    for (const auto& f : faces)
      for (int c = 0; c < 4; ++c)
        if (f[c] == v) {
          q += facePoint(f);
          r += 0.5 * (unit(v) + unit(f[(c + 1) % 4]));  // the edge after v in this face
          ++n;
        }
    if (n != valence) throw std::logic_error("ValenceBasis: vertex point outside the local net");
    return (q / n + 2.0 * r / n + (n - 3.0) * unit(v)) / n;
  }
};

}  // namespace

int ValenceBasis::label(int n, int i, int j) {
  auto e = [n](int k) { return 2 * ((k - 1) % n + 1) - 1; };
  auto f = [n](int k) { return 2 * ((k - 1) % n + 1); };
  if (i == 0 && j == 0) return 0;
  if (i == 1 && j == 0) return e(1);
  if (i == 1 && j == 1) return f(1);
  if (i == 0 && j == 1) return e(2);
  if (i == -1 && j == 1) return f(2);
  if (i == -1 && j == 0) return e(3);
  if (i == 0 && j == -1) return e(n);
  if (i == 1 && j == -1) return f(n);
  if (i == -1 && j == -1) return n == 4 ? f(3) : -1;
  const int extras[7][2] = {{2, -1}, {2, 0}, {2, 1}, {2, 2}, {1, 2}, {0, 2}, {-1, 2}};
  for (int x = 0; x < 7; ++x)
    if (extras[x][0] == i && extras[x][1] == j) return 2 * n + 1 + x;
  return -1;
}

ValenceBasis::ValenceBasis(int n) : valence(n), size(2 * n + 8) {
  if (n < 3) throw std::invalid_argument("ValenceBasis: valence below 3");
  auto L = [n](int i, int j) { return label(n, i, j); };
  LabelNet net{size, {}};
  for (int i = 1; i <= n; ++i) net.faces.push_back({0, 2 * i - 1, 2 * i, i == n ? 1 : 2 * i + 1});
  const std::array<int, 4> c1{L(1, -1), L(2, -1), L(2, 0), L(1, 0)}, c2{L(1, 0), L(2, 0), L(2, 1), L(1, 1)},
      c3{L(1, 1), L(2, 1), L(2, 2), L(1, 2)}, c4{L(0, 1), L(1, 1), L(1, 2), L(0, 2)},
      c5{L(-1, 1), L(0, 1), L(0, 2), L(-1, 2)};
  for (const auto& c : {c1, c2, c3, c4, c5}) net.faces.push_back(c);

  // One step: each label's new point, at half the scale.
  A = Eigen::MatrixXd::Zero(size, size);
  A.row(0) = net.vertexPoint(0, n);
  for (int i = 1; i <= n; ++i) {
    A.row(2 * i - 1) = net.edgePoint(0, 2 * i - 1);
    A.row(2 * i) = net.facePoint(net.faces[i - 1]);
  }
  A.row(L(2, -1)) = net.edgePoint(L(1, 0), L(1, -1));
  A.row(L(2, 0)) = net.vertexPoint(L(1, 0), 4);
  A.row(L(2, 1)) = net.edgePoint(L(1, 0), L(1, 1));
  A.row(L(2, 2)) = net.vertexPoint(L(1, 1), 4);
  A.row(L(1, 2)) = net.edgePoint(L(0, 1), L(1, 1));
  A.row(L(0, 2)) = net.vertexPoint(L(0, 1), 4);
  A.row(L(-1, 2)) = net.edgePoint(L(0, 1), L(-1, 1));

  // New grid points the sub-patches need beyond the layout (column or row 3 of the new grid).
  auto newPoint = [&](int i, int j) -> Row {
    const int l = L(i, j);
    if (l >= 0) return A.row(l);
    if (i == 3 && j == -1) return net.facePoint(c1);
    if (i == 3 && j == 0) return net.edgePoint(L(1, 0), L(2, 0));
    if (i == 3 && j == 1) return net.facePoint(c2);
    if (i == 3 && j == 2) return net.edgePoint(L(1, 1), L(2, 1));
    if (i == 3 && j == 3) return net.facePoint(c3);
    if (i == 2 && j == 3) return net.edgePoint(L(1, 1), L(1, 2));
    if (i == 1 && j == 3) return net.facePoint(c4);
    if (i == 0 && j == 3) return net.edgePoint(L(0, 1), L(0, 2));
    if (i == -1 && j == 3) return net.facePoint(c5);
    throw std::logic_error("ValenceBasis: sub-patch grid point outside the local net");
  };
  for (int k = 0; k < 3; ++k) {
    pick[k] = Eigen::MatrixXd::Zero(16, size);
    for (int b = 0; b < 4; ++b)
      for (int a = 0; a < 4; ++a)
        pick[k].row(b * 4 + a) = newPoint(kSubPatchOrigin[k][0] + a, kSubPatchOrigin[k][1] + b);
  }

  // Eigen-decomposition. Catmull-Clark's subdivision matrix has real eigenvalues, several of them
  // double (1/4, 1/8, 1/16, 1/32 and, for some valences, ring eigenvalues): a general solver may
  // return such a pair as a complex pair with complex eigenvectors. So the solver gives the
  // eigenvalues only; each eigenvalue of multiplicity m gets its m eigenvectors as the kernel of
  // A - lambda I (its m smallest singular vectors). A defective matrix (fewer independent
  // eigenvectors than the multiplicity) would show in the reconstruction error.
  Eigen::EigenSolver<Eigen::MatrixXd> solver(A, false);
  if (solver.info() != Eigen::Success)
    throw std::runtime_error("ValenceBasis: eigen-decomposition failed for valence " + std::to_string(n));
  if (solver.eigenvalues().imag().cwiseAbs().maxCoeff() > 1e-9)
    throw std::runtime_error("ValenceBasis: complex eigenvalues for valence " + std::to_string(n));
  std::vector<double> values(size);
  for (int i = 0; i < size; ++i) values[i] = solver.eigenvalues()[i].real();
  std::sort(values.begin(), values.end(), std::greater<>());
  lambda.resize(size);
  V.resize(size, size);
  for (int i = 0; i < size;) {
    int m = 1;
    while (i + m < size && values[i + m] > values[i] - 1e-9) ++m;
    double mean = 0;
    for (int j = 0; j < m; ++j) mean += values[i + j] / m;
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A - mean * Eigen::MatrixXd::Identity(size, size), Eigen::ComputeFullV);
    for (int j = 0; j < m; ++j) {
      lambda[i + j] = mean;
      V.col(i + j) = svd.matrixV().col(size - m + j);
    }
    i += m;
  }
  Vinv = V.partialPivLu().inverse();
  reconstruction_error = (V * lambda.asDiagonal() * Vinv - A).cwiseAbs().maxCoeff();
  if (!(reconstruction_error < 1e-9))
    throw std::runtime_error("ValenceBasis: subdivision matrix of valence " + std::to_string(n) +
                             " not diagonalisable to 1e-9 (error " + std::to_string(reconstruction_error) + ")");
  for (int k = 0; k < 3; ++k) X[k] = pick[k] * V;
}

}  // namespace sortlast
