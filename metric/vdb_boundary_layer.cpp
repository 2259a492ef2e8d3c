// BoundaryLayerField's OpenVDB half, in the module libanitet_vdb.so (vdb_backend.hpp): the walls'
// closest-triangle grid (MeshToVolume) and the metric. BoundaryLayerField (boundary_layer.cpp)
// forwards here.
#include "vdb_module.hpp"

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

#include "spd.hpp"

namespace anitet {
namespace metric {

namespace {

inline double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// The walls as OpenVDB's mesh adapter wants them: points in index space.
struct WallAdapter {
  const std::vector<double>* xyz;  // world
  const std::vector<uint32_t>* tri;
  const openvdb::math::Transform* xf;
  size_t polygonCount() const { return tri->size() / 3; }
  size_t pointCount() const { return xyz->size() / 3; }
  size_t vertexCount(size_t) const { return 3; }
  void getIndexSpacePoint(size_t n, size_t v, openvdb::Vec3d& pos) const {
    const double* p = &(*xyz)[3 * (*tri)[3 * n + v]];
    pos = xf->worldToIndex(openvdb::Vec3d(p[0], p[1], p[2]));
  }
};

// The largest size (1/sqrt of the smallest eigenvalue) of a metric.
double largest_size(const double m[6]) {
  const double lo = min_eigenvalue(m);
  return lo > 0.0 ? 1.0 / std::sqrt(lo) : 0.0;
}

}  // namespace


struct BoundaryLayerField::Impl {
  const SizingField* background = nullptr;
  double h0 = 0.0, rate = 0.0, band = 0.0;  // rate = r - 1
  double thickness = 0.0, interior_rate = 0.0;  // T, g - 1

  // The normal size at distance d from the walls.
  double normal_size(double d) const {
    return d <= thickness ? h0 + rate * d : h0 + rate * thickness + interior_rate * (d - thickness);
  }
  std::vector<double> xyz;         // wall vertices (compacted)
  std::vector<uint32_t> tri;       // wall triangles
  std::vector<double> normal;      // unit face normal per wall triangle
  std::vector<double> vertex_size; // mean incident wall edge length per wall vertex
  openvdb::Int32Grid::Ptr index;   // closest wall triangle per band voxel
  double origin[3] = {0, 0, 0}, inv_dx = 1.0;

