// The report's comparison of a volume mesh with the input surface it must keep.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <unordered_map>
#include <utility>

#include <tbb/parallel_invoke.h>

#include "core/bvh.hpp"
#include "core/flat_key_map.hpp"
#include "predicates/predicates.hpp"
#include "quality/parallel_for.hpp"
#include "quality/report_detail.hpp"

namespace anitet::quality_detail {

namespace {

constexpr uint32_t kNone = 0xffffffffu;

// A point's coordinates bit for bit (with -0.0 made +0.0, which compares equal to it).
struct PointKey {
  uint64_t b[3];
  bool operator==(const PointKey& o) const { return b[0] == o.b[0] && b[1] == o.b[1] && b[2] == o.b[2]; }
};
PointKey point_key(const double* p) {
  PointKey k;
  for (int i = 0; i < 3; ++i) {
    const double x = p[i] + 0.0;
    std::memcpy(&k.b[i], &x, sizeof x);
  }
  return k;
}

struct CellKey {
  int64_t c[3];
  bool operator==(const CellKey& o) const { return c[0] == o.c[0] && c[1] == o.c[1] && c[2] == o.c[2]; }
};

struct Hash3 {
  template <class K>
  size_t operator()(const K& k) const {
    uint64_t h = 0x243F6A8885A308D3ull;
    for (int i = 0; i < 3; ++i) {
      uint64_t x;
      std::memcpy(&x, reinterpret_cast<const char*>(&k) + 8 * i, 8);
      h = (h ^ x) * 0x9E3779B97F4A7C15ull;
      h ^= h >> 31;
    }
    return static_cast<size_t>(h);
  }
};

using Tri = std::array<uint32_t, 3>;
Tri sorted(uint32_t a, uint32_t b, uint32_t c) {
  Tri t{a, b, c};
  std::sort(t.begin(), t.end());
  return t;
}

// Exact: p lies on the closed triangle abc (coplanar by orient3d, then inside by orient2d in a
// projection along an axis where the triangle does not collapse). Collinear triangles: false.
bool on_closed_triangle(const double* a, const double* b, const double* c, const double* p) {
  if (predicates::orient3d(a, b, c, p) != 0) return false;
  for (int drop = 0; drop < 3; ++drop) {
    const int u = drop == 0 ? 1 : 0, v = drop == 2 ? 1 : 2;
    const double a2[2] = {a[u], a[v]}, b2[2] = {b[u], b[v]}, c2[2] = {c[u], c[v]}, p2[2] = {p[u], p[v]};
    const int o = predicates::orient2d(a2, b2, c2);
    if (o == 0) continue;
    return predicates::orient2d(a2, b2, p2) * o >= 0 && predicates::orient2d(b2, c2, p2) * o >= 0 &&
           predicates::orient2d(c2, a2, p2) * o >= 0;
  }
  return false;
}

// Canonical input vertex per input vertex: the first one with the same coordinates.
std::vector<uint32_t> canonical_vertices(const SurfaceMesh& s,
                                         std::unordered_map<PointKey, uint32_t, Hash3>& exact) {
  const size_t n = s.num_vertices();
  std::vector<uint32_t> canon(n);
  exact.reserve(n);
  for (size_t i = 0; i < n; ++i) canon[i] = exact.emplace(point_key(s.point(i)), uint32_t(i)).first->second;
  return canon;
}

// Mesh vertex -> canonical input vertex (kNone when unmatched); exact first, then within tol.
// Only vertices of input triangles count: an unreferenced input point is not on the surface.
void match_vertices(const VolumeMesh& mesh, const SurfaceMesh& s, const std::vector<uint8_t>& used,
                    const std::vector<uint32_t>& canon, const std::vector<uint8_t>& referenced,
                    const std::unordered_map<PointKey, uint32_t, Hash3>& exact,
                    const QualityOptions& options, std::vector<uint32_t>& omap,
                    SurfaceMatchReport& out) {
  const size_t nv = mesh.num_vertices();
  omap.assign(nv, kNone);
  std::vector<uint8_t> how(nv, 0);  // 1 exact, 2 tolerance
  for_chunks(nv, options.parallel, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      if (!used[v]) continue;
      auto it = exact.find(point_key(mesh.point(v)));
      if (it != exact.end() && referenced[it->second]) {
        omap[v] = it->second;
        how[v] = 1;
      }
    }
  });

