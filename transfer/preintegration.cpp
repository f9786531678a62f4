#include "transfer/preintegration.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sortlast {

namespace {

// tau and colour of a normalised value (the transfer function's own evaluation). The table is
// over normalised values, i.e. in the domain of transfer.scale: a segment's value is taken to go
// linearly in s(v) (log10 v under log), not in v.
struct Emission {
  double tau;
  std::array<double, 3> c;
};
Emission emissionAt(const TransferFunction& tf, double x) {
  const auto e = tf.atNormalised(x);
  return {-std::log1p(-std::min(e[3], TransferFunction::kMaxOpacity)) / tf.unitLength(),
          {e[0], e[1], e[2]}};
}

// Per fine cell: the integral of tau and of c * tau over the cell (normalised value units).
// Each cell is split at the control points inside it, so every piece is smooth (a linear, tau =
// -ln(1 - a) / unit), and integrated with 4-point Gauss-Legendre.
struct Cell {
  double tau;                 // mean extinction over the cell
  std::array<double, 3> c;    // tau-weighted mean colour (the colour at the centre if tau = 0)
};
std::vector<Cell> fineCells(const TransferFunction& tf, int cells) {
  static const double gx[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                               0.8611363115940526};
  static const double gw[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                               0.3478548451374538};
  std::vector<Cell> out(static_cast<size_t>(cells));
  const auto& pts = tf.points();
  for (int g = 0; g < cells; ++g) {
    const double lo = double(g) / cells, hi = double(g + 1) / cells;
    std::vector<double> cuts{lo};
    for (const TfPoint& p : pts)
      if (p.value > lo && p.value < hi) cuts.push_back(p.value);
    cuts.push_back(hi);
    double it = 0.0, ic[3] = {0, 0, 0};
    for (size_t s = 0; s + 1 < cuts.size(); ++s) {
      const double m = 0.5 * (cuts[s] + cuts[s + 1]), r = 0.5 * (cuts[s + 1] - cuts[s]);
      for (int q = 0; q < 4; ++q) {
        Emission e = emissionAt(tf, m + r * gx[q]);
        const double w = gw[q] * r * e.tau;
        it += w;
        for (int k = 0; k < 3; ++k) ic[k] += w * e.c[k];
      }
    }
    Cell& cell = out[size_t(g)];
    cell.tau = it / (hi - lo);
    if (it > 0.0) {
      for (int k = 0; k < 3; ++k) cell.c[k] = ic[k] / it;
    } else {
      cell.c = emissionAt(tf, 0.5 * (lo + hi)).c;
    }
  }
  return out;
}

}  // namespace

PreintegrationTable PreintegrationTable::build(const TransferFunction& tf, int n, double base_length) {
  if (n < 2 || !(base_length > 0.0)) throw std::logic_error("PreintegrationTable: bad size or length");
  PreintegrationTable t;
  t.n = n;
  t.base_length = base_length;
  t.entries.assign(size_t(4) * n * n, 0.0);
  const int s = kSubsteps, cells = (n - 1) * s;
  const std::vector<Cell> fine = fineCells(tf, cells);
  // Constant segments: the midpoint formula at the entry's value.
  for (int i = 0; i < n; ++i) {
    Emission e = emissionAt(tf, double(i) / (n - 1));
    const double d = e.tau * base_length, a = -std::expm1(-d);
    double* out = &t.entries[size_t(4) * (i + size_t(n) * i)];
    for (int k = 0; k < 3; ++k) out[k] = e.c[k] * a;
    out[3] = d;
  }
  std::vector<double> keep(static_cast<size_t>(cells)), alpha(static_cast<size_t>(cells));
  for (int span = 1; span < n; ++span) {
    // Every segment spanning `span` entries crosses span * s cells, each for h of the length.
    const double h = base_length / double(span * s);
    for (int g = 0; g < cells; ++g) {
      alpha[size_t(g)] = -std::expm1(-fine[size_t(g)].tau * h);
      keep[size_t(g)] = 1.0 - alpha[size_t(g)];
    }
    for (int i = 0; i + span < n; ++i) {
      const int j = i + span;
      // Front i, back j: the cells i*s .. j*s - 1 in increasing order; front j, back i: reversed.
      for (int dir = 0; dir < 2; ++dir) {
        double rgb[3] = {0, 0, 0}, transmit = 1.0, depth = 0.0;
        for (int m = 0; m < span * s; ++m) {
          const int g = dir == 0 ? i * s + m : j * s - 1 - m;
          const Cell& c = fine[size_t(g)];
          const double w = transmit * alpha[size_t(g)];
          rgb[0] += w * c.c[0];
          rgb[1] += w * c.c[1];
          rgb[2] += w * c.c[2];
          transmit *= keep[size_t(g)];
          depth += c.tau * h;
        }
        const int f = dir == 0 ? i : j, b = dir == 0 ? j : i;
        double* out = &t.entries[size_t(4) * (f + size_t(n) * b)];
        out[0] = rgb[0];
        out[1] = rgb[1];
        out[2] = rgb[2];
        out[3] = depth;
      }
    }
  }
  return t;
}

std::array<double, 4> PreintegrationTable::lookup(double xf, double xb, double length) const {
  // Texel centres at the ends: coordinate x (n - 1), linear between neighbouring entries.
  auto axis = [&](double x, int& i0, double& f) {
    const double c = std::clamp(x, 0.0, 1.0) * (n - 1);
    i0 = std::min(int(c), n - 2);
    f = c - i0;
  };
  int i, j;
  double fi, fj;
  axis(xf, i, fi);
  axis(xb, j, fj);
  std::array<double, 4> e{};
  for (int dj = 0; dj < 2; ++dj)
    for (int di = 0; di < 2; ++di) {
      const double w = (di ? fi : 1.0 - fi) * (dj ? fj : 1.0 - fj);
      const double* p = &entries[size_t(4) * ((i + di) + size_t(n) * (j + dj))];
      for (int k = 0; k < 4; ++k) e[k] += w * p[k];
    }
  const double r = length / base_length;
  const double a0 = -std::expm1(-e[3]), a = -std::expm1(-e[3] * r);
  const double scale = a0 > 0.0 ? a / a0 : r;
  return {e[0] * scale, e[1] * scale, e[2] * scale, a};
}

std::vector<float> PreintegrationTable::texels() const {
  return std::vector<float>(entries.begin(), entries.end());
}

bool sameTransferFunction(const TransferFunction& a, const TransferFunction& b) {
  if (a.rangeLo() != b.rangeLo() || a.rangeHi() != b.rangeHi() || a.unitLength() != b.unitLength() ||
      !(a.scale() == b.scale()) || a.points().size() != b.points().size())
    return false;
  for (size_t i = 0; i < a.points().size(); ++i) {
    const TfPoint &p = a.points()[i], &q = b.points()[i];
    if (p.value != q.value || p.r != q.r || p.g != q.g || p.b != q.b || p.a != q.a) return false;
  }
  return true;
}

}  // namespace sortlast
