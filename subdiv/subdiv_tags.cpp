#include "subdiv/subdiv_tags.h"

#include <algorithm>

namespace sortlast {

const char* boundaryName(BoundaryInterpolation b) {
  switch (b) {
    case BoundaryInterpolation::None: return "none";
    case BoundaryInterpolation::EdgeOnly: return "edge only";
    case BoundaryInterpolation::EdgeAndCorner: return "edge and corner";
  }
  return "?";
}

const char* creaseMethodName(CreaseMethod m) { return m == CreaseMethod::Chaikin ? "chaikin" : "uniform"; }

VertexRule vertexRule(double vertex_sharpness, const std::vector<double>& edge_sharpness) {
  if (isSharp(vertex_sharpness)) return VertexRule::Corner;
  int sharp = 0;
  for (double s : edge_sharpness) sharp += isSharp(s);
  return sharp == 0 ? VertexRule::Smooth : sharp == 1 ? VertexRule::Dart : sharp == 2 ? VertexRule::Crease : VertexRule::Corner;
}

double decrementSharpness(double s) {
  if (!isSharp(s)) return 0.0;
  if (isInfinite(s)) return kInfinitelySharp;
  return s > 1.0 ? s - 1.0 : 0.0;
}

std::vector<double> childEdgeSharpness(CreaseMethod method, const std::vector<double>& edges) {
  std::vector<double> out(edges.size());
  if (method == CreaseMethod::Uniform || edges.size() < 2) {
    for (size_t i = 0; i < edges.size(); ++i) out[i] = decrementSharpness(edges[i]);
    return out;
  }
  // Chaikin: 3/4 of the edge's own value and 1/4 of the mean of the other semi-sharp edges at
  // this vertex, less 1 (an edge alone among them just decrements).
  double sum = 0;
  int count = 0;
  for (double s : edges)
    if (isSemiSharp(s)) sum += s, ++count;
  for (size_t i = 0; i < edges.size(); ++i) {
    const double s = edges[i];
    if (!isSharp(s)) out[i] = 0.0;
    else if (isInfinite(s)) out[i] = kInfinitelySharp;
    else if (count == 1) out[i] = decrementSharpness(s);
    else {
      const double others = (sum - s) / (count - 1);
      const double c = 0.75 * s + 0.25 * others - 1.0;
      out[i] = isSharp(c) ? c : 0.0;
    }
  }
  return out;
}

double fractionalWeight(CreaseMethod method, double vertex_sharpness, double childVertexSharpness,
                        const std::vector<double>& edges, const std::vector<double>& childEdges) {
  int count = 0;
  double sum = 0;
  if (isSharp(vertex_sharpness) && !isSharp(childVertexSharpness)) count = 1, sum = vertex_sharpness;
  for (size_t i = 0; i < edges.size(); ++i) {
    // Uniform: a value in (0, 1] is the one that decays this step; Chaikin: whichever did.
    const bool decays = method == CreaseMethod::Uniform ? isSharp(edges[i]) && edges[i] <= 1.0
                                                        : isSharp(edges[i]) && !isSharp(childEdges[i]);
    if (decays) sum += edges[i], ++count;
  }
  if (count == 0) return 0.0;
  return std::min(1.0, sum / count);
}

}  // namespace sortlast
