// Where adaptation gets the metric at a point it creates or moves: the input's per-vertex
// tensors interpolated in log-Euclidean space in the input mesh (a point located by TetLocator's
// walk from the tet where a neighbouring point was found), or a SizingField.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/sizing.hpp"
#include "core/status.hpp"
#include "core/volume_mesh.hpp"
#include "metric/tet_locator.hpp"

namespace anitet::adapt {

class MetricSource {
 public:
  virtual ~MetricSource() = default;
  // The metric at p; `hint` is a start for the point location (a tet of the input, or kNoTet)
  // and gets where p was found.
  virtual void eval(const double p[3], uint32_t& hint, double m[6]) const = 0;
};

class VertexMetricSource final : public MetricSource {
 public:
  // values: 1 (size) or 6 (tensor) per vertex of `mesh`, checked (sizes > 0, tensors SPD: the
  // first bad vertex named, 1-based, in an Error::InvalidArgument).
  static Result<std::unique_ptr<VertexMetricSource>> create(const VolumeMesh& mesh, const std::vector<double>& values);
  void eval(const double p[3], uint32_t& hint, double m[6]) const override;
  // The tensor at input vertex v (exactly as given, a size as I / h^2).
  void at_vertex(uint32_t v, double m[6]) const;

 private:
  explicit VertexMetricSource(metric::TetLocator locator) : locator_(std::move(locator)) {}
  metric::TetLocator locator_;
  std::vector<double> tensor_;  // 6 per vertex
  std::vector<double> log_;     // 6 per vertex
};

class FieldMetricSource final : public MetricSource {
 public:
  explicit FieldMetricSource(const SizingField& field) : field_(field) {}
  void eval(const double p[3], uint32_t& hint, double m[6]) const override {
    (void)hint;
    field_.metric(p, m);
  }

 private:
  const SizingField& field_;
};

}  // namespace anitet::adapt
