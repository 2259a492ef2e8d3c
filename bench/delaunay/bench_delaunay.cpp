// Times anitet's incremental Delaunay against CGAL's Delaunay_triangulation_3 (exact predicates,
// inexact constructions; range insertion with spatial sort) on the same point sets, in one run,
// then audits anitet's meshes with check_mesh(check_delaunay).
//
//   bench_delaunay [n = 1000000] [grid side = 50] [repeats = 3] [cube]
//
// `cube`: the random cube alone, without the threads' runs (before/after timings of a kernel
// change).
// Prints points/s per set (best of the repeats, each tool timed alternately on the same points)
// and the ratio, and ends with `ratio_vs_cgal: X` (anitet's points/s over CGAL's on the random
// cube). anitet runs on TBB's default arena (all cores; the parallel build of
// DelaunayOptions::partitions). Then, on the random cube, anitet with 1 and 2 threads (same
// mesh, bit for bit) and with partitions = 1 (one point at a time), alternated, best of the
// repeats: `speedup_2_threads: X` (1 thread over 2) and `speedup_vs_one_at_a_time: Y`.
// Built with the command-line tool's allocator (huge pages for large blocks; see CMakeLists.txt).
// The machines are shared and noisy: compare ratios, not times. Pinned to one core (`taskset -c
// 0`: TBB then runs one thread), the process's CPU time of each tetrahedralization is its work
// whatever the load; it is printed beside the wall time, with `ratio_vs_cgal_cpu: X` (CPU times'
// ratio, best of the repeats, random cube).
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <time.h>

#include <tbb/task_arena.h>

#include "delaunay/delaunay.hpp"

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalDelaunay = CGAL::Delaunay_triangulation_3<K>;
using Clock = std::chrono::steady_clock;

struct PointSet {
  std::string name;
  std::vector<double> xyz;
};

PointSet random_cube(size_t n) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  PointSet s{"random cube", std::vector<double>(3 * n)};
  for (double& c : s.xyz) c = u(rng);
  return s;
}

PointSet random_sphere(size_t n) {
  std::mt19937_64 rng(2);
  std::normal_distribution<double> g(0.0, 1.0);
  PointSet s{"sphere", {}};
  s.xyz.reserve(3 * n);
  while (s.xyz.size() < 3 * n) {
    const double p[3] = {g(rng), g(rng), g(rng)};
    const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    if (r < 1e-3) continue;
    for (double c : p) s.xyz.push_back(c / r);
  }
  return s;
}

PointSet grid(int k) {
  PointSet s{"grid " + std::to_string(k) + "^3", {}};
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      for (int l = 0; l < k; ++l) s.xyz.insert(s.xyz.end(), {double(i), double(j), double(l)});
  return s;
}

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The process's CPU time (all its threads), seconds.
double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

struct Timing {
  double anitet = 1e30, cgal = 1e30;          // best wall times of the repeats
  double anitet_cpu = 1e30, cgal_cpu = 1e30;  // best CPU times
  size_t anitet_tets = 0, cgal_tets = 0;
};

}  // namespace

