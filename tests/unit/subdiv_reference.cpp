#include "subdiv_reference.h"

#include <glm/geometric.hpp>
#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <stdexcept>
#include <vector>

namespace sortlast {

using namespace OpenSubdiv;

namespace {

// The vertex type OpenSubdiv's interpolation templates ask for.
struct Point {
  glm::dvec3 p{0.0};
  void Clear(void* = nullptr) { p = glm::dvec3(0.0); }
  void AddWithWeight(const Point& src, double w) { p += w * src.p; }
};


std::unique_ptr<Far::TopologyRefiner> makeRefiner(const PolyMesh& input) {
  Far::TopologyDescriptor desc;
  desc.numVertices = static_cast<int>(input.points.size());
  desc.numFaces = input.faceCount();
  desc.numVertsPerFace = input.face_sizes.data();
  desc.vertIndicesPerFace = input.face_corners.data();
  // The tags, as OpenSubdiv takes them: creases by vertex pair (each edge once), corners, holes.
  // (Static: the descriptor keeps pointers until Create has run; one refiner is made at a time.)
  static std::vector<int> creasePairs, cornerVertices, holes;
  static std::vector<float> creaseWeights, cornerWeights;
  creasePairs.clear(), cornerVertices.clear(), holes.clear(), creaseWeights.clear(), cornerWeights.clear();
  for (int f = 0; f < input.faceCount(); ++f)
    for (int c = 0; c < input.face_sizes[f]; ++c) {
      const int a = input.corner(f, c), b = input.corner(f, (c + 1) % input.face_sizes[f]);
      const double sh = input.edgeSharp(input.face_offsets[f] + c);
      if (sh <= 0) continue;
      bool seen = false;  // the edge's other face gave it already
      for (size_t i = 0; i < creasePairs.size(); i += 2) seen |= creasePairs[i] == b && creasePairs[i + 1] == a;
      if (seen) continue;
      creasePairs.insert(creasePairs.end(), {a, b});
      creaseWeights.push_back(float(sh));
    }
  for (size_t p = 0; p < input.points.size(); ++p)
    if (input.vertexSharp(int(p)) > 0) cornerVertices.push_back(int(p)), cornerWeights.push_back(float(input.vertexSharp(int(p))));
  for (int f = 0; f < input.faceCount(); ++f)
    if (input.hole(f)) holes.push_back(f);
  desc.numCreases = int(creaseWeights.size());
  desc.creaseVertexIndexPairs = creasePairs.data();
  desc.creaseWeights = creaseWeights.data();
  desc.numCorners = int(cornerWeights.size());
  desc.cornerVertexIndices = cornerVertices.data();
  desc.cornerWeights = cornerWeights.data();
  desc.numHoles = int(holes.size());
  desc.holeIndices = holes.data();
  Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(input.boundary == BoundaryInterpolation::None       ? Sdc::Options::VTX_BOUNDARY_NONE
                                  : input.boundary == BoundaryInterpolation::EdgeOnly ? Sdc::Options::VTX_BOUNDARY_EDGE_ONLY
                                                                                      : Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  sdc.SetCreasingMethod(input.crease_method == CreaseMethod::Chaikin ? Sdc::Options::CREASE_CHAIKIN
                                                                     : Sdc::Options::CREASE_UNIFORM);
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  std::unique_ptr<Far::TopologyRefiner> r(Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, sdc)));
  if (!r) throw std::runtime_error("OpenSubdiv refused the mesh");
  return r;
}

}  // namespace

std::vector<LimitPoint> OsdReference::limitAtVertices(const PolyMesh& input, int levels,
                                                      std::vector<glm::dvec3>& refinedPoints) {
  auto refiner = makeRefiner(input);
  Far::TopologyRefiner::UniformOptions options(levels);
  options.fullTopologyInLastLevel = true;  // Limit() needs each last-level vertex's neighbourhood
  refiner->RefineUniform(options);
  std::vector<Point> points(refiner->GetNumVerticesTotal());
  for (size_t i = 0; i < input.points.size(); ++i) points[i].p = input.points[i];
  Far::PrimvarRefinerReal<double> primvar(*refiner);
  Point* src = points.data();
  for (int level = 1; level <= levels; ++level) {
    Point* dst = src + refiner->GetLevel(level - 1).GetNumVertices();
    primvar.Interpolate(level, src, dst);
    src = dst;
  }
  const int n = refiner->GetLevel(levels).GetNumVertices();
  std::vector<Point> pos(n), tan1(n), tan2(n);
  primvar.Limit(src, pos, tan1, tan2);
  std::vector<LimitPoint> out(n);
  refinedPoints.resize(n);
  for (int i = 0; i < n; ++i) {
    refinedPoints[i] = src[i].p;
    out[i] = {pos[i].p, glm::normalize(glm::cross(tan1[i].p, tan2[i].p))};
  }
  return out;
}

