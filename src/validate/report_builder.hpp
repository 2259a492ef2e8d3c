// Helpers that fill a ValidationReport: problems with capped examples, and text formatting.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "validate/validate.hpp"

namespace anitet::report_detail {

inline std::string format_point(const double* p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.9g, %.9g, %.9g)", p[0], p[1], p[2]);
  return buf;
}

// Messages number triangles and vertices from 1, in the order of the surface as read (vertices
// after the merge of duplicates), as people and most file formats count; the report's examples
// and every array keep 0-based ids.
inline std::string one_based(uint32_t id) { return std::to_string(uint64_t{id} + 1); }

inline std::string format_ids(const std::vector<uint32_t>& ids) {
  std::string out = "(";
  for (size_t i = 0; i < ids.size(); ++i) out += (i ? ", " : "") + one_based(ids[i]);
  return out + ")";
}

inline std::vector<uint32_t> corners(const SurfaceMesh& s, size_t t) {
  return {s.tri[3 * t], s.tri[3 * t + 1], s.tri[3 * t + 2]};
}

// Adds the problems of one validation run to its report.
class ReportBuilder {
 public:
  ReportBuilder(const SurfaceMesh& s, size_t max_examples, ValidationReport& report)
      : s_(s), max_examples_(max_examples), report_(report) {}

  // An instance: the elements and the coordinates of its vertices.
  ProblemExample example(std::vector<uint32_t> triangles, std::vector<uint32_t> vertices) const {
    ProblemExample ex;
    ex.triangles = std::move(triangles);
    ex.vertices = std::move(vertices);
    for (uint32_t v : ex.vertices) {
      if (v < s_.num_vertices()) {
        const double* p = s_.point(v);
        ex.points.push_back({p[0], p[1], p[2]});
      } else {
        ex.points.push_back({NAN, NAN, NAN});  // a bad index has no coordinates
      }
    }
    return ex;
  }

  // Adds a problem of `count` instances (nothing when count is 0); make_example(k) builds
  // instance k for the first max_examples ones.
  template <class MakeExample>
  void add(Error code, Severity severity, const char* kind, size_t count, std::string message,
           MakeExample&& make_example) {
    if (count == 0) return;
    Problem p;
    p.code = code;
    p.kind = kind;
    p.severity = severity;
    p.count = count;
    p.message = std::move(message);
    for (size_t k = 0; k < std::min(count, max_examples_); ++k) {
      p.examples.push_back(make_example(k));
    }
    report_.problems.push_back(std::move(p));
  }

  template <class MakeExample>
  void error(Error code, size_t count, std::string message, MakeExample&& make_example) {
    add(code, Severity::Error, error_name(code), count, std::move(message), make_example);
  }

  // An error about the whole input (no element to name).
  void error(Error code, std::string message) {
    error(code, 1, std::move(message), [](size_t) { return ProblemExample{}; });
  }

  size_t max_examples() const { return max_examples_; }

 private:
  const SurfaceMesh& s_;
  size_t max_examples_;
  ValidationReport& report_;
};

}  // namespace anitet::report_detail
