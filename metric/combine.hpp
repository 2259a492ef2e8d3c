// Sizing fields built from others: an analytic callable, the intersection of several fields, and
// size bounds. All are immutable and as thread-safe as the fields (callables) they wrap.
#pragma once

#include <functional>
#include <vector>

#include "core/sizing.hpp"

namespace anitet {
namespace metric {

// A field given by a callable p -> M (SPD, xx xy yy xz yz zz). The C ABI wraps its C callback
// in one of these.
class AnalyticField final : public SizingField {
 public:
  using Function = std::function<void(const double p[3], double m[6])>;
  explicit AnalyticField(Function f) : f_(std::move(f)) {}
  void metric(const double p[3], double m[6]) const override { f_(p, m); }

 private:
  Function f_;
};

// The intersection of several fields at each point: metrics are intersected pairwise in order
// (simultaneous reduction). For two fields this is the largest ellipsoid inside both; for more it
// is an ellipsoid inside all of them (pairwise intersection is not associative in general).
// The fields must outlive this one.
class IntersectionField final : public SizingField {
 public:
  explicit IntersectionField(std::vector<const SizingField*> fields) : fields_(std::move(fields)) {}
  void metric(const double p[3], double m[6]) const override;

 private:
  std::vector<const SizingField*> fields_;
};

// Sizes of another field clamped to [hmin, hmax] (<= 0: no bound), eigenvectors kept.
class BoundedField final : public SizingField {
 public:
  BoundedField(const SizingField& field, double hmin, double hmax)
      : field_(field), hmin_(hmin), hmax_(hmax) {}
  void metric(const double p[3], double m[6]) const override;

 private:
  const SizingField& field_;
  double hmin_, hmax_;
};

}  // namespace metric
}  // namespace anitet