int main(int argc, char** argv) {
  const size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1000000;
  const int side = argc > 2 ? std::atoi(argv[2]) : 50;
  const int repeats = argc > 3 ? std::max(1, std::atoi(argv[3])) : 3;
  const bool cube_only = argc > 4 && std::string(argv[4]) == "cube";

  std::vector<PointSet> sets;
  sets.push_back(random_cube(n));
  if (!cube_only) {
    sets.push_back(random_sphere(n));
    sets.push_back(grid(side));
  }

  std::vector<anitet::TetMesh> meshes(sets.size());
  double ratio_cube = 0, ratio_cube_cpu = 0;
  bool all_ok = true;
  char details[512] = "";
  for (size_t s = 0; s < sets.size(); ++s) {
    const PointSet& set = sets[s];
    const size_t np = set.xyz.size() / 3;
    std::vector<K::Point_3> points;
    points.reserve(np);
    for (size_t i = 0; i < np; ++i) points.emplace_back(set.xyz[3 * i], set.xyz[3 * i + 1], set.xyz[3 * i + 2]);
    Timing t;
    for (int r = 0; r < repeats; ++r) {  // alternate the two, keep each one's best time
      anitet::TetMesh mesh;
      double c0 = cpu_seconds();
      auto t0 = Clock::now();
      auto result = anitet::delaunay_tetrahedralize(mesh, set.xyz.data(), np);
      double sec = seconds_since(t0);
      t.anitet_cpu = std::min(t.anitet_cpu, cpu_seconds() - c0);
      if (!result.ok()) {
        std::printf("%s: anitet failed: %s\n", set.name.c_str(), result.status().message().c_str());
        return 1;
      }
      if (sec < t.anitet) {
        t.anitet = sec;
        t.anitet_tets = result->num_tets;
        const anitet::DelaunayStats& st = result.value();
        std::snprintf(details, sizeof details,
                      "sort %.3f s, insert %.3f s; walk %.2f steps/pt, cavity %.2f tets/pt, orient3d "
                      "%.1f/pt (%.2g%% exact), insphere %.1f/pt (%.2g%% exact), SoS ties %llu",
                      st.seconds_sort, st.seconds_insert, double(st.walk_steps) / np,
                      double(st.cavity_tets) / np, double(st.orient3d_calls) / np,
                      100.0 * double(st.orient3d_exact) / double(std::max<uint64_t>(1, st.orient3d_calls)),
                      double(st.insphere_calls) / np,
                      100.0 * double(st.insphere_exact) / double(std::max<uint64_t>(1, st.insphere_calls)),
                      static_cast<unsigned long long>(st.sos_ties));
      }
      if (r == repeats - 1) meshes[s] = std::move(mesh);

      c0 = cpu_seconds();
      t0 = Clock::now();
      CgalDelaunay dt(points.begin(), points.end());
      sec = seconds_since(t0);
      t.cgal_cpu = std::min(t.cgal_cpu, cpu_seconds() - c0);
      if (sec < t.cgal) {
        t.cgal = sec;
        t.cgal_tets = dt.number_of_finite_cells();
      }
    }
    const double ratio = t.cgal / t.anitet, ratio_cpu = t.cgal_cpu / t.anitet_cpu;
    if (s == 0) ratio_cube = ratio, ratio_cube_cpu = ratio_cpu;
    std::printf("%-12s %9zu points: anitet %.3f s (%.0f pts/s, %zu tets)  CGAL %.3f s (%.0f pts/s, %zu tets)  "
                "ratio %.2f\n             CPU: anitet %.3f s, CGAL %.3f s, ratio %.2f\n             anitet %s\n",
                set.name.c_str(), np, t.anitet, np / t.anitet, t.anitet_tets, t.cgal, np / t.cgal,
                t.cgal_tets, ratio, t.anitet_cpu, t.cgal_cpu, ratio_cpu, details);
    std::fflush(stdout);
  }

  // Threads: the random cube with 1 and 2 threads and one point at a time.
  if (!cube_only) {
    const PointSet& set = sets[0];
    const size_t np = set.xyz.size() / 3;
    double best[3] = {1e30, 1e30, 1e30};
    uint64_t hash[3] = {0, 0, 0};
    const int threads[3] = {1, 2, 1}, partitions[3] = {2, 2, 1};
    for (int r = 0; r < repeats; ++r)
      for (int c = 0; c < 3; ++c) {
        anitet::TetMesh mesh;
        anitet::DelaunayOptions o;
        o.partitions = partitions[c];
        tbb::task_arena arena(threads[c]);
        const auto t0 = Clock::now();
        const auto result = arena.execute([&] { return anitet::delaunay_tetrahedralize(mesh, set.xyz.data(), np, o); });
        const double sec = seconds_since(t0);
        if (!result.ok()) return 1;
        best[c] = std::min(best[c], sec);
        uint64_t h = 0;
        for (uint32_t v : mesh.tet_v) h = h * 1000003u + v;
        hash[c] = h;
      }
    std::printf("random cube threads: 1 thread %.3f s, 2 threads %.3f s (same mesh: %s), one point at a time %.3f s\n",
                best[0], best[1], hash[0] == hash[1] ? "yes" : "NO", best[2]);
    std::printf("speedup_2_threads: %.2f\nspeedup_vs_one_at_a_time: %.2f\n", best[0] / best[1], best[2] / best[1]);
    all_ok = all_ok && hash[0] == hash[1];
  }

  // Acceptance: the meshes are valid Delaunay tetrahedralizations (exact checks, not timed).
  for (size_t s = 0; s < sets.size(); ++s) {
    anitet::MeshCheckOptions check;
    check.check_delaunay = true;
    const auto t0 = Clock::now();
    const anitet::Status st = anitet::check_mesh(meshes[s], check);
    std::printf("check_mesh(check_delaunay) %-12s: %s (%.1f s)\n", sets[s].name.c_str(),
                st.ok() ? "ok" : st.message().c_str(), seconds_since(t0));
    all_ok = all_ok && st.ok();
  }
  std::printf("ratio_vs_cgal: %.2f\nratio_vs_cgal_cpu: %.2f\n", ratio_cube, ratio_cube_cpu);
  return all_ok ? 0 : 1;
}