struct OsdReference::Impl {
  std::unique_ptr<Far::TopologyRefiner> refiner;
  std::unique_ptr<Far::PatchTable> patches;
  std::unique_ptr<Far::PatchMap> map;
  std::unique_ptr<Far::PtexIndices> ptex;
  std::vector<Point> points;  // refined points, then the patch table's local (end cap) points
  std::vector<int> face_sizes;
};

OsdReference::OsdReference(const PolyMesh& input, int isolation) : impl_(std::make_unique<Impl>()) {
  impl_->refiner = makeRefiner(input);
  Far::PatchTableFactory::Options options(isolation);
  options.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
  // Regular patches along infinitely sharp creases (exact B-spline patches with boundary rules)
  // instead of isolating them to the deepest level and ending in Gregory caps.
  options.useInfSharpPatch = true;
  options.SetPatchPrecision<double>();
  impl_->refiner->RefineAdaptive(options.GetRefineAdaptiveOptions());
  impl_->patches.reset(Far::PatchTableFactory::Create(*impl_->refiner, options));
  impl_->map = std::make_unique<Far::PatchMap>(*impl_->patches);
  impl_->ptex = std::make_unique<Far::PtexIndices>(*impl_->refiner);
  impl_->face_sizes = input.face_sizes;

  const int refined = impl_->refiner->GetNumVerticesTotal();
  impl_->points.resize(refined + impl_->patches->GetNumLocalPoints());
  for (size_t i = 0; i < input.points.size(); ++i) impl_->points[i].p = input.points[i];
  Far::PrimvarRefinerReal<double> primvar(*impl_->refiner);
  Point* src = impl_->points.data();
  for (int level = 1; level < impl_->refiner->GetNumLevels(); ++level) {
    Point* dst = src + impl_->refiner->GetLevel(level - 1).GetNumVertices();
    primvar.Interpolate(level, src, dst);
    src = dst;
  }
  // The end caps' local points, with the double-precision stencils the options asked for
  // (ComputeLocalPointValues reads the single-precision table only).
  if (const auto* local = impl_->patches->GetLocalPointStencilTable<double>())
    local->UpdateValues(impl_->points.data(), impl_->points.data() + refined);
}

OsdReference::~OsdReference() = default;

LimitPoint OsdReference::evaluate(const ControlMesh& control, int face, double u, double v) const {
  const auto& chain = control.corner_chain[face];
  // Up the chain to the input face's children: each step halves into the parent quad's (u, v).
  double s = u, t = v;
  for (size_t i = chain.size(); i-- > 1;) childToParentQuad(chain[i], s, t, s, t);
  const int input_face = control.input_face[face];
  int ptexFace = impl_->ptex->GetFaceId(input_face);
  if (impl_->face_sizes[input_face] == 4) {
    childToParentQuad(chain[0], s, t, s, t);
  } else {
    ptexFace += chain[0];
  }
  const Far::PatchTable::PatchHandle* handle = impl_->map->FindPatch(ptexFace, s, t);
  if (!handle) throw std::runtime_error("OpenSubdiv found no patch");
  double wp[20], ws[20], wt[20];
  impl_->patches->EvaluateBasis(*handle, s, t, wp, ws, wt);
  const Far::ConstIndexArray cvs = impl_->patches->GetPatchVertices(*handle);
  glm::dvec3 p(0.0), ds(0.0), dt(0.0);
  for (int i = 0; i < cvs.size(); ++i) {
    p += wp[i] * impl_->points[cvs[i]].p;
    ds += ws[i] * impl_->points[cvs[i]].p;
    dt += wt[i] * impl_->points[cvs[i]].p;
  }
  return {p, glm::normalize(glm::cross(ds, dt))};
}

}  // namespace sortlast
