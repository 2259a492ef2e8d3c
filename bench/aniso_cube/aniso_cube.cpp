// The anisotropic acceptance case of issue 8: the unit cube with the metric
//     h_x = h_y = 0.1,  h_z = 0.001 + 0.198 |z - 0.5|
// (sizes along the axes: M = diag(1/h_x^2, 1/h_y^2, 1/h_z^2)). The cube's surface is triangulated
// here to the same metric: a structured grid on each face, spacing 0.1 along x and y and the
// z-spacing of unit metric length (so the side faces carry triangles stretched up to 100:1),
// two triangles per cell. The whole pipeline (Mesher) then runs with the analytic metric as its
// sizing field, and the program measures on the output:
//   - the share of the edges not on the cube's surface whose metric length is in [1/sqrt2, sqrt2]
//     (target: at least 90%), with the metric length of refine/ (the geometric mean of the edge's
//     length in the metrics at its two ends) and, for comparison, with M at the edge's midpoint;
//   - the share of tets whose metric radius ratio (the radius ratio of the tet mapped by M^(1/2)
//     at its centroid) is below 0.1 (target: fewer than 0.1%);
//   - the metric length histogram (bins of 0.1 from 0 to 3, then one bin above).
// --direct skips stages 1-3a (layers, recovery of S1, coupling), which do not take such stretched
// triangles today: the initial mesh is the Delaunay tetrahedralization of the surface points
// (the cube is convex, so its hull is S; each face's cells then get the diagonal the Delaunay
// kernel picks, still two triangles per cell), S's facets protected and its vertices fixed, and
// refine_mesh / optimize_mesh run on it with the metric, as the pipeline runs them (with
// --cycles more rounds of both, default the pipeline's MesherOptions::anisotropic_cycles).
// Usage: bench_aniso_cube [--direct] [--no-refine] [--no-optimize] [--cycles N] [--front-layers N] [--size S]
//                         [--surface OUT.off] [-o OUT.mesh]
// Exit status 0 when both targets are met, 1 when not, 2 on a usage error, 3 when meshing fails.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/sizing.hpp"
#include "core/surface_mesh.hpp"
#include "core/tet_mesh.hpp"
#include "delaunay/delaunay.hpp"
#include "io/surface_io.hpp"
#include "io/volume_io.hpp"
#include "pipeline/mesher.hpp"
#include "refine/mesh_ops.hpp"