  // Among the closest-triangle candidates of the 8 voxels around p, the nearest: its index,
  // the closest point and barycentrics. -1 outside the band.
  int64_t nearest(const double p[3], double q[3], double w[3], double& d2) const {
    openvdb::Int32Grid::ConstUnsafeAccessor acc(index->tree());
    int base[3];
    for (int k = 0; k < 3; ++k) base[k] = int(std::floor((p[k] - origin[k]) * inv_dx));
    int32_t seen[8];
    int nseen = 0;
    int64_t best = -1;
    d2 = HUGE_VAL;
    for (int i = 0; i < 8; ++i) {
      int32_t t;
      if (!acc.probeValue(openvdb::Coord(base[0] + (i & 1), base[1] + ((i >> 1) & 1),
                                         base[2] + ((i >> 2) & 1)),
                          t))
        continue;
      if (t < 0 || size_t(t) >= tri.size() / 3 || std::find(seen, seen + nseen, t) != seen + nseen)
        continue;
      seen[nseen++] = t;
      double qq[3], ww[3];
      const uint32_t* v = &tri[3 * size_t(t)];
      closest_point_on_triangle(p, &xyz[3 * v[0]], &xyz[3 * v[1]], &xyz[3 * v[2]], qq, ww);
      const double e[3] = {p[0] - qq[0], p[1] - qq[1], p[2] - qq[2]};
      const double dd = dot3(e, e);
      if (dd < d2) {
        d2 = dd;
        best = t;
        std::copy(qq, qq + 3, q);
        std::copy(ww, ww + 3, w);
      }
    }
    return best;
  }
};

using Layer = BoundaryLayerField::Impl;

void delete_layer(Layer* layer) { delete layer; }

Status create_layer(const SurfaceMesh& surface, const SizingField& background,
                    const BoundaryLayerOptions& o, BoundaryLayerStats* stats, Layer** out) {
  if (!(o.first_height > 0.0) || !std::isfinite(o.first_height))
    return Status(Error::InvalidArgument, "boundary layer: the first height must be > 0");
  if (!(o.growth > 1.0) || !std::isfinite(o.growth))
    return Status(Error::InvalidArgument, "boundary layer: the growth ratio must be > 1");
  if (!(o.far_size >= 0.0) || !(o.voxel_size >= 0.0))
    return Status(Error::InvalidArgument, "boundary layer: far_size and voxel_size must be >= 0");
  if (!(o.layers_thickness >= 0.0) || !std::isfinite(o.layers_thickness))
    return Status(Error::InvalidArgument, "boundary layer: the layers' thickness must be >= 0");
  if (o.interior_growth != 0.0 && !(o.interior_growth >= o.growth && std::isfinite(o.interior_growth)))
    return Status(Error::InvalidArgument, "boundary layer: the interior growth must be 0 or at least the growth ratio");
  auto impl = std::make_unique<Layer>();
  impl->background = &background;
  impl->h0 = o.first_height;
  impl->rate = o.growth - 1.0;
  impl->thickness = o.interior_growth > 0.0 ? o.layers_thickness : HUGE_VAL;
  impl->interior_rate = o.interior_growth > 0.0 ? o.interior_growth - 1.0 : impl->rate;

  // Wall triangles and their vertices, compacted.
  const size_t nv = surface.num_vertices();
  std::unordered_map<uint32_t, uint32_t> remap;
  for (size_t t = 0; t < surface.num_triangles(); ++t) {
    const int32_t label = t < surface.patch.size() ? surface.patch[t] : 0;
    if (!o.wall_patches.empty() &&
        std::find(o.wall_patches.begin(), o.wall_patches.end(), label) == o.wall_patches.end())
      continue;
    uint32_t v[3];
    for (int k = 0; k < 3; ++k) {
      const uint32_t s = surface.tri[3 * t + k];
      if (s >= nv) return Status(Error::BadIndex, "boundary layer: triangle " + std::to_string(t) +
                                                     " refers to a missing vertex");
      auto it = remap.find(s);
      if (it == remap.end()) {
        it = remap.emplace(s, uint32_t(impl->xyz.size() / 3)).first;
        const double* p = surface.point(s);
        for (int c = 0; c < 3; ++c) {
          if (!std::isfinite(p[c]))
            return Status(Error::NonFiniteCoordinate, "boundary layer: vertex " + std::to_string(s));
          impl->xyz.push_back(p[c]);
        }
      }
      v[k] = it->second;
    }
    const double* a = &impl->xyz[3 * v[0]];
    const double* b = &impl->xyz[3 * v[1]];
    const double* c = &impl->xyz[3 * v[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double len = std::sqrt(dot3(n, n));
    if (!(len > 0.0)) continue;  // degenerate: no normal, and its edges are covered by others
    for (double& x : n) x /= len;
    impl->tri.insert(impl->tri.end(), v, v + 3);
    impl->normal.insert(impl->normal.end(), n, n + 3);
  }
  const size_t nt = impl->tri.size() / 3, nw = impl->xyz.size() / 3;
  if (nt == 0) return Status(Error::EmptyInput, "boundary layer: no (non-degenerate) wall triangle");

  // Per-vertex sizes: the mean length of the incident wall edges (each seen from its triangles).
  std::vector<double> sum(nw, 0.0);
  std::vector<uint32_t> count(nw, 0);
  double area = 0.0, edge_sum = 0.0;
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t* v = &impl->tri[3 * t];
    for (int k = 0; k < 3; ++k) {
      const double* a = &impl->xyz[3 * v[k]];
      const double* b = &impl->xyz[3 * v[(k + 1) % 3]];
      const double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
      const double len = std::sqrt(dot3(e, e));
      sum[v[k]] += len;
      sum[v[(k + 1) % 3]] += len;
      count[v[k]] += 1;
      count[v[(k + 1) % 3]] += 1;
      edge_sum += len;
    }
    const double* a = &impl->xyz[3 * v[0]];
    const double* b = &impl->xyz[3 * v[1]];
    const double* c = &impl->xyz[3 * v[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                         u[0] * w[1] - u[1] * w[0]};
    area += 0.5 * std::sqrt(dot3(n, n));
  }
  impl->vertex_size.resize(nw);
  for (size_t v = 0; v < nw; ++v) impl->vertex_size[v] = count[v] ? sum[v] / count[v] : 0.0;

  // Band distance: where h_n reaches far_size.
  double far = o.far_size;
  if (far == 0.0) {
    for (size_t v = 0; v < nw; ++v) {
      double m[6];
      background.metric(&impl->xyz[3 * v], m);
      far = std::max(far, 2.0 * largest_size(m));
    }
  }
  if (!(far > o.first_height) || !std::isfinite(far))
    return Status(Error::InvalidArgument,
                  "boundary layer: far_size must exceed the first height (and the background be "
                  "SPD at the walls)");
  const double top = impl->normal_size(std::min(impl->thickness, (far - o.first_height) / impl->rate));
  impl->band = far <= top ? (far - o.first_height) / impl->rate
                          : impl->thickness + (far - top) / impl->interior_rate;

  // Voxel size: the mean wall edge, grown until the band's estimated voxel count fits.
  double dx = o.voxel_size > 0.0 ? o.voxel_size : edge_sum / double(3 * nt);
  const double band_volume = area * 2.0 * (impl->band + dx) + 8.0 * dx * dx * dx * double(nt);
  if (band_volume / (dx * dx * dx) > double(o.max_voxels))
    dx = std::cbrt(band_volume / double(o.max_voxels)) * 1.05;
  const float band_voxels = float(std::ceil(impl->band / dx) + 2.0);
  try {
    openvdb::initialize();
    openvdb::math::Transform::Ptr xf = openvdb::math::Transform::createLinearTransform(dx);
    impl->index = openvdb::Int32Grid::create(-1);
    const WallAdapter mesh{&impl->xyz, &impl->tri, xf.get()};
    openvdb::FloatGrid::Ptr dist = openvdb::tools::meshToVolume<openvdb::FloatGrid>(
        mesh, *xf, band_voxels, band_voxels, openvdb::tools::UNSIGNED_DISTANCE_FIELD,
        impl->index.get());
    impl->index->setTransform(xf);
    impl->inv_dx = 1.0 / dx;
    if (stats) stats->memory_bytes = size_t(impl->index->memUsage());
  } catch (const std::bad_alloc&) {
    return Status(Error::OutOfMemory, "boundary layer: out of memory building the level set");
  } catch (const std::exception& e) {
    return Status(Error::Internal, std::string("boundary layer: OpenVDB: ") + e.what());
  }
  if (stats) {
    stats->wall_triangles = nt;
    stats->band_distance = impl->band;
    stats->voxel_size = dx;
    stats->band_voxels = size_t(impl->index->activeVoxelCount());
  }
  *out = impl.release();
  return Status::success();
}

bool layer_wall_distance(const Layer& f, const double p[3], double& d, double closest[3]) {
  double w[3], d2;
  if (f.nearest(p, closest, w, d2) < 0) return false;
  d = std::sqrt(d2);
  return d <= f.band;
}

void layer_metric(const Layer& f, const double p[3], double m[6]) {
  double bg[6];
  f.background->metric(p, bg);
  double q[3], w[3], d2;
  const int64_t t = f.nearest(p, q, w, d2);
  const double d = std::sqrt(d2);
  if (t < 0 || !(d <= f.band)) {
    std::copy(bg, bg + 6, m);
    return;
  }
  // Normal: from the closest wall point, or the face's on the wall (same direction inside faces).
  double n[3];
  if (d > 1e-12 * f.h0) {
    for (int k = 0; k < 3; ++k) n[k] = (p[k] - q[k]) / d;
  } else {
    std::copy(&f.normal[3 * size_t(t)], &f.normal[3 * size_t(t)] + 3, n);
  }
  const uint32_t* v = &f.tri[3 * size_t(t)];
  const double hs =
      w[0] * f.vertex_size[v[0]] + w[1] * f.vertex_size[v[1]] + w[2] * f.vertex_size[v[2]];
  const double hn = f.normal_size(d);
  const double ht = std::max(hs, hn);
  const double a = 1.0 / (hn * hn) - 1.0 / (ht * ht), iso = 1.0 / (ht * ht);
  const double bl[6] = {iso + a * n[0] * n[0], a * n[0] * n[1], iso + a * n[1] * n[1],
                        a * n[0] * n[2],       a * n[1] * n[2], iso + a * n[2] * n[2]};
  if (!intersect(bl, bg, m)) std::copy(bg, bg + 6, m);
}

}  // namespace metric
}  // namespace anitet
