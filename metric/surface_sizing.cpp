#include "surface_sizing.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/closest_point.hpp"

namespace anitet {
namespace metric {
namespace {

inline void sub(const double a[3], const double b[3], double r[3]) {
  r[0] = a[0] - b[0];
  r[1] = a[1] - b[1];
  r[2] = a[2] - b[2];
}
inline double dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline void cross(const double a[3], const double b[3], double r[3]) {
  r[0] = a[1] * b[2] - a[2] * b[1];
  r[1] = a[2] * b[0] - a[0] * b[2];
  r[2] = a[0] * b[1] - a[1] * b[0];
}
inline double dist(const double* a, const double* b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

// Separated along `axis` when the triangle's projection misses [-r, r].
inline bool separated(const double axis[3], const double v[3][3], double half) {
  const double p0 = dot(axis, v[0]), p1 = dot(axis, v[1]), p2 = dot(axis, v[2]);
  const double r = half * (std::fabs(axis[0]) + std::fabs(axis[1]) + std::fabs(axis[2]));
  return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
}

}  // namespace

bool triangle_cuts_box(const double a[3], const double b[3], const double c[3],
                       const double centre[3], double half) {
  half *= 1.0 + 1e-9;
  double v[3][3];
  sub(a, centre, v[0]);
  sub(b, centre, v[1]);
  sub(c, centre, v[2]);
  // The box's face normals.
  for (int k = 0; k < 3; ++k) {
    const double lo = std::min({v[0][k], v[1][k], v[2][k]});
    const double hi = std::max({v[0][k], v[1][k], v[2][k]});
    if (lo > half || hi < -half) return false;
  }
  double e[3][3];
  sub(v[1], v[0], e[0]);
  sub(v[2], v[1], e[1]);
  sub(v[0], v[2], e[2]);
  // The triangle's normal.
  double n[3];
  cross(e[0], e[1], n);
  if (separated(n, v, half)) return false;
  // Box edges x triangle edges.
  for (int k = 0; k < 3; ++k) {
    const double unit[3] = {k == 0 ? 1.0 : 0.0, k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0};
    for (int t = 0; t < 3; ++t) {
      double axis[3];
      cross(unit, e[t], axis);
      if (separated(axis, v, half)) return false;
    }
  }
  return true;
}

namespace {

struct Box {
  double lo[3], hi[3];
};

// The surface's box; Error::InvalidArgument for a vertex that is not finite.
Result<Box> surface_box(const SurfaceMesh& surface) {
  Box box;
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = std::numeric_limits<double>::infinity();
    box.hi[k] = -box.lo[k];
  }
  for (size_t v = 0; v < surface.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k) {
      const double x = surface.xyz[3 * v + k];
      if (!std::isfinite(x)) return Status(Error::InvalidArgument, "vertex " + std::to_string(v) + " is not finite");
      box.lo[k] = std::min(box.lo[k], x);
      box.hi[k] = std::max(box.hi[k], x);
    }
  return box;
}

// Each triangle's size (its shortest or mean edge), and the voxel size when none is given: the
// mean edge length, unless a few long edges (needle fans, long CAD strips) make it more than
// twice the median, for the grid must resolve the sizes of most triangles (else a rotated copy
// of a CAD part gets far fewer tets than the part).
Status triangle_sizes(const SurfaceMesh& surface, const SurfaceSizingOptions& options, std::vector<double>& tri_size,
                      double& voxel) {
  const size_t nt = surface.num_triangles(), nv = surface.num_vertices();
  tri_size.resize(nt);
  std::vector<double> edge_lengths(options.voxel_size > 0.0 ? 0 : 3 * nt);
  double edge_sum = 0.0;
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t* f = &surface.tri[3 * t];
    if (f[0] >= nv || f[1] >= nv || f[2] >= nv)
      return Status(Error::BadIndex, "triangle " + std::to_string(t) + " has a bad vertex index");
    const double l0 = dist(surface.point(f[0]), surface.point(f[1]));
    const double l1 = dist(surface.point(f[1]), surface.point(f[2]));
    const double l2 = dist(surface.point(f[2]), surface.point(f[0]));
    edge_sum += l0 + l1 + l2;
    if (!edge_lengths.empty()) {
      edge_lengths[3 * t] = l0;
      edge_lengths[3 * t + 1] = l1;
      edge_lengths[3 * t + 2] = l2;
    }
    tri_size[t] = options.triangle_size == TriangleSize::Shortest ? std::min({l0, l1, l2}) : (l0 + l1 + l2) / 3.0;
  }
  voxel = options.voxel_size;
  if (!(voxel > 0.0)) {
    auto mid = edge_lengths.begin() + std::ptrdiff_t(edge_lengths.size() / 2);
    std::nth_element(edge_lengths.begin(), mid, edge_lengths.end());
    voxel = std::min(edge_sum / (3.0 * double(nt)), 2.0 * *mid);
  }
  if (!(voxel > 0.0)) return Status(Error::InvalidArgument, "the surface has only zero-length edges");
  return Status::success();
}

// The lattice over the box (padded), its voxel grown until it fits options.max_voxels, the box
// centred in it; every value infinite.
Lattice empty_lattice(const Box& box, double h, const SurfaceSizingOptions& options) {
  Lattice lat;
  for (;;) {
    size_t count = 1;
    for (int k = 0; k < 3; ++k) {
      const double n = std::floor((box.hi[k] - box.lo[k]) / h) + 1 + 2 * options.padding;
      lat.dims[k] = n > 1e9 ? 1000000000 : int(n);
      count *= size_t(lat.dims[k]);
    }
    if (count <= options.max_voxels) break;
    h *= std::cbrt(double(count) / double(options.max_voxels)) * 1.001;
  }
  lat.spacing = h;
  lat.components = 1;
  for (int k = 0; k < 3; ++k) lat.origin[k] = 0.5 * (box.lo[k] + box.hi[k]) - 0.5 * h * (lat.dims[k] - 1);
  lat.values.assign(lat.num_nodes(), std::numeric_limits<double>::infinity());
  return lat;
}

// The nodes the surface pins (their size the smallest of the triangles pinning them), marked
// in `pinned`; whether any was.
bool pin_nodes(Lattice& lat, const SurfaceMesh& surface, const std::vector<double>& tri_size, Pinning pinning,
               std::vector<uint8_t>& pinned) {
  const double h = lat.spacing, half = 0.5 * h;
  const double band = half * (1.0 + 1e-9);  // touching counts, as for the cube test
  bool any = false;
  for (size_t t = 0; t < surface.num_triangles(); ++t) {
    const double* p[3] = {surface.point(surface.tri[3 * t]), surface.point(surface.tri[3 * t + 1]),
                          surface.point(surface.tri[3 * t + 2])};
    int b0[3], b1[3];
    for (int k = 0; k < 3; ++k) {
      const double mn = std::min({p[0][k], p[1][k], p[2][k]}) - lat.origin[k];
      const double mx = std::max({p[0][k], p[1][k], p[2][k]}) - lat.origin[k];
      b0[k] = std::max(0, int(std::floor(mn / h - 0.5)));
      b1[k] = std::min(lat.dims[k] - 1, int(std::ceil(mx / h + 0.5)));
    }
    for (int k = b0[2]; k <= b1[2]; ++k)
      for (int j = b0[1]; j <= b1[1]; ++j)
        for (int i = b0[0]; i <= b1[0]; ++i) {
          double c[3];
          lat.position(i, j, k, c);
          const bool pin = pinning == Pinning::HalfVoxelBand ? point_triangle_distance(c, p[0], p[1], p[2]) <= band
                                                             : triangle_cuts_box(p[0], p[1], p[2], c, half);
          if (!pin) continue;
          const size_t n = lat.node(i, j, k);
          pinned[n] = 1;
          any = true;
          lat.values[n] = std::min(lat.values[n], tri_size[t]);
        }
  }
  return any;
}

// drop_outside: the nodes reachable from the lattice's faces without crossing a pinned one are
// outside (skip 2, inactive), but for the shell of those among the 26 neighbours of a pinned
// node, which are kept.
void drop_outside(Lattice& lat, std::vector<uint8_t>& skip, SurfaceSizingStats& stats) {
  const int nx = lat.dims[0], ny = lat.dims[1], nz = lat.dims[2];
  const size_t sy = size_t(nx), sz = size_t(nx) * ny, nn = lat.num_nodes();
  std::vector<size_t> stack;
  auto visit = [&](size_t n) {
    if (skip[n] == 0) {
      skip[n] = 2;
      stack.push_back(n);
    }
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        if (i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1) visit(lat.node(i, j, k));
  while (!stack.empty()) {
    const size_t n = stack.back();
    stack.pop_back();
    const int i = int(n % sy), j = int((n / sy) % size_t(ny)), k = int(n / sz);
    if (i > 0) visit(n - 1);
    if (i + 1 < nx) visit(n + 1);
    if (j > 0) visit(n - sy);
    if (j + 1 < ny) visit(n + sy);
    if (k > 0) visit(n - sz);
    if (k + 1 < nz) visit(n + sz);
  }
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (skip[lat.node(i, j, k)] != 1) continue;
        for (int c = std::max(k - 1, 0); c <= std::min(k + 1, nz - 1); ++c)
          for (int b = std::max(j - 1, 0); b <= std::min(j + 1, ny - 1); ++b)
            for (int a = std::max(i - 1, 0); a <= std::min(i + 1, nx - 1); ++a) {
              uint8_t& st = skip[lat.node(a, b, c)];
              if (st == 2) st = 3;
            }
      }
  lat.active.assign(nn, 1);
  for (size_t n = 0; n < nn; ++n) {
    if (skip[n] == 3) skip[n] = 0;
    if (skip[n] == 2) {
      lat.active[n] = 0;
      ++stats.dropped;
    }
  }
  stats.working_bytes += nn;
}

// One Gauss-Seidel pass of the 6-neighbour average (one-sided at the lattice's faces); skipped
// nodes are never written (the pinned ones: the paper's reset). The largest change.
double laplacian_pass(Lattice& lat, const std::vector<uint8_t>& skip, double w) {
  const int nx = lat.dims[0], ny = lat.dims[1], nz = lat.dims[2];
  const size_t sy = size_t(nx), sz = size_t(nx) * ny;
  double change = 0.0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const size_t n = lat.node(i, j, k);
        if (skip[n]) continue;
        double s = 0.0;
        int c = 0;
        // Dropped neighbours count as absent, like those beyond the lattice's faces.
        if (i > 0 && skip[n - 1] != 2) s += lat.values[n - 1], ++c;
        if (i + 1 < nx && skip[n + 1] != 2) s += lat.values[n + 1], ++c;
        if (j > 0 && skip[n - sy] != 2) s += lat.values[n - sy], ++c;
        if (j + 1 < ny && skip[n + sy] != 2) s += lat.values[n + sy], ++c;
        if (k > 0 && skip[n - sz] != 2) s += lat.values[n - sz], ++c;
        if (k + 1 < nz && skip[n + sz] != 2) s += lat.values[n + sz], ++c;
        if (c == 0) continue;
        const double old = lat.values[n];
        const double next = old + w * (s / c - old);
        lat.values[n] = next;
        change = std::max(change, std::fabs(next - old));
      }
  return change;
}

// A separable [1 2 1]/4 blur along x, y, z (clamped at the faces), then the skipped nodes reset.
// The largest change.
double gaussian_pass(Lattice& lat, const std::vector<uint8_t>& skip, std::vector<double>& tmp) {
  const int nx = lat.dims[0], ny = lat.dims[1], nz = lat.dims[2];
  const std::vector<double> before = lat.values;
  const size_t stride[3] = {1, size_t(nx), size_t(nx) * ny};
  for (int axis = 0; axis < 3; ++axis) {
    const int len = lat.dims[axis];
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const int idx[3] = {i, j, k};
          const size_t n = lat.node(i, j, k);
          const bool has_l = idx[axis] > 0 && skip[n - stride[axis]] != 2;
          const bool has_r = idx[axis] + 1 < len && skip[n + stride[axis]] != 2;
          const double l = has_l ? lat.values[n - stride[axis]] : lat.values[n];
          const double r = has_r ? lat.values[n + stride[axis]] : lat.values[n];
          tmp[n] = 0.25 * (l + r) + 0.5 * lat.values[n];
        }
    lat.values.swap(tmp);
  }
  double change = 0.0;
  for (size_t n = 0; n < lat.num_nodes(); ++n) {
    if (skip[n]) lat.values[n] = before[n];
    else change = std::max(change, std::fabs(lat.values[n] - before[n]));
  }
  return change;
}

}  // namespace

