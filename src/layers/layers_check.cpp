#include "layers/layers_check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <unordered_map>
#include <vector>

#include "core/bvh.hpp"
#include "layers/geometry.hpp"
#include "validate/tri_intersect.hpp"

namespace anitet {

namespace {

using Facets = std::map<std::array<uint32_t, 3>, std::array<uint32_t, 3>>;  // sorted -> oriented

std::array<uint32_t, 3> sorted(const uint32_t* t) {
  std::array<uint32_t, 3> k = {t[0], t[1], t[2]};
  std::sort(k.begin(), k.end());
  return k;
}

bool same_cycle(const std::array<uint32_t, 3>& a, const uint32_t* b) {
  for (int r = 0; r < 3; ++r)
    if (a[r] == b[0] && a[(r + 1) % 3] == b[1] && a[(r + 2) % 3] == b[2]) return true;
  return false;
}

// Signed volume of a closed triangle set, about the point o (for round-off).
long double surface_volume(const std::vector<double>& xyz, const std::vector<uint32_t>& tri,
                           const double* o) {
  long double sum = 0.0L;
  for (size_t t = 0; 3 * t < tri.size(); ++t) {
    long double p[3][3];
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) p[i][k] = (long double)xyz[3 * size_t(tri[3 * t + i]) + k] - o[k];
    sum += p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) -
           p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
           p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
  }
  return sum / 6.0L;
}

// Closed, each directed edge once with its twin present, and one fan around every vertex.
bool closed_oriented_manifold(const std::vector<uint32_t>& tri, std::string& why) {
  std::unordered_map<uint64_t, uint32_t> directed;
  for (size_t t = 0; 3 * t < tri.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint64_t key = (uint64_t(tri[3 * t + k]) << 32) | tri[3 * t + (k + 1) % 3];
      if (!directed.emplace(key, uint32_t(t)).second) {
        why = "S1 uses edge (" + std::to_string(key >> 32) + ", " +
              std::to_string(key & 0xffffffffu) + ") twice in one direction";
        return false;
      }
    }
  for (const auto& [key, t] : directed)
    if (directed.find((key << 32) | (key >> 32)) == directed.end()) {
      why = "S1 is open at the edge of triangle " + std::to_string(t);
      return false;
    }
  // Around v, corner (v, x, y) maps x -> y; one cycle through all corners means one fan.
  std::unordered_map<uint32_t, std::vector<std::pair<uint32_t, uint32_t>>> corners;
  for (size_t t = 0; 3 * t < tri.size(); ++t)
    for (int k = 0; k < 3; ++k)
      corners[tri[3 * t + k]].emplace_back(tri[3 * t + (k + 1) % 3], tri[3 * t + (k + 2) % 3]);
  for (auto& [v, c] : corners) {
    std::unordered_map<uint32_t, uint32_t> next(c.begin(), c.end());
    uint32_t x = c[0].first;
    size_t steps = 0;
    do {
      x = next[x];
      ++steps;
    } while (x != c[0].first && steps <= c.size());
    if (steps != c.size()) {
      why = "S1 is not manifold at vertex " + std::to_string(v);
      return false;
    }
  }
  return true;
}

}  // namespace

