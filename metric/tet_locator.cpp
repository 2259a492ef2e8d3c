#include "tet_locator.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <string>
#include <utility>

#include "core/closest_point.hpp"
#include "core/tet_mesh.hpp"

namespace anitet {
namespace metric {

namespace {

// A walk from a start of the grid takes a few steps; one from a far start in a mesh of 10^7 tets
// a few hundred. More means a cycle (possible in floating point and in non-Delaunay meshes).
constexpr int kMaxWalkSteps = 4096;

double det3(const double u[3], const double v[3], const double w[3]) {
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

// Weights clamped to >= 0 and summing to 1 (points within rounding outside a face).
void clamp_weights(double w[4]) {
  double s = 0.0;
  for (int i = 0; i < 4; ++i) s += (w[i] = std::max(w[i], 0.0));
  if (!(s > 0.0)) {
    w[0] = 1.0;
    w[1] = w[2] = w[3] = 0.0;
    return;
  }
  for (int i = 0; i < 4; ++i) w[i] /= s;
}

}  // namespace

Result<TetLocator> TetLocator::create(const VolumeMesh& mesh) {
  const size_t nv = mesh.num_vertices(), nt = mesh.num_tets();
  if (nt == 0) return Status(Error::EmptyInput, "the mesh has no tetrahedron");
  if (nt >= kNoTet / 4) return Status(Error::InvalidArgument, "too many tetrahedra to locate points in");
  for (size_t i = 0; i < mesh.tet.size(); ++i) {
    if (mesh.tet[i] >= nv) {
      return Status(Error::BadIndex, "tet " + std::to_string(i / 4) + " refers to vertex " + std::to_string(mesh.tet[i]) +
                                         " of " + std::to_string(nv));
    }
  }
  // The adjacency as the meshing stages build it (faces paired by their smallest vertex).
  TetMesh tm = TetMesh::from_volume_mesh(mesh);
  if (Status s = tm.build_adjacency(); !s.ok()) return s;
  TetLocator out;
  out.neighbour_.resize(4 * nt);
  for (size_t i = 0; i < 4 * nt; ++i) {
    out.neighbour_[i] = tm.tet_adj[i] == TetMesh::kNoNeighbour ? kNoTet : uint32_t(tm.tet_adj[i] >> 2);
  }
  out.xyz_ = std::move(tm.xyz);
  out.tet_ = std::move(tm.tet_v);
  out.build_start_grid();
  out.build_boundary();
  return out;
}

void TetLocator::build_start_grid() {
  const size_t nt = num_tets();
  box_ = bounding_box(xyz_.data(), num_vertices());
  double ext[3];
  for (int k = 0; k < 3; ++k) {
    lo_[k] = box_.lo[k];
    ext[k] = std::isfinite(box_.hi[k] - box_.lo[k]) ? box_.hi[k] - box_.lo[k] : 0.0;
  }
  const double longest = std::max({ext[0], ext[1], ext[2], 1e-300});
  const double volume = std::max(ext[0] * ext[1] * ext[2], longest * longest * longest * 1e-9);
  // About two mean tets across a cell (a tet of volume s^3 is about 2 s wide): a walk from the
  // cell's tet takes a few steps. At most one cell per tet.
  cell_ = 2.0 * std::cbrt(volume / double(nt));
  for (;;) {
    double cells = 1.0;
    for (int k = 0; k < 3; ++k) {
      dims_[k] = std::max(1, std::min(1024, int(ext[k] / cell_) + 1));
      cells *= dims_[k];
    }
    if (cells <= double(nt) + 64.0) break;
    cell_ *= 1.25;
  }
  const size_t ncell = size_t(dims_[0]) * size_t(dims_[1]) * size_t(dims_[2]);
  cell_tet_.assign(ncell, kNoTet);
  auto cell_of = [&](const double p[3]) {
    size_t c[3];
    for (int k = 0; k < 3; ++k) {
      const double x = (p[k] - lo_[k]) / cell_;
      c[k] = x >= 0.0 ? (x < dims_[k] ? size_t(x) : size_t(dims_[k] - 1)) : 0;
    }
    return (c[2] * size_t(dims_[1]) + c[1]) * size_t(dims_[0]) + c[0];
  };
  for (size_t t = 0; t < nt; ++t) {
    double centroid[3] = {0, 0, 0};
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) centroid[k] += 0.25 * xyz_[3 * size_t(tet_[4 * t + size_t(i)]) + size_t(k)];
    uint32_t& slot = cell_tet_[cell_of(centroid)];
    if (slot == kNoTet) slot = uint32_t(t);
  }
  // Empty cells (holes, corners of the box) take a filled neighbour's tet, breadth first from the
  // filled cells in index order: the same grid every time.
  std::deque<size_t> queue;
  for (size_t c = 0; c < ncell; ++c)
    if (cell_tet_[c] != kNoTet) queue.push_back(c);
  const size_t step[3] = {1, size_t(dims_[0]), size_t(dims_[0]) * size_t(dims_[1])};
  while (!queue.empty()) {
    const size_t c = queue.front();
    queue.pop_front();
    const size_t idx[3] = {c % step[1], (c / step[1]) % size_t(dims_[1]), c / step[2]};
    for (int k = 0; k < 3; ++k) {
      for (int side = 0; side < 2; ++side) {
        if (side == 0 ? idx[k] == 0 : idx[k] + 1 == size_t(dims_[k])) continue;
        const size_t n = side == 0 ? c - step[k] : c + step[k];
        if (cell_tet_[n] == kNoTet) {
          cell_tet_[n] = cell_tet_[c];
          queue.push_back(n);
        }
      }
    }
  }
}

void TetLocator::build_boundary() {
  for (size_t t = 0; t < num_tets(); ++t) {
    for (int i = 0; i < 4; ++i) {
      if (neighbour_[4 * t + size_t(i)] != kNoTet) continue;
      boundary_face_.push_back(uint32_t(4 * t + size_t(i)));
      for (int k = 0; k < 3; ++k) boundary_tri_.push_back(tet_[4 * t + size_t(kFacetVertex[i][k])]);
    }
  }
  boundary_bvh_.build(xyz_.data(), boundary_tri_.data(), boundary_face_.size());
}

bool TetLocator::weights(const double p[3], uint32_t t, double w[4]) const {
  double e[4][3];  // the vertices relative to p: the weights are then exact for p at a vertex
  for (int i = 0; i < 4; ++i) {
    const double* v = &xyz_[3 * size_t(tet_[4 * size_t(t) + size_t(i)])];
    for (int k = 0; k < 3; ++k) e[i][k] = v[k] - p[k];
  }
  // Volume of the tet with p in place of vertex i, over the tet's (the sum of the four).
  const double n[4] = {det3(e[1], e[2], e[3]), -det3(e[0], e[2], e[3]), det3(e[0], e[1], e[3]),
                       -det3(e[0], e[1], e[2])};
  const double sum = n[0] + n[1] + n[2] + n[3];
  if (sum == 0.0 || !std::isfinite(sum)) return false;
  for (int i = 0; i < 4; ++i) w[i] = n[i] / sum;
  return true;
}

bool TetLocator::walk(const double p[3], uint32_t t, Location& out, uint32_t& exit_face) const {
  exit_face = kNoTet;
  for (int step = 0; step < kMaxWalkSteps; ++step) {
    double w[4];
    if (!weights(p, t, w)) return false;
    int most_negative = 0;
    for (int i = 1; i < 4; ++i)
      if (w[i] < w[most_negative]) most_negative = i;
    if (w[most_negative] >= -kInsideTolerance) {
      clamp_weights(w);
      out.tet = t;
      std::copy(w, w + 4, out.weight);
      out.outside = false;
      out.distance = 0.0;
      return true;
    }
    if (!(w[most_negative] < 0.0)) return false;  // NaN weights: p is not a finite point
    const uint32_t next = neighbour_[4 * size_t(t) + size_t(most_negative)];
    if (next == kNoTet) {
      exit_face = 4 * t + uint32_t(most_negative);
      return false;
    }
    t = next;
  }
  return false;
}

uint32_t TetLocator::closest_boundary_face(const double p[3], double bound, double q[3]) const {
  double far = 0.0;  // beyond this radius the query box holds every face
  for (int k = 0; k < 3; ++k) far += std::max(std::abs(p[k] - box_.lo[k]), std::abs(p[k] - box_.hi[k]));
  double r = std::isfinite(bound) ? bound : cell_;
  for (;;) {
    uint32_t best = kNoTet;
    double best_d = HUGE_VAL;
    boundary_bvh_.query(box_around(p, r), [&](uint32_t f) {
      const uint32_t* v = &boundary_tri_[3 * size_t(f)];
      double c[3];
      closest_point_on_triangle(p, &xyz_[3 * size_t(v[0])], &xyz_[3 * size_t(v[1])], &xyz_[3 * size_t(v[2])], c);
      const double d = std::sqrt((p[0] - c[0]) * (p[0] - c[0]) + (p[1] - c[1]) * (p[1] - c[1]) + (p[2] - c[2]) * (p[2] - c[2]));
      if (d < best_d || (d == best_d && f < best)) {
        best_d = d;
        best = f;
        std::copy(c, c + 3, q);
      }
      return true;
    });
    // A face closer than the best found would overlap the box: the best is the closest.
    if (best != kNoTet && best_d <= r) return best;
    if (!(r <= far)) return best;  // (also for a point that is not finite)
    r *= 2.0;
  }
}

uint32_t TetLocator::start_tet(const double p[3]) const {
  size_t c[3];
  for (int k = 0; k < 3; ++k) {
    const double x = (p[k] - lo_[k]) / cell_;
    c[k] = x >= 0.0 ? (x < dims_[k] ? size_t(x) : size_t(dims_[k] - 1)) : 0;
  }
  return cell_tet_[(c[2] * size_t(dims_[1]) + c[1]) * size_t(dims_[0]) + c[0]];
}

TetLocator::Location TetLocator::locate(const double p[3], uint32_t start) const {
  Location out;
  uint32_t exit_face = kNoTet;
  if (walk(p, start < num_tets() ? start : start_tet(p), out, exit_face)) return out;
  // Left the mesh, or no end: from the closest boundary point q (the face left through bounds
  // its distance).
  double bound = HUGE_VAL;
  if (exit_face != kNoTet) {
    const int i = int(exit_face & 3);
    const uint32_t* v = &tet_[4 * size_t(exit_face >> 2)];
    bound = point_triangle_distance(p, &xyz_[3 * size_t(v[kFacetVertex[i][0]])], &xyz_[3 * size_t(v[kFacetVertex[i][1]])],
                                    &xyz_[3 * size_t(v[kFacetVertex[i][2]])]);
  }
  double q[3] = {0, 0, 0};
  const uint32_t f = closest_boundary_face(p, bound, q);
  if (f == kNoTet) {  // p is not a finite point
    out.tet = 0;
    out.outside = true;
    out.distance = HUGE_VAL;
    return out;
  }
  const uint32_t t = boundary_face_[f] >> 2;
  uint32_t ignored = kNoTet;
  if (walk(p, t, out, ignored)) return out;
  out.tet = t;
  if (!weights(q, t, out.weight)) std::fill(out.weight, out.weight + 4, 0.25);  // (a flat boundary tet)
  clamp_weights(out.weight);
  out.outside = true;
  out.distance = std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
  return out;
}

}  // namespace metric
}  // namespace anitet
