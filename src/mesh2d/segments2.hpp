// Exact tests on segments in the plane (orient2d), shared by the input's checks and stage 1.
#pragma once

#include <algorithm>

#include "predicates/predicates.hpp"

namespace anitet::mesh2d {

// Whether the segments pq and rs, which share no end, meet anywhere: cross, touch or overlap.
inline bool segments_meet(const double* p, const double* q, const double* r, const double* s) {
  using predicates::orient2d;
  const int o1 = orient2d(p, q, r), o2 = orient2d(p, q, s);
  if (o1 * o2 > 0) return false;
  const int o3 = orient2d(r, s, p), o4 = orient2d(r, s, q);
  if (o3 * o4 > 0) return false;
  if (o1 != 0 || o2 != 0 || o3 != 0 || o4 != 0) return true;
  // Collinear: overlap of the projections on an axis along which they are not constant.
  const int k = (p[0] != q[0] || r[0] != s[0]) ? 0 : 1;
  return std::min(p[k], q[k]) <= std::max(r[k], s[k]) && std::min(r[k], s[k]) <= std::max(p[k], q[k]);
}

// Whether the segments from their shared end o to a and to b overlap (collinear, one side).
inline bool overlap_from(const double* o, const double* a, const double* b) {
  if (predicates::orient2d(o, a, b) != 0) return false;
  for (int k = 0; k < 2; ++k)
    if (a[k] != o[k]) return (a[k] > o[k]) == (b[k] > o[k]);
  return false;
}

// Whether p lies on the segment ab strictly between its ends.
inline bool point_on_segment(const double* a, const double* b, const double* p) {
  if (predicates::orient2d(a, b, p) != 0) return false;
  const int k = a[0] != b[0] ? 0 : 1;
  return std::min(a[k], b[k]) < p[k] && p[k] < std::max(a[k], b[k]);
}

}  // namespace anitet::mesh2d