  double scale = 0.0;
  for (double x : s.xyz) {
    if (std::isfinite(x)) scale = std::max(scale, std::fabs(x));
  }
  if (scale == 0.0) scale = 1.0;
  const double q = options.match_tolerance * scale;
  out.tolerance_abs = q;
  if (q > 0.0 && std::isfinite(q)) {
    // Cells of size 2q; each input vertex is filed in every cell its q-box touches (<= 8), so a
    // query looks in one cell only. The cells are found by a hash of their coordinates in a flat
    // map heading a list per cell (a map of vectors cost one allocation per cell): two cells with
    // one hash share a list, which only adds candidates farther than q.
    const double h = 2.0 * q;
    auto cell_key = [](int64_t x, int64_t y, int64_t z) {
      const uint64_t k = Hash3{}(CellKey{{x, y, z}});
      return k == FlatKeyMap::kEmptyKey ? 0 : k;
    };
    constexpr uint32_t kEnd = FlatKeyMap::kAbsent;
    FlatKeyMap heads;
    std::vector<uint32_t> filed, next;  // per filing: the input vertex, the next filing of its cell
    for (size_t i = 0; i < canon.size(); ++i) {
      if (canon[i] != i || !referenced[i]) continue;
      const double* p = s.point(i);
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
      int64_t lo[3], hi[3];
      for (int k = 0; k < 3; ++k) {
        lo[k] = static_cast<int64_t>(std::floor((p[k] - q) / h));
        hi[k] = static_cast<int64_t>(std::floor((p[k] + q) / h));
      }
      for (int64_t x = lo[0]; x <= hi[0]; ++x)
        for (int64_t y = lo[1]; y <= hi[1]; ++y)
          for (int64_t z = lo[2]; z <= hi[2]; ++z) {
            next.push_back(std::exchange(heads.find_or_insert(cell_key(x, y, z), kEnd), uint32_t(filed.size())));
            filed.push_back(uint32_t(i));
          }
    }
    for_chunks(nv, options.parallel, [&](size_t begin, size_t end) {
      for (size_t v = begin; v < end; ++v) {
        if (!used[v] || omap[v] != kNone) continue;
        const double* p = mesh.point(v);
        // The nearest within q, and of equals the highest input id.
        double best = q;
        for (uint32_t f = heads.find(cell_key(static_cast<int64_t>(std::floor(p[0] / h)),
                                              static_cast<int64_t>(std::floor(p[1] / h)),
                                              static_cast<int64_t>(std::floor(p[2] / h))));
             f != kEnd; f = next[f]) {
          const uint32_t i = filed[f];
          const double* c = s.point(i);
          const double dist = std::max({std::fabs(p[0] - c[0]), std::fabs(p[1] - c[1]), std::fabs(p[2] - c[2])});
          if (dist < best || (dist == best && (omap[v] == kNone || i > omap[v]))) {
            best = dist;
            omap[v] = i;
            how[v] = 2;
          }
        }
      }
    });
  }
  for (size_t v = 0; v < nv; ++v) {
    out.matched_exact += how[v] == 1;
    out.matched_tolerance += how[v] == 2;
  }
}

}  // namespace

