#include "mesh2d/front.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "mesh2d/metric2.hpp"
#include "mesh2d/segment_grid.hpp"
#include "mesh2d/segments2.hpp"
#include "mesh2d/triangulation.hpp"
#include "predicates/predicates.hpp"

namespace anitet::mesh2d {

using predicates::orient2d;

bool in_sector(const double* o, const double* p1, const double* p2, const double* q) {
  const int s = orient2d(o, p1, p2);
  const int a1 = orient2d(o, p1, q), a2 = orient2d(o, q, p2);
  if (s > 0) return a1 > 0 && a2 > 0;
  if (s < 0) return a1 > 0 || a2 > 0;
  // p1, p2 on one line through o: opposite rays (a half-plane) or one ray (all but the ray).
  const int k = p1[0] != o[0] ? 0 : 1;
  const bool same = (p1[k] > o[k]) == (p2[k] > o[k]);
  if (!same) return a1 > 0;
  if (a1 != 0) return true;
  return (q[k] > o[k]) != (p1[k] > o[k]);
}

namespace {

double point_segment_distance(const double* r, const double* s, const double* t) {
  const double ex = t[0] - s[0], ey = t[1] - s[1];
  const double l2 = ex * ex + ey * ey;
  const double f = l2 > 0 ? std::clamp(((r[0] - s[0]) * ex + (r[1] - s[1]) * ey) / l2, 0.0, 1.0) : 0.0;
  return std::hypot(s[0] + f * ex - r[0], s[1] + f * ey - r[1]);
}

class Front {
 public:
  Front(std::vector<double>& xy, const FrontOptions& options) : xy_(xy), options_(options), grid_(make_grid(xy)) {}

  struct Edge {
    uint32_t a, b;
    int32_t seg;
    uint32_t tri;  // the triangle on its right (kNone for input edges)
    bool alive;
  };

  uint32_t add_edge(uint32_t a, uint32_t b, int32_t seg, uint32_t tri) {
    const uint32_t id = uint32_t(edges_.size());
    edges_.push_back({a, b, seg, tri, true});
    at_vertex(a).push_back(id);
    at_vertex(b).push_back(id);
    grid_.insert(id, p(a), p(b));
    return id;
  }

  void remove_edge(uint32_t e) {
    Edge& ed = edges_[e];
    ed.alive = false;
    grid_.remove(e);
    for (uint32_t v : {ed.a, ed.b}) {
      std::vector<uint32_t>& list = at_vertex(v);
      list.erase(std::remove(list.begin(), list.end(), e), list.end());
    }
  }

  // The live edge from a to b, kNone if none.
  uint32_t find(uint32_t a, uint32_t b) {
    for (uint32_t e : at_vertex(a))
      if (edges_[e].a == a && edges_[e].b == b) return e;
    return kNone;
  }

  // The incoming edge of e's corner at its start: the one the sector from a->b counter-clockwise
  // reaches first.
  uint32_t prev(uint32_t e) {
    const Edge& ed = edges_[e];
    return first_incoming_ccw(ed.a, ed.b, e);
  }
  // The outgoing edge of e's corner at its end: the one reached first going clockwise from b->a.
  uint32_t next(uint32_t e) {
    const Edge& ed = edges_[e];
    uint32_t best = kNone;
    double best_angle = 10.0;
    const double base = angle(ed.b, ed.a);
    for (uint32_t f : at_vertex(ed.b)) {
      if (f == e || edges_[f].a != ed.b) continue;
      double d = base - angle(ed.b, edges_[f].b);
      while (d <= 0) d += 2 * M_PI;
      if (d < best_angle) best_angle = d, best = f;
    }
    return best;
  }

