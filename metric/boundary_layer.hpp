// Boundary-layer metric: fine in the direction normal to the wall patches, growing with the
// distance d to them, intersected with a background field so the layers and the interior meet
// without a jump.
//
//   normal size      h_n(d) = h0 + (r - 1) d       (the continuous form of layers h0 r^k: layer k
//                                                   starts at d_k = h0 (r^k - 1)/(r - 1), where
//                                                   h_n = h0 r^k exactly)
//                    beyond the layers' thickness T (options.layers_thickness), at the interior
//                    growth g: h_n(d) = h_n(T) + (g - 1) (d - T); g > r reaches the background's
//                    sizes sooner, with fewer tets, while the first tets on the layers' top still
//                    get about the next layer's height h0 r^n
//   tangential size  h_t(d) = max(h_s, h_n(d))     h_s: the wall's edge size at the closest wall
//                                                   point (per-vertex mean edge length,
//                                                   interpolated), never finer than h_n
//   M = intersect(n n^T / h_n^2 + (I - n n^T) / h_t^2, M_background)
// with n the direction from the closest wall point (the face normal on the wall itself).
// Beyond the band distance D = (far_size - h0) / (r - 1), where h_n reaches far_size, the field
// is the background alone: choose far_size at least the background's sizes near the walls (the
// default does) and the cut is invisible.
//
// The closest wall triangle comes from an OpenVDB unsigned-distance level set of the wall
// triangles (its closest-polygon index grid, narrow band D); the distance itself is then computed
// exactly to the candidate triangles of the query's 8 surrounding voxels.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/sizing.hpp"
#include "core/status.hpp"
#include "core/surface_mesh.hpp"

namespace anitet {
namespace metric {

namespace detail {
inline double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
}  // namespace detail

struct BoundaryLayerOptions {
  double first_height = 0.0;          // h0 > 0: the first layer's thickness
  double growth = 1.2;                // r > 1: the layers' thickness ratio
  // Beyond layers_thickness (T >= 0) the normal size grows at interior_growth (g >= r) instead;
  // 0: at growth everywhere.
  double layers_thickness = 0.0;
  double interior_growth = 0.0;
  std::vector<int32_t> wall_patches;  // the surface's patch labels that are walls; empty: all
  // Band end: the normal size there (> h0). 0: twice the background's largest size at the wall
  // vertices.
  double far_size = 0.0;
  // Level-set voxel size. 0: the walls' mean edge length; grown when the band would need more
  // than max_voxels voxels (only candidate finding depends on it, distances are exact).
  double voxel_size = 0.0;
  size_t max_voxels = size_t(1) << 24;
};

struct BoundaryLayerStats {
  size_t wall_triangles = 0;
  double band_distance = 0.0;  // D
  double voxel_size = 0.0;
  size_t band_voxels = 0;      // active voxels of the index grid
  size_t memory_bytes = 0;     // of the OpenVDB grids
};

class BoundaryLayerField final : public SizingField {
 public:
  struct Impl;  // in the OpenVDB module (metric_field.hpp)
  struct ImplDeleter {
    void operator()(Impl* impl) const;
  };
  // Error::InvalidArgument for bad options, Error::EmptyInput when no triangle is a wall,
  // Error::Internal if OpenVDB fails. The background must outlive the field.
  static Result<BoundaryLayerField> create(const SurfaceMesh& surface, const SizingField& background,
                                           const BoundaryLayerOptions& options,
                                           BoundaryLayerStats* stats = nullptr);
  BoundaryLayerField(BoundaryLayerField&&) noexcept;
  BoundaryLayerField& operator=(BoundaryLayerField&&) noexcept;
  ~BoundaryLayerField() override;

  void metric(const double p[3], double m[6]) const override;
  // The distance to the walls and the closest wall point; false beyond the band.
  bool wall_distance(const double p[3], double& d, double closest[3]) const;

  // Internal (the module's result): takes ownership.
  explicit BoundaryLayerField(Impl* impl);

 private:
  std::unique_ptr<Impl, ImplDeleter> impl_;
};

// The point of triangle abc closest to p, with its barycentric weights (w[0] for a, ...).
inline void closest_point_on_triangle(const double p[3], const double a[3], const double b[3],
                                      const double c[3], double q[3], double w[3]) {
  // Voronoi regions of the vertices, then of the edges, else the face (barycentric from areas).
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
  const double bp[3] = {p[0] - b[0], p[1] - b[1], p[2] - b[2]};
  const double cp[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
  const double d1 = detail::dot3(ab, ap), d2 = detail::dot3(ac, ap);
  const double d3 = detail::dot3(ab, bp), d4 = detail::dot3(ac, bp);
  const double d5 = detail::dot3(ab, cp), d6 = detail::dot3(ac, cp);
  const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
  if (d1 <= 0.0 && d2 <= 0.0) {
    w[0] = 1.0, w[1] = 0.0, w[2] = 0.0;
  } else if (d3 >= 0.0 && d4 <= d3) {
    w[0] = 0.0, w[1] = 1.0, w[2] = 0.0;
  } else if (d6 >= 0.0 && d5 <= d6) {
    w[0] = 0.0, w[1] = 0.0, w[2] = 1.0;
  } else if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double t = d1 / (d1 - d3);
    w[0] = 1.0 - t, w[1] = t, w[2] = 0.0;
  } else if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double t = d2 / (d2 - d6);
    w[0] = 1.0 - t, w[1] = 0.0, w[2] = t;
  } else if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    w[0] = 0.0, w[1] = 1.0 - t, w[2] = t;
  } else {
    const double s = 1.0 / (va + vb + vc);
    w[1] = vb * s;
    w[2] = vc * s;
    w[0] = 1.0 - w[1] - w[2];
  }
  for (int k = 0; k < 3; ++k) q[k] = w[0] * a[k] + w[1] * b[k] + w[2] * c[k];
}

}  // namespace metric
}  // namespace anitet