void match_surface(const VolumeMesh& mesh, const SurfaceMesh& surface,
                   const std::vector<uint32_t>& boundary_faces, const std::vector<uint8_t>& used,
                   const TetData& data, const QualityOptions& options, QualityReport& report) {
  SurfaceMatchReport& out = report.surface;
  out = SurfaceMatchReport{};
  out.present = true;
  out.input_vertices = surface.num_vertices();
  const size_t nsv = surface.num_vertices();

  std::unordered_map<PointKey, uint32_t, Hash3> exact;
  const std::vector<uint32_t> canon = canonical_vertices(surface, exact);

  // Input triangles with valid indices, on canonical vertices.
  std::vector<uint32_t> ctri;  // 3 per usable triangle
  std::vector<uint32_t> ctri_id;
  std::vector<std::pair<Tri, uint32_t>> input_keys;
  double enclosed = 0.0;
  double tq_min = 0.0;
  bool have_tq = false;
  for (size_t t = 0; t < surface.num_triangles(); ++t) {
    const uint32_t* v = &surface.tri[3 * t];
    if (v[0] >= nsv || v[1] >= nsv || v[2] >= nsv) continue;
    const double *a = surface.point(v[0]), *b = surface.point(v[1]), *c = surface.point(v[2]);
    enclosed += (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
                 a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
    const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    double l2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      l2 += (b[k] - a[k]) * (b[k] - a[k]) + (c[k] - b[k]) * (c[k] - b[k]) + (a[k] - c[k]) * (a[k] - c[k]);
    }
    const double tq = 2.0 * std::sqrt(3.0) * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) /
                      std::max(l2, 1e-300);
    tq_min = have_tq ? std::min(tq_min, tq) : tq;
    have_tq = true;
    const uint32_t a_ = canon[v[0]], b_ = canon[v[1]], c_ = canon[v[2]];
    input_keys.push_back({sorted(a_, b_, c_), uint32_t(t)});
    ctri.insert(ctri.end(), {a_, b_, c_});
    ctri_id.push_back(uint32_t(t));
  }
  out.input_triangle_quality_min = tq_min;
  out.surface_volume = std::fabs(enclosed);
  out.volume_rel_error = std::fabs(out.surface_volume - report.volume) / std::max(out.surface_volume, 1e-300);
  std::sort(input_keys.begin(), input_keys.end());
  input_keys.erase(std::unique(input_keys.begin(), input_keys.end(),
                               [](const auto& x, const auto& y) { return x.first == y.first; }),
                   input_keys.end());
  out.input_triangles = input_keys.size();

  std::vector<uint8_t> referenced(nsv, 0);  // canonical vertices of usable input triangles
  for (uint32_t v : ctri) referenced[v] = 1;
  std::vector<uint32_t> omap;
  match_vertices(mesh, surface, used, canon, referenced, exact, options, omap, out);
  {
    std::vector<uint8_t> hit(nsv, 0);
    for (size_t v = 0; v < omap.size(); ++v) {
      if (omap[v] != kNone) hit[omap[v]] = 1;
    }
    for (size_t v = 0; v < nsv; ++v) out.input_vertices_missing += referenced[v] && !hit[v];
  }

  // Boundary faces in input ids; Steiner points on the boundary.
  const size_t nb = boundary_faces.size() / 3;
  std::vector<Tri> bkeys;
  bkeys.reserve(nb);
  std::vector<uint8_t> steiner(mesh.num_vertices(), 0);
  for (size_t f = 0; f < nb; ++f) {
    const uint32_t* v = &boundary_faces[3 * f];
    bool all = true;
    for (int k = 0; k < 3; ++k) {
      if (omap[v[k]] == kNone) {
        all = false;
        steiner[v[k]] = 1;
      }
    }
    if (all) bkeys.push_back(sorted(omap[v[0]], omap[v[1]], omap[v[2]]));
  }
  out.steiner_points_on_boundary = size_t(std::count(steiner.begin(), steiner.end(), uint8_t(1)));
  std::sort(bkeys.begin(), bkeys.end());
  bkeys.erase(std::unique(bkeys.begin(), bkeys.end()), bkeys.end());
  size_t common = 0;
  for (const auto& [key, id] : input_keys) {
    if (std::binary_search(bkeys.begin(), bkeys.end(), key)) {
      ++common;
    } else {
      ++out.input_triangles_missing;
      if (out.missing_triangle_examples.size() < options.max_listed) out.missing_triangle_examples.push_back(id);
    }
  }
  out.boundary_faces_not_in_input = nb - common;

  // Mesh vertices other than the input's own lying exactly on the input surface.
  {
    TriangleBVH bvh;
    bvh.build(surface.xyz.data(), ctri.data(), ctri.size() / 3);
    std::vector<uint32_t> on(mesh.num_vertices(), kNone);
    for_chunks(mesh.num_vertices(), options.parallel, [&](size_t begin, size_t end) {
      for (size_t v = begin; v < end; ++v) {
        if (!used[v] || omap[v] != kNone) continue;
        const double* p = mesh.point(v);
        const Box3 box{{p[0], p[1], p[2]}, {p[0], p[1], p[2]}};
        bvh.query(box, [&](size_t t) {
          const uint32_t* c = &ctri[3 * t];
          if (!on_closed_triangle(surface.point(c[0]), surface.point(c[1]), surface.point(c[2]), p)) return true;
          on[v] = ctri_id[t];
          return false;
        });
      }
    });
    for (size_t v = 0; v < on.size(); ++v) {
      if (on[v] == kNone) continue;
      ++out.vertices_on_input_surface;
      if (out.on_surface_examples.size() < options.max_listed) {
        out.on_surface_examples.push_back(uint32_t(v));
        out.on_surface_triangles.push_back(on[v]);
      }
    }
  }

  out.boundary_constrained = out.input_triangles_missing == 0 && out.boundary_faces_not_in_input == 0 &&
                             out.steiner_points_on_boundary == 0 && out.vertices_on_input_surface == 0;

  // The paper's split: tets touching the input surface (a vertex is an input vertex) and the rest.
  std::vector<uint8_t> touch(mesh.num_tets(), 0);
  for_chunks(touch.size(), options.parallel, [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t) {
      const uint32_t* v = &mesh.tet[4 * t];
      touch[t] = omap[v[0]] != kNone || omap[v[1]] != kNone || omap[v[2]] != kNone || omap[v[3]] != kNone;
    }
  });
  // (Each split sums in tet order: the same figures either way.)
  if (options.parallel) {
    tbb::parallel_invoke([&] { out.touching_surface = split_quality(data, touch, 1); },
                         [&] { out.interior = split_quality(data, touch, 0); });
  } else {
    out.touching_surface = split_quality(data, touch, 1);
    out.interior = split_quality(data, touch, 0);
  }
}

}  // namespace anitet::quality_detail