  // Builds the triangle of the live edge e; false if none could be placed.
  bool advance(uint32_t e, FrontResult& out) {
    const Edge ed = edges_[e];
    const uint32_t ep = prev(e), en = next(e);
    if (ep == kNone || en == kNone) return false;
    // First an apex clear of the front by 1e-9 of the new edges' lengths: a front point closer
    // to a new edge costs stage 2's recovery splits down to that distance, and rounding may put
    // the point across the edge's pieces. Where the domain is thinner than that, any apex the
    // exact tests accept (the lemma's).
    uint32_t q = kNone;
    bool closed = false;
    for (double clearance : {1e-9, 0.0})
      if ((q = choose_apex(e, ep, en, clearance, closed, out)) != kNone) break;
    if (q == kNone) return false;
    if (closed) ++out.closed;
    // The triangle (a, b, q): edge 2 is ab, edge 1 is qa, edge 0 is bq.
    const uint32_t t = uint32_t(out.tri.size() / 3);
    out.tri.insert(out.tri.end(), {ed.a, ed.b, q});
    out.tri_tag.insert(out.tri_tag.end(), {kFree, kFree, ed.seg});
    remove_edge(e);
    connect(ed.a, q, t, 1, out);
    connect(q, ed.b, t, 0, out);
    return true;
  }

  const std::vector<Edge>& edges() const { return edges_; }

 private:
  // The apex of e's triangle: a neighbouring front vertex closing a sharp corner well (closed
  // = true), else a new point on e's inward normal, its height halved until valid; kNone if none.
  uint32_t choose_apex(uint32_t e, uint32_t ep, uint32_t en, double clearance, bool& closed, FrontResult& out) {
    const Edge& ed = edges_[e];
    const uint32_t u = edges_[ep].a, w = edges_[en].b;
    uint32_t q = kNone;
    double best = -1.0;
    const double close = options_.close_angle_deg * M_PI / 180.0;
    for (uint32_t cand : {u, w}) {
      const bool at_a = cand == u;
      const double corner = at_a ? corner_angle(ed.a, ed.b, u) : corner_angle(ed.b, w, ed.a);
      if (u != w && corner >= close) continue;
      if (!valid(e, ep, en, cand, clearance)) continue;
      const double quality = min_angle(p(ed.a), p(ed.b), p(cand));
      if (quality > best) best = quality, q = cand;
    }
    closed = q != kNone;
    if (closed) return q;
    double height = apex_height(ed.a, ed.b);
    const double* a = p(ed.a);
    const double* b = p(ed.b);
    const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
    const double nx = -(b[1] - a[1]) / len, ny = (b[0] - a[0]) / len;
    const double mx = 0.5 * (a[0] + b[0]), my = 0.5 * (a[1] + b[1]);
    // Halved until valid, or until the apex rounds onto the midpoint (a needle's tip may need
    // hundreds of halvings).
    for (; mx + height * nx != mx || my + height * ny != my; height *= 0.5, ++out.halvings) {
      xy_.push_back(mx + height * nx);
      xy_.push_back(my + height * ny);
      const uint32_t cand = uint32_t(xy_.size() / 2 - 1);
      if (valid(e, ep, en, cand, clearance)) return cand;
      xy_.resize(xy_.size() - 2);
    }
    return kNone;
  }

  static SegmentGrid make_grid(const std::vector<double>& xy) {
    double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    double hi[2] = {-lo[0], -lo[1]};
    for (size_t i = 0; i < xy.size(); ++i) {
      lo[i % 2] = std::min(lo[i % 2], xy[i]);
      hi[i % 2] = std::max(hi[i % 2], xy[i]);
    }
    if (xy.empty()) lo[0] = lo[1] = hi[0] = hi[1] = 0;
    return SegmentGrid(lo, hi, xy.size() / 2);
  }

  const double* p(uint32_t v) const { return &xy_[2 * size_t(v)]; }
  std::vector<uint32_t>& at_vertex(uint32_t v) {
    if (v >= by_vertex_.size()) by_vertex_.resize(size_t(v) + 1);
    return by_vertex_[v];
  }
  double angle(uint32_t o, uint32_t x) const { return std::atan2(p(x)[1] - p(o)[1], p(x)[0] - p(o)[0]); }
  // The angle swept counter-clockwise from o->x to o->y, in (0, 2 pi].
  double corner_angle(uint32_t o, uint32_t x, uint32_t y) const {
    double d = angle(o, y) - angle(o, x);
    while (d <= 0) d += 2 * M_PI;
    return d;
  }

