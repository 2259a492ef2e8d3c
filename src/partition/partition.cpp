#include "partition/partition.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace anitet::partition {
namespace {

// Caller weights as METIS's integers: relative to the largest, in 0 .. scale, a positive weight
// at least 1, with the sum below 2^31 (METIS's indices).
std::vector<int32_t> integer_weights(const double* w, size_t n) {
  double max = 0;
  for (size_t t = 0; t < n; ++t) max = std::max(max, w[t]);
  const double scale = std::min(1000.0, std::floor(double(INT32_MAX - 1) / double(n)));
  std::vector<int32_t> out(n);
  for (size_t t = 0; t < n; ++t) {
    out[t] = w[t] > 0 ? std::max(int32_t(1), int32_t(std::lround(w[t] / max * scale))) : 0;
  }
  return out;
}

Status check_options(const VolumeMesh& mesh, const PartitionOptions& o) {
  const size_t nt = mesh.num_tets();
  if (nt == 0) return Status(Error::EmptyInput, "the mesh has no tet");
  if (o.num_parts < 1 || size_t(o.num_parts) > nt) {
    return Status(Error::InvalidArgument, "num_parts is " + std::to_string(o.num_parts) + ", not in [1, " +
                                              std::to_string(nt) + "] (the mesh's tets)");
  }
  if (o.ghost_layers < 0) {
    return Status(Error::InvalidArgument, "ghost_layers is " + std::to_string(o.ghost_layers) + ", not >= 0");
  }
  if (!(o.imbalance > 0 && o.imbalance <= 1)) {
    return Status(Error::InvalidArgument, "imbalance is " + std::to_string(o.imbalance) + ", not in (0, 1]");
  }
  if (o.tet_weights) {
    bool positive = false;
    for (size_t t = 0; t < nt; ++t) {
      const double w = o.tet_weights[t];
      if (!std::isfinite(w) || w < 0) {
        return Status(Error::InvalidArgument, "the weight of tet " + std::to_string(t) + " is " + std::to_string(w) +
                                                  ", not finite and >= 0");
      }
      positive = positive || w > 0;
    }
    if (!positive) return Status(Error::InvalidArgument, "every tet weight is 0");
  }
  return Status::success();
}

}  // namespace

PartitionQuality measure_partition(const Csr& dual, const Csr& vertex_tets, const std::vector<int32_t>& tet_part,
                                   int num_parts, const double* weights) {
  PartitionQuality q;
  const size_t nt = dual.rows();
  q.edge_cut = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, nt, 16384), int64_t(0),
      [&](const tbb::blocked_range<size_t>& r, int64_t cut) {
        for (size_t t = r.begin(); t != r.end(); ++t)
          for (int64_t k = dual.begin(t); k < dual.end(t); ++k)
            cut += dual.items[size_t(k)] > t && tet_part[dual.items[size_t(k)]] != tet_part[t];
        return cut;
      },
      [](int64_t a, int64_t b) { return a + b; });
  for (size_t v = 0; v < vertex_tets.rows(); ++v) {
    for (int64_t k = vertex_tets.begin(v) + 1; k < vertex_tets.end(v); ++k)
      if (tet_part[vertex_tets.items[size_t(k)]] != tet_part[vertex_tets.items[size_t(vertex_tets.begin(v))]]) {
        ++q.interface_vertices;
        break;
      }
  }
  std::vector<double> load(size_t(num_parts), 0.0);
  std::vector<int64_t> count(size_t(num_parts), 0);
  for (size_t t = 0; t < nt; ++t) {
    load[size_t(tet_part[t])] += weights ? weights[t] : 1.0;
    ++count[size_t(tet_part[t])];
  }
  for (int p = 0; p < num_parts; ++p) {
    q.total_weight += load[size_t(p)];
    q.max_part_weight = std::max(q.max_part_weight, load[size_t(p)]);
    q.empty_parts += count[size_t(p)] == 0;
  }
  q.imbalance = q.total_weight > 0 ? q.max_part_weight * num_parts / q.total_weight - 1.0 : 0.0;
  return q;
}

Result<Partition> partition_mesh(const VolumeMesh& mesh, const PartitionOptions& options) {
  Status ok = check_options(mesh, options);
  if (!ok.ok()) return ok;
  Result<Csr> dual = dual_graph(mesh);
  if (!dual.ok()) return dual.status();
  Result<Csr> vtets = vertex_tets(mesh);
  if (!vtets.ok()) return vtets.status();
  std::vector<int32_t> weights;
  if (options.tet_weights) weights = integer_weights(options.tet_weights, mesh.num_tets());
  Result<std::vector<int32_t>> cut = cut_dual_graph(dual.value(), options.num_parts, weights, options.imbalance);
  if (!cut.ok()) return cut.status();
  Partition out;
  out.tet_part = std::move(cut).value();
  out.quality = measure_partition(dual.value(), vtets.value(), out.tet_part, options.num_parts, options.tet_weights);
  dual = Csr{};
  Result<std::vector<Part>> parts = build_parts(mesh, vtets.value(), out.tet_part, options.num_parts, options.ghost_layers);
  if (!parts.ok()) return parts.status();
  out.parts = std::move(parts).value();
  return out;
}

}  // namespace anitet::partition