LayersCheck check_layers(const SurfaceMesh& s, const LayersOutput& out) {
  LayersCheck r;
  auto note = [&](const std::string& what) {
    if (r.problems.size() < 600) r.problems += (r.problems.empty() ? "" : "; ") + what;
  };
  const TetMesh& m = out.mesh;
  const size_t nv = s.num_vertices();

  Status st = check_mesh(m);
  r.mesh_valid = st.ok() && m.free_tets.empty();
  if (!r.mesh_valid) note(st.ok() ? "T1 has deleted tet slots" : st.message());

  r.input_vertices_kept = m.num_vertices() >= nv;
  for (size_t v = 0; v < nv && r.input_vertices_kept; ++v)
    r.input_vertices_kept = std::equal(s.point(v), s.point(v) + 3, m.point(uint32_t(v))) &&
                            (m.vflags[v] & vflag::kOnInputSurface) != 0;
  for (size_t v = nv; v < m.num_vertices() && r.input_vertices_kept; ++v)
    r.input_vertices_kept = (m.vflags[v] & vflag::kOnInputSurface) == 0;
  if (!r.input_vertices_kept) note("T1 does not start with S's vertices");

  // T1's unmatched facets, oriented like the front (normal into the tet = kFacetVertex order).
  Facets open;
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
    if (m.is_deleted(t)) continue;
    for (int i = 0; i < 4; ++i) {
      if (m.tet_adj[4 * size_t(t) + i] != TetMesh::kNoNeighbour) continue;
      const uint32_t f[3] = {m.vertex(t, kFacetVertex[i][0]), m.vertex(t, kFacetVertex[i][1]),
                             m.vertex(t, kFacetVertex[i][2])};
      open[sorted(f)] = {f[0], f[1], f[2]};
    }
  }
  // S's triangle (a, b, c) faces out of the material, i.e. away from its tet: the reverse cycle.
  r.input_faces_present = true;
  for (size_t t = 0; t < s.num_triangles(); ++t) {
    const uint32_t* f = &s.tri[3 * t];
    const uint32_t rev[3] = {f[0], f[2], f[1]};
    auto it = open.find(sorted(f));
    if (it == open.end() || !same_cycle(it->second, rev)) {
      if (r.input_faces_present) note("input triangle " + std::to_string(t) + " is not a T1 boundary facet on the right side");
      r.input_faces_present = false;
    }
  }
  // S1's triangles face away from the region still to mesh: into their tet, the same cycle.
  r.boundary_is_s_and_s1 = open.size() == s.num_triangles() + out.num_front_triangles();
  for (size_t i = 0; i < out.num_front_triangles(); ++i) {
    auto it = open.find(sorted(&out.front_tri[3 * i]));
    if (it == open.end() || !same_cycle(it->second, &out.front_tri[3 * i]))
      r.boundary_is_s_and_s1 = false;
  }
  if (!r.boundary_is_s_and_s1) note("T1's boundary facets are not exactly S and S1");

  std::string why;
  r.front_manifold = closed_oriented_manifold(out.front_tri, why);
  if (!r.front_manifold) note(why);

  r.front_off_input = true;
  for (uint32_t v : out.front_tri) r.front_off_input = r.front_off_input && v >= nv;
  if (!r.front_off_input) note("S1 uses a vertex of S");

  r.front_tets_match = out.front_tet.size() == out.num_front_triangles() &&
                       out.front_facet.size() == out.num_front_triangles();
  for (size_t i = 0; i < out.num_front_triangles() && r.front_tets_match; ++i) {
    const uint32_t t = out.front_tet[i];
    const int f = out.front_facet[i];
    r.front_tets_match = t < m.num_tet_slots() && f < 4 &&
                         same_cycle({m.vertex(t, kFacetVertex[f][0]), m.vertex(t, kFacetVertex[f][1]),
                                     m.vertex(t, kFacetVertex[f][2])},
                                    &out.front_tri[3 * i]);
  }
  if (!r.front_tets_match) note("front_tet/front_facet do not name S1's triangles");

  // Exact: no S1 triangle meets an S triangle (they share no vertex, so any contact counts).
  TriangleBVH bvh;
  bvh.build(s.xyz.data(), s.tri.data(), s.num_triangles());
  r.front_disjoint = true;
  for (size_t i = 0; i < out.num_front_triangles() && r.front_disjoint; ++i) {
    const double* q[3];
    Box3 box;
    for (int k = 0; k < 3; ++k) q[k] = m.point(out.front_tri[3 * i + k]);
    for (int k = 0; k < 3; ++k) {
      box.lo[k] = std::min({q[0][k], q[1][k], q[2][k]});
      box.hi[k] = std::max({q[0][k], q[1][k], q[2][k]});
    }
    bvh.query(box, [&](size_t t) {
      const double* p[3] = {s.point(s.tri[3 * t]), s.point(s.tri[3 * t + 1]),
                            s.point(s.tri[3 * t + 2])};
      if (tri_intersect::triangles_intersect(p, q)) {
        r.front_disjoint = false;
        note("S1 triangle " + std::to_string(i) + " meets input triangle " + std::to_string(t));
        return false;
      }
      return true;
    });
  }

  // Volumes about the centre of S's box.
  double o[3] = {0, 0, 0};
  if (nv > 0) {
    double lo[3], hi[3];
    std::copy_n(s.point(0), 3, lo);
    std::copy_n(s.point(0), 3, hi);
    for (size_t v = 1; v < nv; ++v)
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], s.point(v)[k]);
        hi[k] = std::max(hi[k], s.point(v)[k]);
      }
    for (int k = 0; k < 3; ++k) o[k] = 0.5 * (lo[k] + hi[k]);
  }
  long double vt = 0.0L;
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
    if (m.is_deleted(t)) continue;
    long double p[4][3];
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) p[i][k] = (long double)m.point(m.vertex(t, i))[k] - o[k];
    long double e[3][3];
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) e[i][k] = p[i + 1][k] - p[0][k];
    vt += (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
           e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
           e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) / 6.0L;
  }
  const long double vs = surface_volume(s.xyz, s.tri, o);
  const long double vs1 = surface_volume(m.xyz, out.front_tri, o);
  r.volume_t1 = double(vt);
  r.volume_s = double(vs);
  r.volume_s1 = double(vs1);
  r.volume_rel_error = double(std::fabs(vt - (vs - vs1)) / std::max(std::fabs(vs), 1e-300L));
  return r;
}