  // The incoming edge at o (other than skip) reached first going counter-clockwise from o->x.
  uint32_t first_incoming_ccw(uint32_t o, uint32_t x, uint32_t skip) {
    uint32_t best = kNone;
    double best_angle = 10.0;
    for (uint32_t f : at_vertex(o)) {
      if (f == skip || edges_[f].b != o) continue;
      const double d = corner_angle(o, x, edges_[f].a);
      if (d < best_angle) best_angle = d, best = f;
    }
    return best;
  }

  // The equilateral apex height over ab in the field's metric at ab's midpoint.
  double apex_height(uint32_t ia, uint32_t ib) const {
    const double* a = p(ia);
    const double* b = p(ib);
    const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
    if (!options_.field) return 0.5 * std::sqrt(3.0) * len;
    const double mid[3] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.0};
    double m[6];
    options_.field->metric(mid, m);
    const double e[3] = {b[0] - a[0], b[1] - a[1], 0.0};
    const double n[3] = {-e[1] / len, e[0] / len, 0.0};
    const double h = 0.5 * std::sqrt(3.0) * metric_norm(m, e) / metric_norm(m, n);
    return std::isfinite(h) && h > 0 ? h : 0.5 * std::sqrt(3.0) * len;
  }

  // The front after the triangle t: its edge k joins x to y (x->y with t on the right). An
  // edge y->x on the front is consumed (its segment tags t's edge), else x->y joins the front.
  void connect(uint32_t x, uint32_t y, uint32_t t, int k, FrontResult& out) {
    const uint32_t twin = find(y, x);
    if (twin != kNone) {
      out.tri_tag[3 * size_t(t) + size_t(k)] = edges_[twin].seg;
      remove_edge(twin);
      return;
    }
    add_edge(x, y, kFree, t);
  }

