// validate_surface: the checks and repairs in order (see validate.hpp), one step per function.
#include "validate/validate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

#include <tbb/parallel_invoke.h>

#include "core/bvh.hpp"
#include "predicates/predicates.hpp"
#include "validate/repair.hpp"
#include "validate/report_builder.hpp"
#include "validate/self_intersect.hpp"
#include "validate/shells.hpp"
#include "validate/topology.hpp"

namespace anitet {

namespace {

using report_detail::corners;
using report_detail::format_ids;
using report_detail::format_point;
using report_detail::one_based;
using report_detail::ReportBuilder;
using Pair = std::pair<uint32_t, uint32_t>;

// Exactly collinear corners: all three coordinate-plane projections have zero area.
bool collinear(const double* a, const double* b, const double* c) {
  if (predicates::orient2d(a, b, c) != 0) return false;              // (x, y)
  if (predicates::orient2d(a + 1, b + 1, c + 1) != 0) return false;  // (y, z)
  const double a2[2] = {a[2], a[0]}, b2[2] = {b[2], b[0]}, c2[2] = {c[2], c[0]};
  return predicates::orient2d(a2, b2, c2) == 0;  // (z, x)
}

bool is_finite(const double* p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// Array shapes and vertex indices: false when nothing else can be checked.
bool check_arrays(const SurfaceMesh& s, ReportBuilder& out) {
  if (s.xyz.size() % 3 != 0 || s.tri.size() % 3 != 0) {
    out.error(Error::InvalidArgument, "the coordinate or index array is not a multiple of 3");
    return false;
  }
  if (!s.patch.empty() && s.patch.size() != s.num_triangles()) {  // no labels: all patch 0
    out.error(Error::InvalidArgument, "the patch array has " + std::to_string(s.patch.size()) +
                                          " labels for " + std::to_string(s.num_triangles()) +
                                          " triangles");
    return false;
  }
  if (s.num_triangles() == 0) {
    out.error(Error::EmptyInput, "the surface has no triangles");
    return false;
  }
  std::vector<uint32_t> bad;
  for (size_t t = 0; t < s.num_triangles(); ++t) {
    for (int c = 0; c < 3; ++c) {
      if (s.tri[3 * t + c] >= s.num_vertices()) {
        bad.push_back(static_cast<uint32_t>(t));
        break;
      }
    }
  }
  if (bad.empty()) return true;
  out.error(Error::BadIndex, bad.size(),
            std::to_string(bad.size()) + " triangles refer to vertices that do not exist (" +
                std::to_string(s.num_vertices()) + " vertices); first: triangle " +
                one_based(bad[0]) + " " + format_ids(corners(s, bad[0])),
            [&](size_t k) { return out.example({bad[k]}, corners(s, bad[k])); });
  return false;
}

void merge_vertices(SurfaceMesh& s, ValidationReport& report) {
  const size_t removed = repair::merge_duplicate_vertices(s, report.vertex_map);
  if (removed == 0) return;
  report.repairs.push_back(Repair{"merged_duplicate_vertices", removed,
                                  "merged " + std::to_string(removed) +
                                      " vertices with exactly equal coordinates (" +
                                      std::to_string(s.num_vertices()) + " remain)"});
}

// NaN/Inf coordinates: true when every vertex is finite (geometric checks can run).
bool check_finite(const SurfaceMesh& s, ReportBuilder& out) {
  std::vector<uint32_t> bad;
  for (size_t v = 0; v < s.num_vertices(); ++v) {
    if (!is_finite(s.point(v))) bad.push_back(static_cast<uint32_t>(v));
  }
  if (bad.empty()) return true;
  out.error(Error::NonFiniteCoordinate, bad.size(),
            std::to_string(bad.size()) +
                " vertices have NaN or infinite coordinates (geometric checks skipped); first: "
                "vertex " +
                one_based(bad[0]) + " " + format_point(s.point(bad[0])),
            [&](size_t k) { return out.example({}, {bad[k]}); });
  return false;
}

// Degenerate triangles. usable[t]: three distinct vertex ids (enters the topology);
// testable[t]: also not collinear and finite (enters the intersection search).
void check_degenerate(const SurfaceMesh& s, bool geometry_ok, ReportBuilder& out,
                      std::vector<uint8_t>& usable, std::vector<uint8_t>& testable) {
  const size_t nt = s.num_triangles();
  usable.assign(nt, 1);
  testable.assign(nt, 1);
  std::vector<uint32_t> bad;
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t a = s.tri[3 * t], b = s.tri[3 * t + 1], c = s.tri[3 * t + 2];
    usable[t] = (a != b && b != c && a != c);
    bool degenerate = !usable[t];
    if (!degenerate && geometry_ok) degenerate = collinear(s.point(a), s.point(b), s.point(c));
    testable[t] = !degenerate && geometry_ok;
    if (degenerate) bad.push_back(static_cast<uint32_t>(t));
  }
  if (bad.empty()) return;
  out.error(Error::DegenerateTriangle, bad.size(),
            std::to_string(bad.size()) +
                " triangles have zero area (a repeated vertex or three collinear points); "
                "first: triangle " +
                one_based(bad[0]) + " " + format_ids(corners(s, bad[0])) + " at " +
                format_point(s.point(s.tri[3 * size_t(bad[0])])),
            [&](size_t k) { return out.example({bad[k]}, corners(s, bad[k])); });
}

// Triangles with the vertex set of a triangle with a smaller id.
void check_duplicates(const SurfaceMesh& s, ReportBuilder& out) {
  const size_t nt = s.num_triangles();
  std::vector<std::array<uint32_t, 4>> keys(nt);  // sorted corners, then the triangle id
  for (size_t t = 0; t < nt; ++t) {
    keys[t] = {s.tri[3 * t], s.tri[3 * t + 1], s.tri[3 * t + 2], static_cast<uint32_t>(t)};
    std::sort(keys[t].begin(), keys[t].begin() + 3);
  }
  std::sort(keys.begin(), keys.end());
  std::vector<Pair> dups;  // (duplicate, original)
  for (size_t i = 0; i < nt;) {  // groups of equal vertex sets, the smallest id first
    size_t j = i + 1;
    while (j < nt && std::equal(keys[j].begin(), keys[j].begin() + 3, keys[i].begin())) {
      dups.emplace_back(keys[j][3], keys[i][3]);
      ++j;
    }
    i = j;
  }
  if (dups.empty()) return;
  std::sort(dups.begin(), dups.end());
  out.error(Error::DuplicateTriangle, dups.size(),
            std::to_string(dups.size()) +
                " triangles repeat the vertex set of an earlier triangle; first: triangle " +
                one_based(dups[0].first) + " repeats triangle " +
                one_based(dups[0].second) + " " + format_ids(corners(s, dups[0].first)),
            [&](size_t k) {
              return out.example({dups[k].first, dups[k].second}, corners(s, dups[k].first));
            });
}

void report_topology(const SurfaceMesh& s, const topology::EdgeTable& edges,
                     const topology::Topology& topo, ReportBuilder& out) {
  const auto edge_example = [&](uint32_t e) {
    std::vector<uint32_t> tris;
    for (uint32_t h = edges.edge_begin[e]; h < edges.edge_begin[e + 1]; ++h) {
      tris.push_back(edges.half_tri[h]);
    }
    return out.example(tris, {edges.edge_lo(e), edges.edge_hi(e)});
  };
  const auto edge_text = [&](uint32_t e) {
    return "edge (" + one_based(edges.edge_lo(e)) + ", " + one_based(edges.edge_hi(e)) +
           ") at " + format_point(s.point(edges.edge_lo(e))) + " - " +
           format_point(s.point(edges.edge_hi(e))) + " of triangles " +
           format_ids(edge_example(e).triangles);
  };
  const auto add_edges = [&](Error code, const std::vector<uint32_t>& list, const char* what) {
    if (list.empty()) return;
    out.error(code, list.size(),
              std::to_string(list.size()) + " edges " + what + "; first: " + edge_text(list[0]),
              [&](size_t k) { return edge_example(list[k]); });
  };
  add_edges(Error::OpenBoundary, topo.boundary_edges,
            "have only one triangle (the surface is open)");
  add_edges(Error::NonManifoldEdge, topo.non_manifold_edges, "have more than two triangles");
  add_edges(Error::InconsistentOrientation, topo.inconsistent_edges,
            "are used twice in the same direction (neighbours disagree on orientation)");
  const auto& vs = topo.non_manifold_vertices;
  if (!vs.empty()) {
    out.error(Error::NonManifoldVertex, vs.size(),
              std::to_string(vs.size()) +
                  " vertices have corners forming more than one fan; first: vertex " +
                  one_based(vs[0]) + " at " + format_point(s.point(vs[0])),
              [&](size_t k) { return out.example({}, {vs[k]}); });
  }
}

// Reports the intersecting pairs, split by shells; returns, per shell, whether it crosses
// another shell.
std::vector<uint8_t> report_intersections(const SurfaceMesh& s, const topology::Topology& topo,
                                          const std::vector<Pair>& pairs, ReportBuilder& out) {
  std::vector<uint8_t> crossed(topo.shell_first_triangle.size(), 0);
  std::vector<Pair> self, across;
  std::set<std::pair<int32_t, int32_t>> shell_pairs;
  for (const Pair& pr : pairs) {
    const int32_t a = topo.shell_of[pr.first], b = topo.shell_of[pr.second];
    if (a == b) {
      self.push_back(pr);
    } else {
      across.push_back(pr);
      shell_pairs.insert({std::min(a, b), std::max(a, b)});
      crossed[a] = crossed[b] = 1;
    }
  }
  const auto pair_example = [&](const Pair& pr) {
    std::vector<uint32_t> vs = corners(s, pr.first), vb = corners(s, pr.second);
    vs.insert(vs.end(), vb.begin(), vb.end());
    return out.example({pr.first, pr.second}, vs);
  };
  const auto pair_text = [&](const Pair& pr) {
    return "triangles " + one_based(pr.first) + " " + format_ids(corners(s, pr.first)) +
           " and " + one_based(pr.second) + " " + format_ids(corners(s, pr.second)) +
           " near " + format_point(s.point(s.tri[3 * size_t(pr.first)]));
  };
  if (!self.empty()) {
    out.error(Error::SelfIntersection, self.size(),
              std::to_string(self.size()) +
                  " pairs of triangles of one shell intersect; first: " + pair_text(self[0]),
              [&](size_t k) { return pair_example(self[k]); });
  }
  if (!across.empty()) {
    std::string shells_text;
    size_t listed = 0;
    for (const auto& sp : shell_pairs) {
      if (listed++ == out.max_examples()) {
        shells_text += ", ...";
        break;
      }
      shells_text += (listed > 1 ? ", " : "") + std::to_string(sp.first) + "-" +
                     std::to_string(sp.second);
    }
    out.error(Error::IntersectingShells, across.size(),
              std::to_string(across.size()) +
                  " pairs of triangles of different shells intersect (" +
                  std::to_string(shell_pairs.size()) + " pairs of shells: " + shells_text +
                  "); first: " + pair_text(across[0]),
              [&](size_t k) { return pair_example(across[k]); });
  }
  return crossed;
}

// Fills report.shells: nesting (closed shells), then each closed shell's orientation against the
// rule (outward at even depth, into the cavity at odd depth), flipped when allowed. A shell that
// crosses another is never flipped: its nesting means nothing.
void nest_and_orient(SurfaceMesh& s, const TriangleBVH& bvh, const topology::Topology& topo,
                     const std::vector<std::vector<uint32_t>>& shell_tris,
                     const std::vector<uint8_t>& crossed, bool geometry_ok, bool may_flip,
                     ValidationReport& report, ReportBuilder& out) {
  const size_t num_shells = shell_tris.size();
  report.shells.resize(num_shells);
  shells::Nesting nest;
  if (geometry_ok) nest = shells::nest_shells(s, bvh, topo, shell_tris);
  report.num_regions = geometry_ok ? size_t(nest.num_regions) : 0;
  std::vector<uint32_t> misoriented;
  for (size_t sh = 0; sh < num_shells; ++sh) {
    ShellInfo& info = report.shells[sh];
    info.first_triangle = topo.shell_first_triangle[sh];
    info.num_triangles = topo.shell_size[sh];
    info.closed = topo.shell_closed[sh] != 0;
    if (!geometry_ok || !info.closed) continue;
    info.parent = nest.parent[sh];
    info.depth = nest.depth[sh];
    info.region = nest.region[sh];
    const int sign = shells::volume_sign(s, shell_tris[sh], &info.signed_volume);
    const int expected = info.depth % 2 == 0 ? 1 : -1;
    if (sign == 0 || sign == expected) continue;
    if (!may_flip || crossed[sh]) {
      misoriented.push_back(static_cast<uint32_t>(sh));
      continue;
    }
    repair::flip_triangles(s, shell_tris[sh]);
    info.flipped = true;
    info.signed_volume = -info.signed_volume;
    report.repairs.push_back(
        Repair{"flipped_shell", shell_tris[sh].size(),
               "reoriented shell " + std::to_string(sh) + " (" +
                   std::to_string(shell_tris[sh].size()) + " triangles, depth " +
                   std::to_string(info.depth) + "): it faced " +
                   (expected > 0 ? "inward" : "out of its cavity")});
  }
  if (misoriented.empty()) return;
  out.error(Error::InconsistentOrientation, misoriented.size(),
            std::to_string(misoriented.size()) +
                " closed shells face the wrong way (bodies must face outward, cavities inward); "
                "first: shell " +
                std::to_string(misoriented[0]),
            [&](size_t k) {
              return out.example({topo.shell_first_triangle[misoriented[k]]}, {});
            });
}

// Shells whose neighbours disagree on the orientation but that are closed and orientable are
// made consistent (a repair, as the whole-shell flip is), and the topology measured again; a
// non-orientable one is an error naming an edge where no orientation agrees.
void reorient_triangles(SurfaceMesh& s, const std::vector<uint8_t>& usable, topology::EdgeTable& edges,
                        topology::Topology& topo, ValidationReport& report, ReportBuilder& out) {
  const std::vector<repair::ShellReorientation> done = repair::orient_shells_consistently(s, edges, topo);
  std::vector<repair::ShellReorientation> failed;
  bool changed = false;
  for (const repair::ShellReorientation& r : done) {
    if (!r.orientable) {
      failed.push_back(r);
      continue;
    }
    changed = true;
    report.repairs.push_back(Repair{"reoriented_triangles", r.flipped,
                                    "reoriented " + std::to_string(r.flipped) + " of the " +
                                        std::to_string(topo.shell_size[r.shell]) + " triangles of shell " +
                                        std::to_string(r.shell) + " to match their neighbours"});
  }
  if (changed) topo = topology::analyse(s, usable, edges);  // the same edges, now consistent
  if (failed.empty()) return;
  const auto& f = failed[0];
  out.add(Error::InconsistentOrientation, Severity::Error, "non_orientable_shell", failed.size(),
          std::to_string(failed.size()) + " shells are not orientable (no orientation of their triangles agrees "
          "across every edge, as on a Moebius band); first: shell " + std::to_string(f.shell) + " at edge (" +
          one_based(f.edge_lo) + ", " + one_based(f.edge_hi) + ") " + format_point(s.point(f.edge_lo)) +
          " - " + format_point(s.point(f.edge_hi)),
          [&](size_t k) { return out.example({topo.shell_first_triangle[failed[k].shell]}, {failed[k].edge_lo, failed[k].edge_hi}); });
}

void report_unreferenced(const SurfaceMesh& s, ReportBuilder& out) {
  std::vector<uint8_t> referenced(s.num_vertices(), 0);
  for (uint32_t v : s.tri) referenced[v] = 1;
  std::vector<uint32_t> unused;
  for (size_t v = 0; v < s.num_vertices(); ++v) {
    if (!referenced[v]) unused.push_back(static_cast<uint32_t>(v));
  }
  if (unused.empty()) return;
  out.add(Error::Ok, Severity::Warning, "unreferenced_vertex", unused.size(),
          std::to_string(unused.size()) +
              " vertices are used by no triangle (kept, ids unchanged); first: vertex " +
              one_based(unused[0]) + " at " + format_point(s.point(unused[0])),
          [&](size_t k) { return out.example({}, {unused[k]}); });
}

}  // namespace

ValidationReport validate_surface(SurfaceMesh& s, const ValidationOptions& options) {
  ValidationReport report;
  ReportBuilder out(s, options.max_examples, report);
  if (!check_arrays(s, out)) return report;
  if (options.merge_duplicate_vertices) merge_vertices(s, report);
  const bool geometry_ok = check_finite(s, out);

  std::vector<uint8_t> usable, testable;
  check_degenerate(s, geometry_ok, out, usable, testable);
  // The combinatorial checks (duplicates, edges, shells) beside the geometric ones (the BVH and
  // the intersecting pairs, which report nothing yet): the report's entries keep their order.
  topology::EdgeTable edges;
  topology::Topology topo;
  TriangleBVH bvh;
  auto combinatorial = [&] {
    check_duplicates(s, out);
    edges = topology::build_edge_table(s, usable);
    topo = topology::analyse(s, usable, edges);
  };
  auto geometric = [&] {
    if (geometry_ok) bvh.build(s.xyz.data(), s.tri.data(), s.num_triangles());
    if (geometry_ok && options.check_self_intersections)
      report.intersecting_pairs = find_intersecting_pairs(s, bvh, testable, options.num_threads);
  };
  if (options.num_threads == 1) {
    combinatorial();
    geometric();
  } else {
    tbb::parallel_invoke(combinatorial, geometric);
  }
  // Orientation only now: the geometric half reads the triangles (which flips do not move).
  if (options.orient_triangles) reorient_triangles(s, usable, edges, topo, report, out);
  report_topology(s, edges, topo, out);
  std::vector<std::vector<uint32_t>> shell_tris(topo.shell_first_triangle.size());
  for (size_t t = 0; t < s.num_triangles(); ++t) {
    if (topo.shell_of[t] >= 0) shell_tris[topo.shell_of[t]].push_back(static_cast<uint32_t>(t));
  }
  const std::vector<uint8_t> crossed =
      report_intersections(s, topo, report.intersecting_pairs, out);
  nest_and_orient(s, bvh, topo, shell_tris, crossed, geometry_ok, options.orient_shells, report,
                  out);
  report_unreferenced(s, out);
  return report;
}

}  // namespace anitet
