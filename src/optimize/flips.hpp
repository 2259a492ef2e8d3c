// Quality-driven flips (internal to optimize/): 2-3 on a facet, and edge removal (3-2, 4-4, and
// up to a ring of 7 tets) with the triangulation of the edge's ring that maximizes the worst
// radius ratio (dynamic programming over the ring polygon). A flip is applied only when it raises
// the worst radius ratio of the tets it replaces by more than `gain`.
#pragma once

#include <cstdint>
#include <vector>

#include "core/tet_mesh.hpp"
#include "refine/mesh_ops.hpp"

namespace anitet::optimize_detail {

// The shape measure the flips and moves maximize: meshops::shape_quality, or, when vertex_metric
// is filled (an anisotropic metric; 6 per vertex), the same measured in the metric: each tet in
// the mean of its four vertices' metrics, so that its figure does not depend on which ball or
// flip measures it. Euclidean when empty, bit for bit meshops::shape_quality.
struct Quality {
  std::vector<double> vertex_metric;
  bool anisotropic() const { return !vertex_metric.empty(); }
  double of(const TetMesh& m, const uint32_t v[4]) const;
  double tet(const TetMesh& m, uint32_t t) const { return of(m, &m.tet_v[4 * size_t(t)]); }
  static const Quality& euclidean();  // the empty one
};

struct FlipContext {
  TetMesh& mesh;
  meshops::VertexTets& vt;
  meshops::ReplaceScratch scratch;
  std::vector<uint32_t> ring_tets, ring;
  std::vector<uint32_t> old;
  std::vector<meshops::TetVerts> fresh;
  double gain = 1e-6;
  // kRefuse in the optimizer (S's edges never move); kKeep on a recovered surface, whose
  // constrained edges are subsegments of S that no flip here can remove anyway.
  meshops::ConstrainedEdges rule = meshops::ConstrainedEdges::kRefuse;
  size_t flips23 = 0, edge_removals = 0;
  const Quality* quality = &Quality::euclidean();
  double tet(uint32_t t) const { return quality->tet(mesh, t); }
  double of(const uint32_t v[4]) const { return quality->of(mesh, v); }
};

// 2-3 flip of facet i of tet t (not protected, with a neighbour).
bool try_flip23(FlipContext& c, uint32_t t, int i);
// Removes edge k (kEdgeVertex order) of tet t.
bool try_remove_edge(FlipContext& c, uint32_t t, int k);
// The live tets whose shape quality is below `quality`, in slot order (measured on every core).
std::vector<uint32_t> tets_below(const TetMesh& m, double quality, const Quality& measure = Quality::euclidean());
// Tries edge removals then 2-3 flips on every live tet below `quality`, then for at most
// `rounds` - 1 more rounds on the new tets still below it. Returns the number of flips.
size_t flip_sweep(FlipContext& c, double quality, int rounds);

}  // namespace anitet::optimize_detail
