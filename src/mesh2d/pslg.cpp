#include "mesh2d/pslg.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "mesh2d/segment_grid.hpp"
#include "mesh2d/segments2.hpp"

namespace anitet::mesh2d {

namespace {

std::string with_origin(const std::string& what, size_t i, int first, const std::vector<Origin>& origin) {
  std::string s = what + " " + std::to_string(i + size_t(first));
  if (i >= origin.size()) return s;
  const Origin& o = origin[i];
  if (o.line) return s + " (line " + std::to_string(o.line) + ")";
  if (o.feature) {
    s += " (feature " + std::to_string(o.feature) + ", polygon " + std::to_string(o.polygon) + ", ring " +
         std::to_string(o.ring);
    if (o.vertex) s += ", vertex " + std::to_string(o.vertex);
    return s + ")";
  }
  return s;
}

std::string prefix(const Pslg& pslg) { return pslg.name.empty() ? std::string() : pslg.name + ": "; }

}  // namespace

std::string describe_point(const Pslg& p, size_t i) { return with_origin("point", i, p.first_index, p.point_origin); }
std::string describe_segment(const Pslg& p, size_t i) { return with_origin("segment", i, p.first_index, p.seg_origin); }
std::string describe_hole(const Pslg& p, size_t i) { return with_origin("hole", i, 1, p.hole_origin); }
std::string describe_region(const Pslg& p, size_t i) { return with_origin("region", i, 1, p.region_origin); }

namespace {

Status check_points(const Pslg& p) {
  const size_t n = p.num_points();
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(p.xy[2 * i]) || !std::isfinite(p.xy[2 * i + 1]))
      return Status(Error::NonFiniteCoordinate, prefix(p) + describe_point(p, i) + " has a coordinate that is not finite");
  for (size_t i = 0; i < p.num_holes(); ++i)
    if (!std::isfinite(p.holes[2 * i]) || !std::isfinite(p.holes[2 * i + 1]))
      return Status(Error::NonFiniteCoordinate, prefix(p) + describe_hole(p, i) + " has a coordinate that is not finite");
  for (size_t i = 0; i < p.regions.size(); ++i)
    if (!std::isfinite(p.regions[i].x) || !std::isfinite(p.regions[i].y) || !std::isfinite(p.regions[i].attribute))
      return Status(Error::NonFiniteCoordinate, prefix(p) + describe_region(p, i) + " has a value that is not finite");
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return std::make_pair(p.xy[2 * a], p.xy[2 * a + 1]) < std::make_pair(p.xy[2 * b], p.xy[2 * b + 1]) ||
           (p.xy[2 * a] == p.xy[2 * b] && p.xy[2 * a + 1] == p.xy[2 * b + 1] && a < b);
  });
  for (size_t k = 1; k < n; ++k) {
    const uint32_t a = order[k - 1], b = order[k];
    if (p.xy[2 * a] == p.xy[2 * b] && p.xy[2 * a + 1] == p.xy[2 * b + 1])
      return Status(Error::DuplicatePoint, prefix(p) + describe_point(p, a) + " and " + describe_point(p, b) +
                                               " are at the same place");
  }
  return Status::success();
}

Status check_segment_ends(const Pslg& p) {
  const size_t n = p.num_points(), m = p.num_segments();
  if (m < 3) return Status(Error::EmptyInput, prefix(p) + "fewer than 3 segments: no domain to mesh");
  if (p.label.size() != m) return Status(Error::InvalidArgument, prefix(p) + "one label per segment is needed");
  std::vector<std::pair<uint64_t, uint32_t>> keys(m);
  for (size_t s = 0; s < m; ++s) {
    const uint32_t a = p.seg[2 * s], b = p.seg[2 * s + 1];
    if (a >= n || b >= n)
      return Status(Error::BadIndex, prefix(p) + describe_segment(p, s) + " refers to point " +
                                         std::to_string(size_t(std::max(a, b)) + size_t(p.first_index)) + ", but there are " +
                                         std::to_string(n) + " points");
    if (a == b)
      return Status(Error::InvalidArgument, prefix(p) + describe_segment(p, s) + " goes from " +
                                                describe_point(p, a) + " to itself");
    keys[s] = {(uint64_t(std::min(a, b)) << 32) | std::max(a, b), uint32_t(s)};
  }
  std::sort(keys.begin(), keys.end());
  for (size_t k = 1; k < m; ++k)
    if (keys[k].first == keys[k - 1].first)
      return Status(Error::InvalidArgument, prefix(p) + describe_segment(p, keys[k - 1].second) + " and " +
                                                describe_segment(p, keys[k].second) + " join the same two points");
  std::vector<uint32_t> degree(n, 0);
  for (uint32_t v : p.seg) ++degree[v];
  for (size_t s = 0; s < m; ++s)
    for (int e = 0; e < 2; ++e) {
      const uint32_t v = p.seg[2 * s + size_t(e)];
      if (degree[v] != 1) continue;
      return Status(Error::OpenBoundary, prefix(p) + "open loop: " + describe_segment(p, s) + " ends at " +
                                             describe_point(p, v) + ", which no other segment continues");
    }
  return Status::success();
}

Status check_crossings(const Pslg& p) {
  SegmentGrid grid(p.xy, p.seg);
  Status found;
  grid.for_each_pair([&](uint32_t s, uint32_t t) {
    const uint32_t a = p.seg[2 * s], b = p.seg[2 * s + 1], c = p.seg[2 * t], d = p.seg[2 * t + 1];
    bool meet;
    if (a == c) meet = overlap_from(p.point(a), p.point(b), p.point(d));
    else if (a == d) meet = overlap_from(p.point(a), p.point(b), p.point(c));
    else if (b == c) meet = overlap_from(p.point(b), p.point(a), p.point(d));
    else if (b == d) meet = overlap_from(p.point(b), p.point(a), p.point(c));
    else meet = segments_meet(p.point(a), p.point(b), p.point(c), p.point(d));
    if (!meet) return true;
    const uint32_t lo = std::min(s, t), hi = std::max(s, t);
    found = Status(Error::SelfIntersection, prefix(p) + describe_segment(p, lo) + " and " + describe_segment(p, hi) +
                                                " cross or overlap");
    return false;
  });
  if (!found.ok()) return found;
  // Points on no segment lying on one.
  std::vector<uint8_t> on_segment(p.num_points(), 0);
  for (uint32_t v : p.seg) on_segment[v] = 1;
  for (size_t v = 0; v < p.num_points(); ++v) {
    if (on_segment[v]) continue;
    const double* q = p.point(v);
    const bool ok = grid.for_each_near(q[0], q[1], [&](uint32_t s) {
      if (!point_on_segment(p.point(p.seg[2 * s]), p.point(p.seg[2 * s + 1]), q)) return true;
      found = Status(Error::SelfIntersection, prefix(p) + describe_point(p, v) + " lies on " + describe_segment(p, s));
      return false;
    });
    if (!ok) return found;
  }
  return Status::success();
}

}  // namespace

Status check_pslg(const Pslg& pslg) {
  if (pslg.xy.size() % 2 != 0 || pslg.seg.size() % 2 != 0 || pslg.holes.size() % 2 != 0)
    return Status(Error::InvalidArgument, prefix(pslg) + "coordinate and index arrays must hold pairs");
  if (Status s = check_points(pslg); !s.ok()) return s;
  if (Status s = check_segment_ends(pslg); !s.ok()) return s;
  return check_crossings(pslg);
}

}  // namespace anitet::mesh2d
