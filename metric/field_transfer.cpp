#include "field_transfer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "spd.hpp"

namespace anitet {
namespace metric {

namespace {

constexpr size_t kGrain = 1024;  // points per task

struct OutsideCount {
  size_t count = 0;
  double max_distance = 0.0;
};

// log M of one tensor field at every old vertex; the first vertex (counting from 0) whose tensor
// is not SPD, or SIZE_MAX.
size_t log_tensors(const VertexFields& fields, size_t offset, std::vector<double>& logs) {
  const size_t nv = fields.num_vertices(), record = fields.record_size();
  logs.resize(6 * nv);
  std::vector<uint8_t> bad(nv, 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nv, kGrain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t v = r.begin(); v != r.end(); ++v) {
      if (!sym_log(&fields.values[record * v + offset], &logs[6 * v])) bad[v] = 1;
    }
  });
  const auto first = std::find(bad.begin(), bad.end(), uint8_t(1));
  return first == bad.end() ? SIZE_MAX : size_t(first - bad.begin());
}

// One record per old vertex.
Status check_fields(const VertexFields& fields, size_t nv) {
  const size_t record = fields.record_size();
  if (record == 0 || fields.values.size() != record * nv) {
    return Status(Error::InvalidArgument, "the fields have " + std::to_string(record ? fields.values.size() / record : 0) +
                                              " vertex records (" + std::to_string(fields.values.size()) +
                                              " values) for a mesh of " + std::to_string(nv) +
                                              " vertices: a field of another mesh?");
  }
  return Status::success();
}

}  // namespace

Result<PointLocations> locate_points(const TetLocator& old_mesh, const double* xyz, size_t num_points) {
  for (size_t i = 0; i < 3 * num_points; ++i) {
    if (!std::isfinite(xyz[i])) {
      return Status(Error::InvalidArgument, "point " + std::to_string(i / 3) + " has a coordinate that is not finite");
    }
  }
  PointLocations out;
  out.tet.resize(num_points);
  out.weight.resize(4 * num_points);
  // (Each point is located on its own: the answer does not depend on how the points are split.)
  const OutsideCount outside = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, num_points, kGrain), OutsideCount(),
      [&](const tbb::blocked_range<size_t>& r, OutsideCount acc) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
          const TetLocator::Location loc = old_mesh.locate(xyz + 3 * i);
          out.tet[i] = loc.tet;
          std::copy(loc.weight, loc.weight + 4, &out.weight[4 * i]);
          if (loc.outside) {
            ++acc.count;
            acc.max_distance = std::max(acc.max_distance, loc.distance);
          }
        }
        return acc;
      },
      [](OutsideCount a, const OutsideCount& b) {
        a.count += b.count;
        a.max_distance = std::max(a.max_distance, b.max_distance);
        return a;
      });
  out.outside = outside.count;
  out.max_outside_distance = outside.max_distance;
  return out;
}

Result<VertexFields> interpolate_fields(const TetLocator& old_mesh, const VertexFields& fields,
                                        const PointLocations& where, TensorInterpolation tensors,
                                        TransferReport* report) {
  const size_t record = fields.record_size();
  if (Status s = check_fields(fields, old_mesh.num_vertices()); !s.ok()) return s;
  const bool tets_ok = std::all_of(where.tet.begin(), where.tet.end(), [&](uint32_t t) { return t < old_mesh.num_tets(); });
  if (where.weight.size() != 4 * where.tet.size() || !tets_ok) {
    return Status(Error::InvalidArgument, "point locations of another mesh, or inconsistent");
  }
  // Tensor fields interpolated in log space: their logs at the old vertices.
  const size_t nf = fields.kinds.size();
  std::vector<std::vector<double>> logs(nf);
  std::vector<bool> log_euclidean(nf, false);
  for (size_t f = 0; f < nf; ++f) {
    if (fields.kinds[f] != FieldKind::SymTensor || tensors == TensorInterpolation::Linear) continue;
    const size_t bad = log_tensors(fields, fields.offset(f), logs[f]);
    if (bad == SIZE_MAX) {
      log_euclidean[f] = true;
    } else if (tensors == TensorInterpolation::LogEuclidean) {
      return Status(Error::InvalidArgument, "field " + std::to_string(f + 1) + ": the tensor of vertex " +
                                                std::to_string(bad + 1) + " (counting from 1) is not positive definite");
    } else {
      logs[f].clear();
    }
  }
  const size_t np = where.num_points();
  VertexFields out;
  out.kinds = fields.kinds;
  out.values.resize(np * record);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, np, kGrain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const uint32_t* v = old_mesh.tet(where.tet[i]);
      const double* w = &where.weight[4 * i];
      double* dst = &out.values[record * i];
      for (size_t f = 0, offset = 0; f < nf; offset += size_t(field_components(fields.kinds[f])), ++f) {
        const size_t n = size_t(field_components(fields.kinds[f]));
        if (log_euclidean[f]) {
          double l[6] = {0, 0, 0, 0, 0, 0};
          for (int k = 0; k < 4; ++k)
            for (size_t c = 0; c < 6; ++c) l[c] += w[k] * logs[f][6 * size_t(v[k]) + c];
          sym_exp(l, dst + offset);
          continue;
        }
        for (size_t c = 0; c < n; ++c) {
          double x = 0.0;
          for (int k = 0; k < 4; ++k) x += w[k] * fields.values[record * size_t(v[k]) + offset + c];
          dst[offset + c] = x;
        }
      }
    }
  });
  if (report) {
    report->outside = where.outside;
    report->max_outside_distance = where.max_outside_distance;
    report->log_euclidean = log_euclidean;
  }
  return out;
}

Result<VertexFields> transfer_fields(const VolumeMesh& old_mesh, const VertexFields& fields,
                                     const std::vector<double>& new_xyz, TensorInterpolation tensors,
                                     TransferReport* report) {
  if (new_xyz.size() % 3 != 0) return Status(Error::InvalidArgument, "new points: not 3 coordinates each");
  if (Status s = check_fields(fields, old_mesh.num_vertices()); !s.ok()) return s;
  Result<TetLocator> locator = TetLocator::create(old_mesh);
  if (!locator.ok()) return locator.status();
  Result<PointLocations> where = locate_points(locator.value(), new_xyz.data(), new_xyz.size() / 3);
  if (!where.ok()) return where.status();
  return interpolate_fields(locator.value(), fields, where.value(), tensors, report);
}

}  // namespace metric
}  // namespace anitet
