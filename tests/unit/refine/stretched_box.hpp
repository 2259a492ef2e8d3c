// Test fixture: the unit box with a constant anisotropic metric, meshed as refinement and
// optimization receive it (the Delaunay tetrahedralization of the box's boundary lattice points,
// spacing = the metric's sizes, so S's triangles are unit triangles in the metric, stretched in
// space; S = the hull facets, protected, its vertices fixed), and the measure of its result.
#pragma once

#include <gtest/gtest.h>

#include <vector>

#include "core/sizing.hpp"
#include "core/tet_mesh.hpp"
#include "delaunay/delaunay.hpp"
#include "refine/mesh_ops.hpp"

namespace anitet::test {

// A constant anisotropic metric: sizes hx, hy, hz along the axes.
class AxisSizing final : public SizingField {
 public:
  AxisSizing(double hx, double hy, double hz) : h_{hx, hy, hz} {}
  void metric(const double[3], double m[6]) const override {
    m[0] = 1.0 / (h_[0] * h_[0]);
    m[1] = 0.0;
    m[2] = 1.0 / (h_[1] * h_[1]);
    m[3] = 0.0;
    m[4] = 0.0;
    m[5] = 1.0 / (h_[2] * h_[2]);
  }

 private:
  double h_[3];
};

// n[k] lattice cells along axis k; `points` receives the boundary lattice points (the mesh's
// first vertices, in this order).
inline TetMesh stretched_box_mesh(const int n[3], std::vector<double>& points) {
  points.clear();
  for (int i = 0; i <= n[0]; ++i)
    for (int j = 0; j <= n[1]; ++j)
      for (int k = 0; k <= n[2]; ++k) {
        if (i != 0 && i != n[0] && j != 0 && j != n[1] && k != 0 && k != n[2]) continue;
        points.insert(points.end(), {double(i) / n[0], double(j) / n[1], double(k) / n[2]});
      }
  TetMesh mesh;
  EXPECT_TRUE(delaunay_tetrahedralize(mesh, points.data(), points.size() / 3).ok());
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t)
    if (!mesh.is_deleted(t) && mesh.is_ghost(t))
      mesh.set_facet_protected(mesh.neighbour(t, 3), mesh.neighbour_facet(t, 3), true);
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t)
    if (!mesh.is_deleted(t) && mesh.is_ghost(t)) mesh.delete_tet(t);
  EXPECT_TRUE(mesh.build_adjacency().ok());
  for (uint8_t& f : mesh.vflags) f |= vflag::kOnInputSurface;
  return mesh;
}

// The live tets whose radius ratio in the (constant) metric of `field` is below `below`.
inline size_t tets_below_in_metric(const TetMesh& mesh, const SizingField& field, double below,
                                   size_t* tets = nullptr) {
  double m[6];
  field.metric(mesh.point(0), m);
  const meshops::MetricMap map = meshops::MetricMap::of(m);
  size_t live = 0, bad = 0;
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t) {
    if (mesh.is_deleted(t)) continue;
    double q[4][3];
    for (int i = 0; i < 4; ++i) map.apply(mesh.point(mesh.vertex(t, i)), q[i]);
    ++live;
    bad += meshops::radius_ratio(q[0], q[1], q[2], q[3]) < below;
  }
  if (tets) *tets = live;
  return bad;
}

}  // namespace anitet::test
