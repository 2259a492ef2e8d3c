// Batched metric queries at random points of an N^3-voxel tensor field (N = 256 unless
// ANITET_BENCH_METRIC_N says otherwise): MetricField (two OpenVDB Vec3d grids holding log(M))
// against trilinear interpolation of the same six doubles from a dense interleaved array, in the
// same run. Pairs to compare:
//   Dense_LogTrilinear  vs  Vdb_LogTrilinear_Batched (and _LogTrilinear, point by point)
//                           the interpolation alone: the criterion
//   Dense_Metric        vs  Vdb_Metric (batched; and Vdb_Metric_PerPoint)   plus exp() back to M
//   Dense_Size          vs  Vdb_Size (batched)   an isotropic size grid (one double per voxel)
// Batched Vdb calls sort their points by leaf (inside the timed region). The machine is shared:
// compare CPU times of the same run (wall times swing with the other jobs).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <random>
#include <vector>

#include "metric/lattice.hpp"
#include "metric/metric_field.hpp"
#include "metric/spd.hpp"

namespace {

using anitet::metric::Lattice;
using anitet::metric::MetricField;

constexpr size_t kBatch = 1 << 20;  // random points per batch

int grid_n() {
  const char* s = std::getenv("ANITET_BENCH_METRIC_N");
  return s ? std::max(2, std::atoi(s)) : 256;
}

// A smooth anisotropic log-metric: sizes 1e-3 .. 1e-1 turning with position.
void log_metric_at(const double p[3], double l[6]) {
  const double a = std::sin(6.0 * p[0]) * std::cos(4.0 * p[1]), b = std::cos(5.0 * p[2]);
  l[0] = 2.0 * std::log(1.0 / (0.01 + 0.009 * a));
  l[2] = 2.0 * std::log(1.0 / (0.02 + 0.01 * b));
  l[5] = 2.0 * std::log(1.0 / (0.05 + 0.04 * a * b));
  l[1] = 0.5 * a;
  l[3] = 0.3 * b;
  l[4] = 0.2 * a * b;
}

struct Fixture {
  int n = 0;
  double dx = 0.0;
  std::vector<double> dense;       // 6 per node, x fastest
  std::vector<double> dense_size;  // 1 per node
  std::unique_ptr<MetricField> field, size_field;
  std::vector<double> points;      // kBatch random points in the unit cube

  Fixture() {
    n = grid_n();
    dx = 1.0 / (n - 1);
    Lattice lat;
    lat.spacing = dx;
    lat.dims[0] = lat.dims[1] = lat.dims[2] = n;
    lat.components = 6;
    lat.values.resize(6 * lat.num_nodes());
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          double p[3];
          lat.position(i, j, k, p);
          log_metric_at(p, &lat.values[6 * lat.node(i, j, k)]);
        }
    field = std::make_unique<MetricField>(std::move(MetricField::from_lattice(lat).value()));
    dense = std::move(lat.values);
    Lattice sl;
    sl.spacing = dx;
    sl.dims[0] = sl.dims[1] = sl.dims[2] = n;
    sl.components = 1;
    sl.values.resize(sl.num_nodes());
    for (size_t v = 0; v < sl.num_nodes(); ++v) sl.values[v] = std::exp(-0.5 * dense[6 * v]);
    size_field = std::make_unique<MetricField>(std::move(MetricField::from_lattice(sl).value()));
    dense_size = std::move(sl.values);
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    points.resize(3 * kBatch);
    for (double& x : points) x = u(rng);
  }

