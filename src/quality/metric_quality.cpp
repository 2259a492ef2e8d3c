// The UGAWG measures of a mesh that carries a vertex metric: metric edge lengths (each edge
// once) and the mean ratio of each tet in its finest corner's metric.
#include <algorithm>
#include <cmath>
#include <string>

#include <tbb/parallel_sort.h>

#include "core/metric_measures.hpp"
#include "quality/parallel_for.hpp"
#include "quality/report_detail.hpp"

namespace anitet::quality_detail {

namespace {

// Readable bins around the range [1/sqrt 2, sqrt 2] that UGAWG counts.
const std::vector<double> kLengthBins = {0.0, 0.3, 0.5, 0.6, kUnitRangeMin, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3,
                                         kUnitRangeMax, 1.6, 2.0, 3.0, 5.0};

}  // namespace

Status measure_metric(const VolumeMesh& mesh, int histogram_bins, bool parallel, MetricQuality& out) {
  out = MetricQuality();
  const size_t nv = mesh.num_vertices(), nt = mesh.num_tets();
  const std::vector<double>& vm = mesh.vertex_metric;
  if (vm.empty()) return Status::success();
  if (vm.size() != nv && vm.size() != 6 * nv)
    return Status(Error::InvalidArgument, "the vertex metric has " + std::to_string(vm.size()) + " values for " +
                                              std::to_string(nv) + " vertices (1 size or 6 tensor components each)");
  // Tensors (sizes as I / h^2), checked SPD, and their determinants.
  std::vector<double> m(6 * nv), det(nv);
  for (size_t v = 0; v < nv; ++v) {
    double* t = &m[6 * v];
    if (vm.size() == nv) {
      const double h = vm[v];
      if (!(h > 0.0) || !std::isfinite(h))
        return Status(Error::InvalidArgument, "the metric's size at vertex " + std::to_string(v + 1) + " is not > 0");
      const double s = 1.0 / (h * h);
      t[0] = t[2] = t[5] = s;
      t[1] = t[3] = t[4] = 0.0;
    } else {
      std::copy(&vm[6 * v], &vm[6 * v] + 6, t);
    }
    det[v] = metric_det(t);
    const double minor2 = t[0] * t[2] - t[1] * t[1];
    if (!(t[0] > 0.0) || !(minor2 > 0.0) || !(det[v] > 0.0) || !std::isfinite(det[v]))
      return Status(Error::InvalidArgument,
                    "the metric tensor at vertex " + std::to_string(v + 1) + " is not symmetric positive definite");
  }
  out.present = true;
  // Edges once each.
  std::vector<uint64_t> keys(6 * nt);
  for_chunks(nt, parallel, [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t) {
      const uint32_t* w = &mesh.tet[4 * t];
      static const int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
      for (int e = 0; e < 6; ++e) {
        const uint32_t a = std::min(w[kEdge[e][0]], w[kEdge[e][1]]), b = std::max(w[kEdge[e][0]], w[kEdge[e][1]]);
        keys[6 * t + size_t(e)] = (uint64_t(a) << 32) | b;
      }
    }
  });
  if (parallel) tbb::parallel_sort(keys.begin(), keys.end());
  else std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<double> length(keys.size());
  for_chunks(keys.size(), parallel, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      const auto a = uint32_t(keys[k] >> 32), b = uint32_t(keys[k] & 0xffffffffu);
      length[k] = ugawg_edge_length(mesh.point(a), mesh.point(b), &m[6 * size_t(a)], &m[6 * size_t(b)]);
    }
  });
  out.edges = length.size();
  out.edge_length = make_stats(length);
  out.length_bin_edges = kLengthBins;
  out.length_histogram.assign(kLengthBins.size(), 0);
  size_t in = 0, below = 0;
  for (double l : length) {
    in += in_unit_range(l);
    below += l < kUnitRangeMin;
    const auto bin = size_t(std::upper_bound(kLengthBins.begin(), kLengthBins.end(), l) - kLengthBins.begin());
    out.length_histogram[bin > 0 ? bin - 1 : 0] += 1;
  }
  if (!length.empty()) {
    out.in_range = double(in) / double(length.size());
    out.shorter = double(below) / double(length.size());
    out.longer = 1.0 - out.in_range - out.shorter;
  }
  // Mean ratio per tet.
  std::vector<double> q(nt);
  for_chunks(nt, parallel, [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t) {
      const uint32_t* w = &mesh.tet[4 * t];
      uint32_t finest = w[0];
      for (int i = 1; i < 4; ++i)
        if (det[w[i]] > det[finest]) finest = w[i];
      q[t] = ugawg_mean_ratio(mesh.point(w[0]), mesh.point(w[1]), mesh.point(w[2]), mesh.point(w[3]),
                              &m[6 * size_t(finest)], det[finest]);
    }
  });
  out.mean_ratio = make_stats(q);
  const int bins = std::max(1, histogram_bins);
  out.mean_ratio_histogram.assign(size_t(bins), 0);
  for (double x : q) {
    const auto bin = long(std::clamp(x, 0.0, 1.0) * bins);
    out.mean_ratio_histogram[size_t(std::clamp<long>(bin, 0, bins - 1))] += 1;
  }
  return Status::success();
}

}  // namespace anitet::quality_detail
