#include "mesh2d/conforming.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "delaunay/spatial_sort.hpp"

namespace anitet::mesh2d {

Result<Triangulation> delaunay_in_box(const std::vector<double>& xy, const std::vector<uint32_t>& which,
                                      uint32_t* first_corner) {
  Triangulation m;
  m.xy = xy;
  m.vtri.assign(m.num_vertices(), kNone);
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  for (uint32_t v : which)
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], xy[2 * size_t(v) + size_t(k)]);
      hi[k] = std::max(hi[k], xy[2 * size_t(v) + size_t(k)]);
    }
  if (which.empty()) lo[0] = lo[1] = hi[0] = hi[1] = 0;
  const double span = std::max({hi[0] - lo[0], hi[1] - lo[1], 1e-300 + std::fabs(lo[0]) * 1e-12});
  const double pad = 0.5 * span + 1.0e-300;
  const uint32_t c0 = m.add_vertex(lo[0] - pad, lo[1] - pad);
  const uint32_t c1 = m.add_vertex(hi[0] + pad, lo[1] - pad);
  const uint32_t c2 = m.add_vertex(hi[0] + pad, hi[1] + pad);
  const uint32_t c3 = m.add_vertex(lo[0] - pad, hi[1] + pad);
  if (first_corner) *first_corner = c0;
  const uint32_t t0 = m.add_triangle(c0, c1, c2), t1 = m.add_triangle(c0, c2, c3);
  m.link(t0, 1, t1, 2);  // (c2, c0) of t0 is opposite c1; (c0, c2) of t1 is opposite c3
  // Insertion order: BRIO rounds sorted along a Hilbert curve (3D, at z = 0).
  std::vector<double> xyz(3 * which.size());
  for (size_t i = 0; i < which.size(); ++i) {
    xyz[3 * i] = xy[2 * size_t(which[i])];
    xyz[3 * i + 1] = xy[2 * size_t(which[i]) + 1];
    xyz[3 * i + 2] = 0.0;
  }
  const std::vector<uint32_t> order = delaunay_detail::brio_order(xyz.data(), which.size(), delaunay_detail::BrioOptions{});
  Kernel kernel(m);
  uint32_t hint = t0;
  for (uint32_t i : order) {
    const uint32_t v = which[i];
    const double* p = &xy[2 * size_t(v)];
    const Location loc = kernel.locate(p, hint);
    if (loc.kind == Location::OnVertex)
      return Status(Error::DuplicatePoint, "points " + std::to_string(m.v(loc.t, loc.k)) + " and " + std::to_string(v) +
                                               " are at the same place");
    if (kernel.insert_vertex(v, loc) == kNone)
      return Status(Error::Internal, "Delaunay: point " + std::to_string(v) + " could not be inserted");
    hint = kernel.created().front();
  }
  return m;
}

Status recover_segments(Triangulation& m, const std::vector<uint32_t>& seg, const std::vector<int32_t>& tags,
                        ConformingStats* stats, size_t max_steiner) {
  // Beside a point at distance d from a segment of length L, recovery splits ~log2(L/d) <= ~2100
  // times in doubles; past the default, the input is beyond what midpoints can resolve (a
  // fuzzer's 6-segment polygon 1e20 long and 1e-8 wide took 100k splits, seconds under ASan).
  if (max_steiner == 0) max_steiner = 64 * (seg.size() / 2) + 16384;
  struct Piece {
    uint32_t a, b;
    int32_t tag;
  };
  std::vector<Piece> todo;
  for (size_t i = seg.size() / 2; i-- > 0;) todo.push_back({seg[2 * i], seg[2 * i + 1], i < tags.size() ? tags[i] : int32_t(i)});
  Kernel kernel(m);
  size_t steiner = 0;
  while (!todo.empty()) {
    const Piece piece = todo.back();
    todo.pop_back();
    uint32_t t;
    int k;
    if (m.find_edge(piece.a, piece.b, t, k) || m.find_edge(piece.b, piece.a, t, k)) {
      if (m.constrained(t, k) && m.edge_tag(t, k) != piece.tag)
        return Status(Error::RecoveryFailed, "two segments share the edge " + std::to_string(piece.a) + "-" +
                                                 std::to_string(piece.b));
      m.set_edge_tag(t, k, piece.tag);
      continue;
    }
    if (++steiner > max_steiner)
      return Status(Error::RecoveryFailed, "segment recovery needs more than " + std::to_string(max_steiner) +
                                               " Steiner points (segments crossing?)");
    const double* a = m.point(piece.a);
    const double* b = m.point(piece.b);
    const double mid[2] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])};
    const Location loc = kernel.locate(mid, m.vtri[piece.a]);
    const uint32_t v = (loc.kind == Location::Inside || loc.kind == Location::OnEdge) ? kernel.insert(mid, loc) : kNone;
    if (v == kNone)
      return Status(Error::RecoveryFailed, "the midpoint of the piece " + std::to_string(piece.a) + "-" +
                                               std::to_string(piece.b) + " cannot be inserted (crossing segments?)");
    todo.push_back({v, piece.b, piece.tag});
    todo.push_back({piece.a, v, piece.tag});
  }
  if (stats) stats->steiner += steiner;
  return Status::success();
}

uint32_t label_faces(const Triangulation& m, std::vector<uint32_t>& face) {
  face.assign(m.num_slots(), kNone);
  uint32_t count = 0;
  std::vector<uint32_t> stack;
  for (uint32_t s = 0; s < m.num_slots(); ++s) {
    if (!m.alive(s) || face[s] != kNone) continue;
    face[s] = count;
    stack.push_back(s);
    while (!stack.empty()) {
      const uint32_t t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const uint32_t n = m.across(t, k);
        if (n == kNone || m.constrained(t, k) || face[n] != kNone) continue;
        face[n] = count;
        stack.push_back(n);
      }
    }
    ++count;
  }
  return count;
}

Status chain_vertices(const Triangulation& m, uint32_t from, uint32_t to, int32_t tag, std::vector<uint32_t>& out) {
  out.assign(1, from);
  std::vector<uint32_t> fan;
  uint32_t prev = kNone, cur = from;
  while (cur != to) {
    uint32_t next = kNone;
    m.star(cur, fan);
    for (uint32_t t : fan) {
      const int i = m.index_of(t, cur);
      // The two edges of t at cur: (cur, x) opposite y and (y, cur) opposite x.
      for (int e : {(i + 2) % 3, (i + 1) % 3}) {
        if (m.edge_tag(t, e) != tag) continue;
        const uint32_t other = m.edge_a(t, e) == cur ? m.edge_b(t, e) : m.edge_a(t, e);
        if (other != prev) next = other;
      }
    }
    if (next == kNone || out.size() > m.num_vertices())
      return Status(Error::RecoveryFailed, "the chain of tag " + std::to_string(tag) + " breaks at vertex " +
                                               std::to_string(cur));
    prev = cur;
    cur = next;
    out.push_back(cur);
  }
  return Status::success();
}

}  // namespace anitet::mesh2d