  // Plain trilinear interpolation of `comp` interleaved doubles per node.
  template <int comp>
  inline void dense_trilinear(const std::vector<double>& data, const double p[3], double out[comp]) const {
    const double inv = 1.0 / dx;
    int base[3];
    double f[3];
    for (int a = 0; a < 3; ++a) {
      double x = std::min(std::max(p[a] * inv, 0.0), double(n - 1));
      int i = std::min(int(x), n - 2);
      base[a] = i;
      f[a] = x - i;
    }
    const size_t sx = comp, sy = size_t(comp) * n, sz = size_t(comp) * n * n;
    const double* c = &data[base[0] * sx + base[1] * sy + base[2] * sz];
    for (int q = 0; q < comp; ++q) {
      const double c00 = c[q] + f[0] * (c[q + sx] - c[q]);
      const double c10 = c[q + sy] + f[0] * (c[q + sy + sx] - c[q + sy]);
      const double c01 = c[q + sz] + f[0] * (c[q + sz + sx] - c[q + sz]);
      const double c11 = c[q + sz + sy] + f[0] * (c[q + sz + sy + sx] - c[q + sz + sy]);
      const double c0 = c00 + f[1] * (c10 - c00), c1 = c01 + f[1] * (c11 - c01);
      out[q] = c0 + f[2] * (c1 - c0);
    }
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

void Dense_LogTrilinear(benchmark::State& state) {
  Fixture& f = fixture();
  std::vector<double> out(6 * kBatch);
  for (auto _ : state) {
    for (size_t i = 0; i < kBatch; ++i) f.dense_trilinear<6>(f.dense, &f.points[3 * i], &out[6 * i]);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * kBatch);
}

void Vdb_LogTrilinear(benchmark::State& state) {
  Fixture& f = fixture();
  MetricField::Sampler s(*f.field);
  std::vector<double> out(6 * kBatch);
  for (auto _ : state) {
    for (size_t i = 0; i < kBatch; ++i) s.log_metric(&f.points[3 * i], &out[6 * i]);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * kBatch);
}

void Vdb_LogTrilinear_Batched(benchmark::State& state) {
  Fixture& f = fixture();
  MetricField::Sampler s(*f.field);
  std::vector<double> out(6 * kBatch);
  for (auto _ : state) {
    s.log_metrics(f.points.data(), kBatch, out.data());
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * kBatch);
}

void Dense_Metric(benchmark::State& state) {
  Fixture& f = fixture();
  std::vector<double> out(6 * kBatch);
  for (auto _ : state) {
    for (size_t i = 0; i < kBatch; ++i) {
      double l[6];
      f.dense_trilinear<6>(f.dense, &f.points[3 * i], l);
      anitet::metric::sym_exp(l, &out[6 * i]);
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * kBatch);
}

void Vdb_Metric(benchmark::State& state) {
  Fixture& f = fixture();
  MetricField::Sampler s(*f.field);
  std::vector<double> out(6 * kBatch);
  for (auto _ : state) {
    s.metrics(f.points.data(), kBatch, out.data());
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * kBatch);
}

void Vdb_Metric_PerPoint(benchmark::State& state) {
  Fixture& f = fixture();
  MetricField::Sampler s(*f.field);
  std::vector<double> out(6 * kBatch);
  for (auto _ : state) {
    for (size_t i = 0; i < kBatch; ++i) s.metric(&f.points[3 * i], &out[6 * i]);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * kBatch);
}

void Dense_Size(benchmark::State& state) {
  Fixture& f = fixture();
  std::vector<double> out(6 * kBatch);
  for (auto _ : state) {
    for (size_t i = 0; i < kBatch; ++i) {
      double h;
      f.dense_trilinear<1>(f.dense_size, &f.points[3 * i], &h);
      anitet::isotropic_metric(h, &out[6 * i]);
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * kBatch);
}

void Vdb_Size(benchmark::State& state) {
  Fixture& f = fixture();
  MetricField::Sampler s(*f.size_field);
  std::vector<double> out(6 * kBatch);
  for (auto _ : state) {
    s.metrics(f.points.data(), kBatch, out.data());
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * kBatch);
}

void Field_Memory(benchmark::State& state) {
  Fixture& f = fixture();
  for (auto _ : state) benchmark::DoNotOptimize(f.field.get());
  state.counters["vdb_MB"] = double(f.field->memory_bytes()) / 1048576.0;
  state.counters["dense_MB"] = double(f.dense.size() * sizeof(double)) / 1048576.0;
  state.counters["voxels"] = double(f.field->active_voxels());
}

BENCHMARK(Field_Memory)->Iterations(1);
BENCHMARK(Dense_LogTrilinear)->Unit(benchmark::kMillisecond);
BENCHMARK(Vdb_LogTrilinear)->Unit(benchmark::kMillisecond);
BENCHMARK(Vdb_LogTrilinear_Batched)->Unit(benchmark::kMillisecond);
BENCHMARK(Dense_Metric)->Unit(benchmark::kMillisecond);
BENCHMARK(Vdb_Metric)->Unit(benchmark::kMillisecond);
BENCHMARK(Vdb_Metric_PerPoint)->Unit(benchmark::kMillisecond);
BENCHMARK(Dense_Size)->Unit(benchmark::kMillisecond);
BENCHMARK(Vdb_Size)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