namespace {

constexpr double kA = 0.001, kB = 0.198, kHxy = 0.1;

double hz(double z) { return kA + kB * std::fabs(z - 0.5); }

class CubeMetric final : public anitet::SizingField {
 public:
  void metric(const double p[3], double m[6]) const override {
    const double h = hz(std::clamp(p[2], 0.0, 1.0));
    m[0] = 1.0 / (kHxy * kHxy);
    m[1] = 0.0;
    m[2] = 1.0 / (kHxy * kHxy);
    m[3] = 0.0;
    m[4] = 0.0;
    m[5] = 1.0 / (h * h);
  }
};

// z nodes of unit metric length: s(z) = integral of dz / h_z is split evenly, symmetric about 0.5.
std::vector<double> z_nodes() {
  const double half = std::log((kA + 0.5 * kB) / kA) / kB;  // metric length of [0, 0.5]
  const int n = std::max(1, static_cast<int>(std::lround(half)));
  std::vector<double> upper;  // distances u from 0.5 of the nodes, 0 .. 0.5
  for (int k = 0; k <= n; ++k) {
    const double s = half * k / n;
    upper.push_back(k == n ? 0.5 : kA * (std::exp(kB * s) - 1.0) / kB);
  }
  std::vector<double> z;
  for (int k = n; k >= 1; --k) z.push_back(0.5 - upper[k]);
  for (int k = 0; k <= n; ++k) z.push_back(0.5 + upper[k]);
  return z;
}

anitet::SurfaceMesh cube_surface() {
  const int nxy = static_cast<int>(std::lround(1.0 / kHxy));
  const std::vector<double> zs = z_nodes();
  const int nz = static_cast<int>(zs.size()) - 1;
  anitet::SurfaceMesh s;
  std::map<std::tuple<int, int, int>, uint32_t> ids;
  auto vid = [&](int i, int j, int k) {
    auto [it, fresh] = ids.try_emplace({i, j, k}, static_cast<uint32_t>(s.xyz.size() / 3));
    if (fresh) {
      s.xyz.push_back(double(i) / nxy);
      s.xyz.push_back(double(j) / nxy);
      s.xyz.push_back(zs[size_t(k)]);
    }
    return it->second;
  };
  // A quad given by its lattice corners in cyclic order, split into two triangles oriented so
  // that their normal points along `out` (the face's outward axis, +-1 on axis `axis`).
  auto quad = [&](const int c[4][3], int axis, int out, int label) {
    uint32_t v[4];
    for (int q = 0; q < 4; ++q) v[q] = vid(c[q][0], c[q][1], c[q][2]);
    const double* p0 = s.point(v[0]);
    const double* p1 = s.point(v[1]);
    const double* p2 = s.point(v[2]);
    const double u[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
    const double w[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    if (n[axis] * out > 0.0) {
      s.add_triangle(v[0], v[1], v[2], label);
      s.add_triangle(v[0], v[2], v[3], label);
    } else {
      s.add_triangle(v[0], v[2], v[1], label);
      s.add_triangle(v[0], v[3], v[2], label);
    }
  };
  for (int side = 0; side < 2; ++side) {
    const int out = side ? 1 : -1;
    // z = const faces.
    for (int i = 0; i < nxy; ++i)
      for (int j = 0; j < nxy; ++j) {
        const int k = side ? nz : 0;
        const int c[4][3] = {{i, j, k}, {i + 1, j, k}, {i + 1, j + 1, k}, {i, j + 1, k}};
        quad(c, 2, out, 5 + side);
      }
    // x = const and y = const faces (stretched cells).
    for (int a = 0; a < nxy; ++a)
      for (int k = 0; k < nz; ++k) {
        const int i = side ? nxy : 0;
        const int cx[4][3] = {{i, a, k}, {i, a + 1, k}, {i, a + 1, k + 1}, {i, a, k + 1}};
        quad(cx, 0, out, 1 + side);
        const int cy[4][3] = {{a, i, k}, {a + 1, i, k}, {a + 1, i, k + 1}, {a, i, k + 1}};
        quad(cy, 1, out, 3 + side);
      }
  }
  return s;
}

// Radius ratio of the tet mapped by M^(1/2), M diagonal here (the map diag(sqrt m)).
double metric_radius_ratio(const double m[6], const double* a, const double* b, const double* c,
                           const double* d) {
  const double f[3] = {std::sqrt(m[0]), std::sqrt(m[2]), std::sqrt(m[5])};
  double q[4][3];
  const double* p[4] = {a, b, c, d};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) q[i][k] = f[k] * p[i][k];
  return anitet::meshops::radius_ratio(q[0], q[1], q[2], q[3]);
}

using EdgeSet = std::set<std::pair<uint32_t, uint32_t>>;

std::pair<uint32_t, uint32_t> edge_key(uint32_t a, uint32_t b) {
  return a < b ? std::make_pair(a, b) : std::make_pair(b, a);
}

// Stages 1-3a replaced for the convex cube: Delaunay of S's points, hull facets protected.
// `surface` receives S as the Delaunay kernel triangulated it (outward orientation).
anitet::Status direct_initial_mesh(const anitet::SurfaceMesh& cube, anitet::TetMesh& mesh,
                                   anitet::SurfaceMesh& surface) {
  anitet::Result<anitet::DelaunayStats> dt =
      anitet::delaunay_tetrahedralize(mesh, cube.xyz.data(), cube.num_vertices());
  if (!dt.ok()) return dt.status();
  surface = anitet::SurfaceMesh();
  surface.xyz = cube.xyz;
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t) {
    if (mesh.is_deleted(t) || !mesh.is_ghost(t)) continue;
    const uint32_t n = mesh.neighbour(t, 3);
    mesh.set_facet_protected(n, mesh.neighbour_facet(t, 3), true);
    // Facet 3 of the ghost, seen from the ghost's side: (0 1 2) faces the hull's inside, so the
    // outward triangle is (0 2 1).
    surface.add_triangle(mesh.vertex(t, 0), mesh.vertex(t, 2), mesh.vertex(t, 1));
  }
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t)
    if (!mesh.is_deleted(t) && mesh.is_ghost(t)) mesh.delete_tet(t);
  if (anitet::Status st = mesh.build_adjacency(); !st.ok()) return st;
  for (uint8_t& f : mesh.vflags) f |= anitet::vflag::kOnInputSurface;
  return anitet::check_mesh(mesh);
}