  // Whether the triangle (a, b, q) on e = a->b, with ep = u->a and en = b->w its corners'
  // other edges, lies in the unmeshed region: positive, inside both corners (and q's), its
  // new edges meeting no front edge, no front vertex inside.
  bool valid(uint32_t e, uint32_t ep, uint32_t en, uint32_t q, double clearance_factor) {
    const uint32_t a = edges_[e].a, b = edges_[e].b, u = edges_[ep].a, w = edges_[en].b;
    if (q == a || q == b) return false;
    if (orient2d(p(a), p(b), p(q)) <= 0) return false;
    if (q != u && !in_sector(p(a), p(b), p(u), p(q))) return false;
    if (q != w && !in_sector(p(b), p(w), p(a), p(q))) return false;
    if (q == u && u != w) {
      const uint32_t ep2 = prev(ep);
      if (ep2 == kNone || !in_sector(p(u), p(a), p(edges_[ep2].a), p(b))) return false;
    }
    if (q == w && u != w) {
      const uint32_t en2 = next(en);
      if (en2 == kNone || !in_sector(p(w), p(edges_[en2].b), p(b), p(a))) return false;
    }
    // Clearance: a point within it of an edge lets stage 2's rounded midpoints, or the coupling's
    // fans, put it on the wrong side: at least 256 roundings of the coordinates here.
    double magnitude = 0;
    for (uint32_t v : {a, b, q}) magnitude = std::max({magnitude, std::abs(p(v)[0]), std::abs(p(v)[1])});
    const double clearance =
        std::max(clearance_factor * std::max(std::hypot(p(q)[0] - p(a)[0], p(q)[1] - p(a)[1]),
                                             std::hypot(p(q)[0] - p(b)[0], p(q)[1] - p(b)[1])),
                 256 * std::numeric_limits<double>::epsilon() * magnitude);
    // ... between the triangle's own vertices and edges too (a flat triangle).
    if (point_segment_distance(p(q), p(a), p(b)) < clearance || point_segment_distance(p(a), p(q), p(b)) < clearance ||
        point_segment_distance(p(b), p(a), p(q)) < clearance)
      return false;
    const double lo[2] = {std::min({p(a)[0], p(b)[0], p(q)[0]}) - clearance, std::min({p(a)[1], p(b)[1], p(q)[1]}) - clearance};
    const double hi[2] = {std::max({p(a)[0], p(b)[0], p(q)[0]}) + clearance, std::max({p(a)[1], p(b)[1], p(q)[1]}) + clearance};
    return grid_.for_each_in_box(lo, hi, [&](uint32_t f) {
      if (f == e) return true;
      const uint32_t fa = edges_[f].a, fb = edges_[f].b;
      for (const auto& [s, t] : {std::pair{a, q}, std::pair{q, b}}) {
        if ((s == u && t == a) || (s == a && t == u) || (s == b && t == w) || (s == w && t == b)) continue;
        if ((fa == s && fb == t) || (fa == t && fb == s)) continue;  // that edge itself (consumed)
        const bool shared = fa == s || fa == t || fb == s || fb == t;
        if (shared) {
          const uint32_t o = (fa == s || fa == t) ? fa : fb;
          const uint32_t other = o == s ? t : s;
          const uint32_t f_other = o == fa ? fb : fa;
          if (overlap_from(p(o), p(other), p(f_other))) return false;
        } else if (segments_meet(p(s), p(t), p(fa), p(fb))) {
          return false;
        }
      }
      for (uint32_t r : {fa, fb}) {
        if (r == a || r == b || r == q) continue;
        if (orient2d(p(a), p(b), p(r)) > 0 && orient2d(p(b), p(q), p(r)) > 0 && orient2d(p(q), p(a), p(r)) > 0) return false;
        for (const auto& [s, t] : {std::pair{a, q}, std::pair{q, b}})
          if (point_segment_distance(p(r), p(s), p(t)) < clearance) return false;
      }
      if (q != fa && q != fb && point_segment_distance(p(q), p(fa), p(fb)) < clearance) return false;
      return true;
    });
  }

  std::vector<double>& xy_;
  const FrontOptions& options_;
  SegmentGrid grid_;
  std::vector<Edge> edges_;
  std::vector<std::vector<uint32_t>> by_vertex_;
};

}  // namespace

Result<FrontResult> build_front(std::vector<double>& xy, const std::vector<uint32_t>& edges,
                                const std::vector<int32_t>& edge_seg, const FrontOptions& options,
                                int32_t* failed_segment) {
  FrontResult out;
  Front front(xy, options);
  for (size_t i = 0; i < edges.size() / 2; ++i) front.add_edge(edges[2 * i], edges[2 * i + 1], edge_seg[i], kNone);
  for (int layer = 0; layer < std::max(options.layers, 1); ++layer) {
    std::vector<uint32_t> todo;
    for (uint32_t e = 0; e < front.edges().size(); ++e)
      if (front.edges()[e].alive) todo.push_back(e);
    for (uint32_t e : todo) {
      if (!front.edges()[e].alive) continue;  // consumed by a closed corner
      if (!front.advance(e, out)) {
        if (failed_segment) *failed_segment = front.edges()[e].seg;
        return Status(Error::Internal, "stage 1: no triangle could be placed on the front edge " +
                                           std::to_string(front.edges()[e].a) + "-" + std::to_string(front.edges()[e].b));
      }
    }
  }
  for (const Front::Edge& e : front.edges()) {
    if (!e.alive) continue;
    out.s1.push_back(e.a);
    out.s1.push_back(e.b);
    out.s1_tri.push_back(e.tri);
  }
  return out;
}

}  // namespace anitet::mesh2d