Result<Lattice> surface_sizing(const SurfaceMesh& surface, const SurfaceSizingOptions& options,
                               SurfaceSizingStats* stats_out) {
  if (surface.num_triangles() == 0) return Status(Error::EmptyInput, "the surface has no triangle");
  if (!(options.tolerance > 0.0) || options.max_iterations < 1 || options.padding < 0 ||
      !(options.relaxation > 0.0 && options.relaxation < 2.0) || options.max_voxels < 8)
    return Status(Error::InvalidArgument, "bad surface sizing options");
  Result<Box> box = surface_box(surface);
  if (!box.ok()) return box.status();
  std::vector<double> tri_size;
  double h = 0.0;
  if (Status st = triangle_sizes(surface, options, tri_size, h); !st.ok()) return st;
  Lattice lat = empty_lattice(box.value(), h, options);
  const size_t nn = lat.num_nodes();
  std::vector<uint8_t> pinned(nn, 0);
  // A surface whose band holds no node at all (small, lying between the nodes of a voxel grown
  // by max_voxels far beyond its triangles) is pinned by the cube test, which always pins.
  SurfaceSizingStats stats;
  if (!pin_nodes(lat, surface, tri_size, options.pinning, pinned) && options.pinning == Pinning::HalfVoxelBand)
    stats.cube_fallback = pin_nodes(lat, surface, tri_size, Pinning::CutCube, pinned);
  stats.voxels = nn;
  stats.voxel_size = lat.spacing;
  stats.working_bytes = nn * (sizeof(double) + 1);
  double sum = 0.0;
  for (size_t n = 0; n < nn; ++n)
    if (pinned[n]) {
      ++stats.pinned;
      sum += lat.values[n];
    }
  if (stats.pinned == 0) return Status(Error::Internal, "no voxel is pinned by the surface");
  const double mean = sum / double(stats.pinned);
  stats.mean_size = mean;
  for (size_t n = 0; n < nn; ++n)
    if (!pinned[n]) lat.values[n] = mean;
  // skip[n]: pinned (1) or dropped (2): never written by the smoothing.
  std::vector<uint8_t>& skip = pinned;
  if (options.drop_outside) drop_outside(lat, skip, stats);
  std::vector<double> tmp;
  if (options.smoothing == Smoothing::Gaussian) {
    tmp.resize(nn);
    stats.working_bytes += nn * sizeof(double);
  }
  const double stop = options.tolerance * mean;
  double change = std::numeric_limits<double>::infinity();
  int it = 0;
  while (it < options.max_iterations && !(change < stop)) {
    ++it;
    change = options.smoothing == Smoothing::Laplacian ? laplacian_pass(lat, skip, options.relaxation)
                                                       : gaussian_pass(lat, skip, tmp);
  }
  stats.iterations = it;
  stats.converged = change < stop;
  stats.last_change = change / mean;
  if (stats_out) *stats_out = stats;
  return lat;
}

Result<MetricField> surface_sizing_field(const SurfaceMesh& surface,
                                         const SurfaceSizingOptions& options,
                                         SurfaceSizingStats* stats) {
  Result<Lattice> lat = surface_sizing(surface, options, stats);
  if (!lat.ok()) return lat.status();
  return MetricField::from_lattice(lat.value(), options.prune_tolerance);
}

}  // namespace metric
}  // namespace anitet