int usage() {
  std::fprintf(stderr,
               "usage: bench_aniso_cube [--direct] [--no-refine] [--no-optimize] [--cycles N] [--front-layers N] [--size S] "
               "[--surface OUT.off] [-o OUT.mesh]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  anitet::MesherOptions opt;
  std::string out_mesh, out_surface;
  bool direct = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_next = i + 1 < argc;
    if (a == "--no-refine") opt.run_refine = false;
    else if (a == "--direct") direct = true;
    else if (a == "--no-optimize") opt.run_optimize = false;
    else if (a == "--cycles" && has_next) opt.anisotropic_cycles = std::atoi(argv[++i]);
    else if (a == "--front-layers" && has_next) opt.layers.layers = std::atoi(argv[++i]);
    else if (a == "--size" && has_next) opt.refine.size_scale = std::atof(argv[++i]);
    else if (a == "--surface" && has_next) out_surface = argv[++i];
    else if (a == "-o" && has_next) out_mesh = argv[++i];
    else return usage();
  }
  const anitet::SurfaceMesh cube = cube_surface();
  anitet::SurfaceMesh surface = cube;
  std::printf("surface: %zu vertices, %zu triangles\n", cube.num_vertices(), cube.num_triangles());
  const CubeMetric field;
  anitet::VolumeMesh mesh;
  const auto t0 = std::chrono::steady_clock::now();
  if (direct) {
    anitet::TetMesh tm;
    if (anitet::Status st = direct_initial_mesh(cube, tm, surface); !st.ok()) {
      std::fprintf(stderr, "initial mesh: %s\n", st.message().c_str());
      return 3;
    }
    std::printf("initial Delaunay mesh: %zu tets, S: %zu triangles\n", tm.num_live_tets(), surface.num_triangles());
    if (opt.run_refine) {
      anitet::Result<anitet::RefineStats> rs = anitet::refine_mesh(tm, field, opt.refine);
      if (!rs.ok()) {
        std::fprintf(stderr, "refine: %s\n", rs.status().message().c_str());
        return 3;
      }
      std::printf("refine: %d passes, %zu splits (%zu rejected), %zu collapses (%zu rejected), "
                  "in range %.4f (refine's own count), %.3f s\n",
                  rs->passes, rs->splits, rs->split_rejected, rs->collapses, rs->collapse_rejected,
                  rs->length_in_range, rs->seconds);
    }
    if (opt.run_optimize) {
      const anitet::ScaledSizing scaled(field, opt.refine.size_scale);
      anitet::Result<anitet::OptimizeStats> os = anitet::optimize_mesh(tm, scaled, opt.optimize);
      if (!os.ok()) {
        std::fprintf(stderr, "optimize: %s\n", os.status().message().c_str());
        return 3;
      }
      std::printf("optimize: %zu moves (%zu rejected), %zu flips 2-3, %zu edge removals, %zu perturbations, %.3f s\n",
                  os->moves, os->moves_rejected, os->flips23, os->edge_removals, os->perturbations, os->seconds);
      // As the pipeline does on an anisotropic field.
      if (opt.run_refine && os->anisotropic && opt.anisotropic_cycles > 0) {
        anitet::RefineStats rs;
        anitet::OptimizeStats more = os.value();
        if (anitet::Status st = anitet::refine_optimize_cycles(tm, field, opt.refine, opt.optimize,
                                                               opt.anisotropic_cycles, rs, more);
            !st.ok()) {
          std::fprintf(stderr, "%s\n", st.message().c_str());
          return 3;
        }
        std::printf("%d more refine + optimize cycles: %d passes, %zu splits, %zu collapses, in range %.4f "
                    "(refine's own count), %.3f s + %.3f s\n",
                    opt.anisotropic_cycles, rs.passes, rs.splits, rs.collapses, rs.length_in_range, rs.seconds,
                    more.seconds - os->seconds);
      }
    }
    if (anitet::Status st = anitet::check_mesh(tm); !st.ok()) {
      std::fprintf(stderr, "final mesh broken: %s\n", st.message().c_str());
      return 3;
    }
    // Keep every vertex (S's ids stay those of `surface`), boundary triangles from S.
    mesh = tm.to_volume_mesh(false);
    mesh.bnd_tri = surface.tri;
    mesh.bnd_patch.assign(surface.num_triangles(), 1);
  } else {
    opt.sizing = &field;
    anitet::Result<anitet::MesherResult> res = anitet::Mesher(opt).run(cube);
    if (!res.ok()) {
      std::fprintf(stderr, "meshing failed: %s\n", res.status().message().c_str());
      return 3;
    }
    mesh = std::move(res.value().mesh);
    for (const anitet::StageReport& s : res.value().stages)
      std::printf("stage %-12s %8.3f s  %zu tets\n", s.name.c_str(), s.seconds, s.tets);
    const anitet::RefineStats& rs = res.value().refine;
    std::printf("refine: %d passes, %zu splits (%zu rejected), %zu collapses (%zu rejected), "
                "in range %.4f (refine's own count)\n",
                rs.passes, rs.splits, rs.split_rejected, rs.collapses, rs.collapse_rejected, rs.length_in_range);
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("mesh: %zu vertices, %zu tets, %.3f s\n", mesh.num_vertices(), mesh.num_tets(), secs);
  if (!out_surface.empty()) {
    if (anitet::Status st = anitet::write_surface(surface, out_surface); !st.ok()) {
      std::fprintf(stderr, "%s\n", st.message().c_str());
      return 3;
    }
  }
  if (!out_mesh.empty()) {
    if (anitet::Status st = anitet::write_volume_mesh(mesh, out_mesh); !st.ok()) {
      std::fprintf(stderr, "%s\n", st.message().c_str());
      return 3;
    }
  }

  // Edges: of the tets, minus those of the boundary triangles.
  auto key = edge_key;
  EdgeSet surface_edges, edges;
  for (size_t t = 0; t < mesh.num_boundary_triangles(); ++t)
    for (int k = 0; k < 3; ++k)
      surface_edges.insert(key(mesh.bnd_tri[3 * t + k], mesh.bnd_tri[3 * t + (k + 1) % 3]));
  for (size_t t = 0; t < mesh.num_tets(); ++t)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const auto e = key(mesh.tet[4 * t + i], mesh.tet[4 * t + j]);
        if (!surface_edges.count(e)) edges.insert(e);
      }
  const double lo = std::sqrt(0.5), hi = std::sqrt(2.0);
  constexpr int kBins = 31;  // [0.1 k, 0.1 (k + 1)) for k < 30, then [3, inf)
  std::vector<size_t> hist(kBins, 0);
  size_t in_range = 0, in_range_mid = 0;
  double sum = 0.0;
  for (const auto& [a, b] : edges) {
    const double* pa = mesh.point(a);
    const double* pb = mesh.point(b);
    const double len = anitet::metric_edge_length(field, pa, pb);
    const double mid[3] = {0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1]), 0.5 * (pa[2] + pb[2])};
    double mm[6];
    field.metric(mid, mm);
    const double len_mid = anitet::metric_edge_length(mm, pa, pb);
    sum += len;
    in_range += len >= lo && len <= hi;
    in_range_mid += len_mid >= lo && len_mid <= hi;
    ++hist[size_t(std::min(kBins - 1, static_cast<int>(len / 0.1)))];
  }
  const double ne = double(std::max<size_t>(edges.size(), 1));
  const double frac_in = double(in_range) / ne;
  std::printf("interior edges: %zu, metric length mean %.3f, in [1/sqrt2, sqrt2]: %.2f%% "
              "(M at the midpoint: %.2f%%)  target >= 90%%\n",
              edges.size(), sum / ne, 100.0 * frac_in, 100.0 * double(in_range_mid) / ne);
  std::printf("metric length histogram (edges not on the surface):\n");
  for (int k = 0; k < kBins; ++k) {
    if (k < kBins - 1) std::printf("  [%.1f, %.1f) %8zu  %6.2f%%\n", 0.1 * k, 0.1 * (k + 1), hist[size_t(k)], 100.0 * double(hist[size_t(k)]) / ne);
    else std::printf("  [3.0, inf) %8zu  %6.2f%%\n", hist[size_t(k)], 100.0 * double(hist[size_t(k)]) / ne);
  }

  // Metric radius ratio at the centroid; Euclidean radius ratio for comparison.
  size_t bad = 0, below04 = 0, touching = 0, bad_touching = 0;
  double qmin = 1.0, qsum = 0.0, emin = 1.0, esum = 0.0;
  std::vector<size_t> qhist(10, 0);
  for (size_t t = 0; t < mesh.num_tets(); ++t) {
    const double* p[4];
    double c[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < 4; ++i) {
      p[i] = mesh.point(mesh.tet[4 * t + i]);
      for (int k = 0; k < 3; ++k) c[k] += 0.25 * p[i][k];
    }
    double m[6];
    field.metric(c, m);
    const double q = metric_radius_ratio(m, p[0], p[1], p[2], p[3]);
    const double e = anitet::meshops::radius_ratio(p[0], p[1], p[2], p[3]);
    bad += q < 0.1;
    bool on_s = false;  // S's vertices come first (input order) in both modes
    for (int i = 0; i < 4; ++i) on_s |= mesh.tet[4 * t + i] < surface.num_vertices();
    touching += on_s;
    bad_touching += on_s && q < 0.1;
    below04 += q < 0.4;
    qmin = std::min(qmin, q);
    qsum += q;
    emin = std::min(emin, e);
    esum += e;
    ++qhist[size_t(std::clamp(static_cast<int>(q * 10.0), 0, 9))];
  }
  const double nt = double(std::max<size_t>(mesh.num_tets(), 1));
  const double frac_bad = double(bad) / nt;
  std::printf("metric radius ratio: mean %.3f, min %.4f, < 0.1: %zu (%.3f%%, target < 0.1%%), < 0.4: %.2f%%\n",
              qsum / nt, qmin, bad, 100.0 * frac_bad, 100.0 * double(below04) / nt);
  std::printf("tets touching S: %zu, of them below 0.1: %zu; tets not touching S: %zu, below 0.1: %zu\n",
              touching, bad_touching, mesh.num_tets() - touching, bad - bad_touching);
  std::printf("metric radius ratio histogram:");
  for (int k = 0; k < 10; ++k) std::printf(" %zu", qhist[size_t(k)]);
  std::printf("\nEuclidean radius ratio: mean %.3f, min %.4f\n", esum / nt, emin);
  const bool met = frac_in >= 0.9 && frac_bad < 0.001;
  std::printf("targets %s\n", met ? "MET" : "NOT MET");
  return met ? 0 : 1;
}