LayersQuality layers_quality(const LayersOutput& out) {
  LayersQuality q;
  const TetMesh& m = out.mesh;
  double sum = 0.0;
  q.min = 1.0;
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
    if (m.is_deleted(t)) continue;
    const double rr = layers::radius_ratio(m.point(m.vertex(t, 0)), m.point(m.vertex(t, 1)),
                                           m.point(m.vertex(t, 2)), m.point(m.vertex(t, 3)));
    sum += rr;
    q.min = std::min(q.min, rr);
    q.below_0_05 += rr < 0.05;
    q.below_0_1 += rr < 0.1;
    q.above_0_4 += rr > 0.4;
    ++q.tets;
  }
  q.mean = q.tets ? sum / double(q.tets) : 0.0;
  if (q.tets == 0) q.min = 0.0;
  return q;
}

double triangle_quality(const double* a, const double* b, const double* c) {
  double n[3];
  const double area = 0.5 * layers::unit_normal(a, b, c, n);
  double sq = 0.0;
  for (int k = 0; k < 3; ++k)
    sq += (b[k] - a[k]) * (b[k] - a[k]) + (c[k] - b[k]) * (c[k] - b[k]) + (a[k] - c[k]) * (a[k] - c[k]);
  return sq > 0.0 ? 4.0 * std::sqrt(3.0) * area / sq : 0.0;
}

WorstTets worst_tets(const SurfaceMesh& surface, const LayersOutput& out, size_t k) {
  WorstTets w;
  const size_t nt = surface.num_triangles();
  if (nt == 0) return w;
  std::vector<double> tq(nt);
  for (size_t t = 0; t < nt; ++t)
    tq[t] = triangle_quality(surface.point(surface.tri[3 * t]), surface.point(surface.tri[3 * t + 1]),
                             surface.point(surface.tri[3 * t + 2]));
  std::vector<double> sorted = tq;
  std::sort(sorted.begin(), sorted.end());
  w.input_quality_min = sorted.front();
  w.input_quality_median = sorted[nt / 2];
  const TetMesh& m = out.mesh;
  std::vector<std::pair<double, uint32_t>> q;
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
    if (m.is_deleted(t)) continue;
    q.emplace_back(layers::radius_ratio(m.point(m.vertex(t, 0)), m.point(m.vertex(t, 1)),
                                        m.point(m.vertex(t, 2)), m.point(m.vertex(t, 3))),
                   t);
  }
  k = std::min(k, q.size());
  std::partial_sort(q.begin(), q.begin() + ptrdiff_t(k), q.end());
  std::vector<double> ranks;
  for (size_t i = 0; i < k; ++i) {
    WorstTet x;
    x.tet = q[i].second;
    x.radius_ratio = q[i].first;
    x.layer = x.tet < out.tet_layer.size() ? out.tet_layer[x.tet] : 0;
    x.column = x.tet < out.tet_column.size() ? out.tet_column[x.tet] : 0;
    if (x.column < nt) {
      x.column_quality = tq[x.column];
      x.column_rank = double(std::lower_bound(sorted.begin(), sorted.end(), tq[x.column]) -
                             sorted.begin()) / double(nt);
    }
    ranks.push_back(x.column_rank);
    w.tets.push_back(x);
  }
  if (!ranks.empty()) {
    std::sort(ranks.begin(), ranks.end());
    w.median_rank = ranks[ranks.size() / 2];
  }
  return w;
}

}  // namespace anitet
