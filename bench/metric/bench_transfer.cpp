// Field transfer (metric/field_transfer.hpp) from the jittered Kuhn cube mesh with N^3 cells
// (6 N^3 tets; N = 60 unless ANITET_BENCH_TRANSFER_N says otherwise) to the vertices of another
// jittered cube mesh of 1.2 N cells a side (what an adaptation's new mesh looks like to it):
// the locator's construction, the location of every point, and the interpolation of a scalar, a
// vector and a metric (log-Euclidean). Each on one thread and on all (Arg: 1 = one thread,
// 0 = all). The machine is shared: compare CPU times of the same run.
#include <benchmark/benchmark.h>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cstdlib>
#include <memory>
#include <random>
#include <vector>

#include "metric/field_transfer.hpp"
#include "test_util.hpp"  // tests/unit/metric: cube_mesh, random_spd

namespace {

using namespace anitet;
using namespace anitet::metric;

int mesh_n() {
  const char* s = std::getenv("ANITET_BENCH_TRANSFER_N");
  return s ? std::max(2, std::atoi(s)) : 60;
}

// [0, 1]^3 with its interior vertices moved by up to 0.2 cell (every tet stays positive).
VolumeMesh jittered_cube(int n, unsigned seed) {
  VolumeMesh m = test::cube_mesh(n);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    bool interior = true;
    for (int k = 0; k < 3; ++k) interior = interior && m.xyz[3 * v + size_t(k)] > 0 && m.xyz[3 * v + size_t(k)] < n;
    for (int k = 0; k < 3; ++k) m.xyz[3 * v + size_t(k)] = (m.xyz[3 * v + size_t(k)] + (interior ? u(rng) : 0.0)) / n;
  }
  return m;
}

struct Setup {
  VolumeMesh old_mesh = jittered_cube(mesh_n(), 1);
  std::vector<double> points = jittered_cube(mesh_n() * 6 / 5, 2).xyz;
  VertexFields fields;
  Setup() {
    fields.kinds = {FieldKind::Scalar, FieldKind::Vector, FieldKind::SymTensor};
    std::mt19937_64 rng(3);
    for (size_t v = 0; v < old_mesh.num_vertices(); ++v) {
      const double* p = old_mesh.point(v);
      double m[6];
      test::random_spd(rng, 0.01, 0.1, m);
      const double record[10] = {p[0] + p[1], p[0], p[1], p[2], m[0], m[1], m[2], m[3], m[4], m[5]};
      fields.values.insert(fields.values.end(), record, record + 10);
    }
  }
};

const Setup& setup() {
  static const Setup s;
  return s;
}

std::unique_ptr<tbb::global_control> threads(const benchmark::State& state) {
  const size_t n = state.range(0) == 1 ? 1 : size_t(tbb::this_task_arena::max_concurrency());
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, n);
}

void Locator_Create(benchmark::State& state) {
  const Setup& s = setup();
  for (auto _ : state) benchmark::DoNotOptimize(TetLocator::create(s.old_mesh));
  state.counters["tets"] = double(s.old_mesh.num_tets());
}

void Locate_Points(benchmark::State& state) {
  const Setup& s = setup();
  const auto control = threads(state);
  const TetLocator locator = TetLocator::create(s.old_mesh).value();
  for (auto _ : state) benchmark::DoNotOptimize(locate_points(locator, s.points.data(), s.points.size() / 3));
  state.counters["points/s"] = benchmark::Counter(double(s.points.size() / 3), benchmark::Counter::kIsIterationInvariantRate);
}

void Interpolate_Fields(benchmark::State& state) {
  const Setup& s = setup();
  const auto control = threads(state);
  const TetLocator locator = TetLocator::create(s.old_mesh).value();
  const PointLocations where = locate_points(locator, s.points.data(), s.points.size() / 3).value();
  for (auto _ : state) benchmark::DoNotOptimize(interpolate_fields(locator, s.fields, where));
  state.counters["points/s"] = benchmark::Counter(double(s.points.size() / 3), benchmark::Counter::kIsIterationInvariantRate);
}

void Transfer_Fields(benchmark::State& state) {
  const Setup& s = setup();
  const auto control = threads(state);
  for (auto _ : state) benchmark::DoNotOptimize(transfer_fields(s.old_mesh, s.fields, s.points));
  state.counters["points/s"] = benchmark::Counter(double(s.points.size() / 3), benchmark::Counter::kIsIterationInvariantRate);
}

BENCHMARK(Locator_Create)->Unit(benchmark::kMillisecond);
BENCHMARK(Locate_Points)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(Interpolate_Fields)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(Transfer_Fields)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
