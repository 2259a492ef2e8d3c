#include "pipeline/bl_report.hpp"

#include <algorithm>
#include <cmath>

namespace anitet {

namespace {

double distance(const double* p, const double* q) {
  return std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

}  // namespace

void measure_boundary_layer(const SurfaceMesh& surface, const BoundaryLayerOptions& bl, int layers,
                            const std::vector<uint32_t>& vertex_origin, const std::vector<double>& t1_xyz,
                            const TetMesh& mesh, BoundaryLayerReport& r) {
  r.layers = layers;
  r.columns_reaching.assign(size_t(std::max(layers, 0)) + 1, 0);
  const size_t nv = vertex_origin.size();
  std::vector<std::vector<uint32_t>> children(nv);
  for (uint32_t v = 0; v < nv; ++v)
    if (vertex_origin[v] != TetMesh::kNone && vertex_origin[v] < nv) children[vertex_origin[v]].push_back(v);
  std::vector<uint8_t> wall(surface.num_vertices(), 0);
  for (size_t t = 0; t < surface.num_triangles(); ++t)
    if (std::find(bl.wall_patches.begin(), bl.wall_patches.end(), surface.patch[t]) != bl.wall_patches.end())
      for (int k = 0; k < 3; ++k) wall[surface.tri[3 * t + k]] = 1;
  double first_sum = 0.0, growth_sum = 0.0;
  r.first_height_min = HUGE_VAL;
  for (uint32_t v = 0; v < surface.num_vertices(); ++v) {
    if (!wall[v]) continue;
    ++r.wall_vertices;
    uint32_t at = v;
    double worst = 0.0, first = 0.0, last = 0.0;
    int reached = 0;
    for (int i = 0; i < layers; ++i) {
      if (at >= nv || children[at].empty()) break;
      ++reached;
      const uint32_t next = children[at].back();
      const double h = distance(mesh.point(at), mesh.point(next));
      if (i == 0) first = h;
      last = h;
      worst = std::max(worst, std::abs(h / (bl.first_height * std::pow(bl.growth, i)) - 1.0));
      at = next;
    }
    ++r.columns_reaching[size_t(reached)];
    if (reached < layers || layers == 0) continue;
    ++r.full_columns;
    first_sum += first;
    r.first_height_min = std::min(r.first_height_min, first);
    r.first_height_max = std::max(r.first_height_max, first);
    growth_sum += layers > 1 && first > 0.0 ? std::pow(last / first, 1.0 / (layers - 1)) : 1.0;
    if (worst <= 0.1) {
      ++r.nominal_columns;
      r.max_height_error = std::max(r.max_height_error, worst);
    }
  }
  if (r.full_columns) {
    r.first_height_mean = first_sum / double(r.full_columns);
    r.growth_mean = growth_sum / double(r.full_columns);
  } else {
    r.first_height_min = 0.0;
  }
  for (uint32_t v = 0; v < nv && 3 * size_t(v) + 2 < t1_xyz.size(); ++v)
    if (mesh.vflags[v] & vflag::kBoundaryLayer)
      r.max_displacement = std::max(r.max_displacement, distance(mesh.point(v), &t1_xyz[3 * size_t(v)]));
}

}  // namespace anitet
