// ns/call of the predicates on random inputs (the filter's speed) and on degenerate inputs (the
// exact path's), with the fraction of calls that needed the exact path as a counter.
//   predicates_bench --benchmark_filter=orient3d
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "predicates/predicates.hpp"

namespace {

using anitet::predicates::PredicateCounters;
using anitet::predicates::reset_thread_counters;
using anitet::predicates::thread_counters;

constexpr int kPoints = 1 << 12;  // 96 KB of points: measures the predicate, not memory

enum class Data { Random, Translated, Grid, Cospherical };

// Points for each data kind: uniform in the unit cube; the same shifted by 1e6 and scaled by
// 1e-4 (near-degenerate in double: the filter still has to decide most of them); a 4x4x4
// integer grid (coplanar/cospherical ties everywhere); rounded points on a sphere.
std::vector<double> make_points(Data kind) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> p(3 * kPoints);
  for (int i = 0; i < kPoints; ++i) {
    double* q = &p[3 * size_t(i)];
    switch (kind) {
      case Data::Random:
        for (int k = 0; k < 3; ++k) q[k] = u(rng);
        break;
      case Data::Translated:
        for (int k = 0; k < 3; ++k) q[k] = 1e6 + 1e-4 * u(rng);
        break;
      case Data::Grid:
        for (int k = 0; k < 3; ++k) q[k] = std::floor(4 * u(rng));
        break;
      case Data::Cospherical: {
        const double th = 6.283185307179586 * u(rng), z = 2 * u(rng) - 1;
        const double s = std::sqrt(1 - z * z);
        q[0] = s * std::cos(th);
        q[1] = s * std::sin(th);
        q[2] = z;
        break;
      }
    }
  }
  return p;
}

// Random index tuples into the points (precomputed so that the loop measures the predicate).
std::vector<std::array<uint32_t, 5>> make_tuples() {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<uint32_t> pick(0, kPoints - 1);
  std::vector<std::array<uint32_t, 5>> t(kPoints);
  for (auto& x : t) {
    for (size_t j = 0; j < x.size(); ++j) {
      do {  // distinct points: duplicates are degenerate by construction
        x[j] = pick(rng);
      } while (std::find(x.begin(), x.begin() + long(j), x[j]) != x.begin() + long(j));
    }
  }
  return t;
}

void report(benchmark::State& state, uint64_t calls, uint64_t exact) {
  state.counters["exact_fraction"] = double(exact) / double(calls ? calls : 1);
  state.SetItemsProcessed(int64_t(calls));
}

void BM_orient3d(benchmark::State& state) {
  const auto pts = make_points(Data(state.range(0)));
  const auto tup = make_tuples();
  reset_thread_counters();
  size_t i = 0;
  for (auto _ : state) {
    const auto& t = tup[i++ & (kPoints - 1)];
    benchmark::DoNotOptimize(anitet::predicates::orient3d(&pts[3 * t[0]], &pts[3 * t[1]],
                                                          &pts[3 * t[2]], &pts[3 * t[3]]));
  }
  report(state, thread_counters().orient3d_calls, thread_counters().orient3d_exact);
}

void BM_insphere(benchmark::State& state) {
  const auto pts = make_points(Data(state.range(0)));
  const auto tup = make_tuples();
  reset_thread_counters();
  size_t i = 0;
  for (auto _ : state) {
    const auto& t = tup[i++ & (kPoints - 1)];
    benchmark::DoNotOptimize(anitet::predicates::insphere(&pts[3 * t[0]], &pts[3 * t[1]],
                                                          &pts[3 * t[2]], &pts[3 * t[3]],
                                                          &pts[3 * t[4]]));
  }
  report(state, thread_counters().insphere_calls, thread_counters().insphere_exact);
}

void BM_insphere_sos(benchmark::State& state) {
  const auto pts = make_points(Data(state.range(0)));
  const auto tup = make_tuples();
  reset_thread_counters();
  size_t i = 0;
  for (auto _ : state) {
    const auto& t = tup[i++ & (kPoints - 1)];
    benchmark::DoNotOptimize(anitet::predicates::insphere_sos(
        &pts[3 * t[0]], &pts[3 * t[1]], &pts[3 * t[2]], &pts[3 * t[3]], &pts[3 * t[4]], t[0],
        t[1], t[2], t[3], t[4]));
  }
  report(state, thread_counters().insphere_calls, thread_counters().insphere_exact);
  state.counters["sos_ties"] =
      double(thread_counters().sos_ties) / double(thread_counters().insphere_calls);
}

void BM_orient2d(benchmark::State& state) {
  const auto pts = make_points(Data(state.range(0)));
  const auto tup = make_tuples();
  reset_thread_counters();
  size_t i = 0;
  for (auto _ : state) {
    const auto& t = tup[i++ & (kPoints - 1)];
    benchmark::DoNotOptimize(
        anitet::predicates::orient2d(&pts[3 * t[0]], &pts[3 * t[1]], &pts[3 * t[2]]));
  }
  report(state, thread_counters().orient2d_calls, thread_counters().orient2d_exact);
}

void BM_orient4d(benchmark::State& state) {
  const auto pts = make_points(Data(state.range(0)));
  const auto tup = make_tuples();
  std::vector<double> h(kPoints);
  for (int j = 0; j < kPoints; ++j) {
    const double* q = &pts[3 * size_t(j)];
    h[size_t(j)] = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
  }
  reset_thread_counters();
  size_t i = 0;
  for (auto _ : state) {
    const auto& t = tup[i++ & (kPoints - 1)];
    benchmark::DoNotOptimize(anitet::predicates::orient4d(
        &pts[3 * t[0]], &pts[3 * t[1]], &pts[3 * t[2]], &pts[3 * t[3]], &pts[3 * t[4]], h[t[0]],
        h[t[1]], h[t[2]], h[t[3]], h[t[4]]));
  }
  report(state, thread_counters().orient4d_calls, thread_counters().orient4d_exact);
}

void data_args(benchmark::internal::Benchmark* b) {
  b->ArgName("data")->Arg(int(Data::Random))->Arg(int(Data::Translated))->Arg(int(Data::Grid))
      ->Arg(int(Data::Cospherical));
}

BENCHMARK(BM_orient2d)->Apply(data_args);
BENCHMARK(BM_orient3d)->Apply(data_args);
BENCHMARK(BM_insphere)->Apply(data_args);
BENCHMARK(BM_insphere_sos)->Apply(data_args);
BENCHMARK(BM_orient4d)->Apply(data_args);

}  // namespace

BENCHMARK_MAIN();
