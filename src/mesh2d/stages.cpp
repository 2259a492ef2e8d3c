#include "mesh2d/stages.hpp"

#include <algorithm>
#include <string>
#include <unordered_map>

#include "mesh2d/conforming.hpp"

namespace anitet::mesh2d {

void front_edges(const Pslg& p, const Domain& d, std::vector<uint32_t>& edges, std::vector<int32_t>& seg) {
  edges.clear();
  seg.clear();
  for (size_t s = 0; s < p.num_segments(); ++s) {
    const uint32_t a = p.seg[2 * s], b = p.seg[2 * s + 1];
    if (d.sides[s] & 1) edges.insert(edges.end(), {a, b}), seg.push_back(int32_t(s));
    if (d.sides[s] & 2) edges.insert(edges.end(), {b, a}), seg.push_back(int32_t(s));
  }
}

namespace {

// T2: the Delaunay triangulation of S1's points with S1 recovered (tags: S1 edge index), carved
// to the inside of S1 (the left of its edges). Vertices: xy's, 4 box corners, Steiner points.
// chains[g]: S1 edge g's pieces' vertices in order, found before the carving (S1 may touch
// itself at an input point, whose triangles then form two fans that star() cannot both see).
Result<Triangulation> stage2(const std::vector<double>& xy, const FrontResult& f, uint32_t& first_corner,
                             std::vector<std::vector<uint32_t>>& chains, StageStats* stats) {
  std::vector<uint32_t> points(f.s1);
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  Result<Triangulation> dt = delaunay_in_box(xy, points, &first_corner);
  if (!dt.ok()) return Status(dt.status().code(), "stage 2: " + dt.status().message());
  Triangulation& m = dt.value();
  const size_t n_s1 = f.s1.size() / 2;
  std::vector<int32_t> tags(n_s1);
  for (size_t i = 0; i < n_s1; ++i) tags[i] = int32_t(i);
  ConformingStats cs;
  if (Status s = recover_segments(m, f.s1, tags, &cs); !s.ok()) return Status(s.code(), "stage 2: " + s.message());
  if (stats) stats->steiner_on_s1 = cs.steiner;
  // Carve: flood from the triangles left of S1's pieces.
  std::vector<uint8_t> inside(m.num_slots(), 0);
  std::vector<uint32_t> stack;
  chains.assign(n_s1, {});
  for (size_t g = 0; g < n_s1; ++g) {
    std::vector<uint32_t>& chain = chains[g];
    if (Status s = chain_vertices(m, f.s1[2 * g], f.s1[2 * g + 1], int32_t(g), chain); !s.ok())
      return Status(s.code(), "stage 2: " + s.message());
    for (size_t i = 0; i + 1 < chain.size(); ++i) {
      uint32_t t;
      int k;
      if (!m.find_edge(chain[i], chain[i + 1], t, k)) return Status(Error::Internal, "stage 2: an S1 piece has no inner triangle");
      if (!inside[t]) inside[t] = 1, stack.push_back(t);
    }
  }
  while (!stack.empty()) {
    const uint32_t t = stack.back();
    stack.pop_back();
    for (int k = 0; k < 3; ++k) {
      const uint32_t n = m.across(t, k);
      if (n == kNone || m.constrained(t, k) || inside[n]) continue;
      inside[n] = 1;
      stack.push_back(n);
    }
  }
  for (uint32_t t = 0; t < m.num_slots(); ++t)
    if (m.alive(t) && !inside[t]) m.free_triangle(t);
  for (uint32_t t = 0; t < m.num_slots(); ++t)
    if (m.alive(t))
      for (int k = 0; k < 3; ++k)
        if (m.across(t, k) != kNone && !m.alive(m.across(t, k))) m.nbr[3 * size_t(t) + size_t(k)] = kNone;
  m.rebuild_vertex_triangles();
  for (uint32_t t = 0; t < m.num_slots(); ++t)
    if (m.alive(t))
      for (int k = 0; k < 3; ++k)
        if (m.v(t, k) >= first_corner && m.v(t, k) < first_corner + 4)
          return Status(Error::Internal, "stage 2: S1 does not enclose its inside (a box corner is inside)");
  return dt;
}

}  // namespace

Result<Triangulation> boundary_constrained_triangulation(const Pslg& pslg, const Domain& domain,
                                                         const FrontOptions& front_options, StageStats* stats) {
  StageStats local;
  StageStats& st = stats ? *stats : local;
  std::vector<uint32_t> edges;
  std::vector<int32_t> seg;
  front_edges(pslg, domain, edges, seg);
  std::vector<double> xy = pslg.xy;
  int32_t failed = kFree;
  Result<FrontResult> front = build_front(xy, edges, seg, front_options, &failed);
  if (!front.ok() && failed != kFree)
    return Status(Error::InvalidArgument, (pslg.name.empty() ? std::string() : pslg.name + ": ") + "no triangle fits beside " +
                                              describe_segment(pslg, size_t(failed)) +
                                              ": the domain there is narrower than about 1e-13 times its coordinates "
                                              "(the precision stage 1 needs)");
  if (!front.ok()) return front.status();
  const FrontResult& f = front.value();
  st.t1_triangles = f.tri.size() / 3;
  st.s1_edges = f.s1.size() / 2;
  st.halvings = f.halvings;
  st.closed = f.closed;

  uint32_t corner = 0;
  std::vector<std::vector<uint32_t>> chains;
  Result<Triangulation> t2 = stage2(xy, f, corner, chains, &st);
  if (!t2.ok()) return t2.status();
  Triangulation& m2 = t2.value();
  // Vertex ids: xy's as they are; T2's Steiner points (after the 4 corners) moved down by 4.
  auto id = [&](uint32_t v) { return v < corner ? v : v - 4; };
  std::vector<double> all = xy;
  all.insert(all.end(), m2.xy.begin() + 2 * (size_t(corner) + 4), m2.xy.end());
  std::vector<uint32_t> tri;
  for (uint32_t t = 0; t < m2.num_slots(); ++t)
    if (m2.alive(t)) {
      tri.insert(tri.end(), {id(m2.v(t, 0)), id(m2.v(t, 1)), id(m2.v(t, 2))});
      ++st.t2_triangles;
    }
  // Coupling: T1's triangle on each S1 edge becomes the fan over the edge's pieces from its
  // third vertex. A triangle with two split S1 edges is split twice: the second time, the fan
  // triangle that still holds that edge whole.
  std::vector<uint32_t> t1(f.tri);
  std::vector<uint8_t> t1_alive(t1.size() / 3, 1);
  std::unordered_map<uint64_t, uint32_t> holder;  // directed edge -> T1 triangle holding it
  auto key = [](uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | b; };
  auto hold = [&](uint32_t t) {
    for (int k = 0; k < 3; ++k) holder[key(t1[3 * size_t(t) + size_t(k)], t1[3 * size_t(t) + size_t((k + 1) % 3)])] = t;
  };
  for (uint32_t t = 0; t < t1_alive.size(); ++t) hold(t);
  for (size_t g = 0; g < f.s1.size() / 2; ++g) {
    const std::vector<uint32_t>& chain = chains[g];
    if (chain.size() == 2) continue;
    const auto it = holder.find(key(f.s1[2 * g + 1], f.s1[2 * g]));
    if (it == holder.end() || !t1_alive[it->second])
      return Status(Error::Internal, "coupling: S1 edge " + std::to_string(g) + " is no T1 triangle's edge");
    const uint32_t t = it->second;
    t1_alive[t] = 0;
    ++st.coupled;
    uint32_t v = kNone;
    for (int k = 0; k < 3; ++k)
      if (t1[3 * size_t(t) + size_t(k)] != f.s1[2 * g] && t1[3 * size_t(t) + size_t(k)] != f.s1[2 * g + 1])
        v = t1[3 * size_t(t) + size_t(k)];
    for (size_t i = 0; i + 1 < chain.size(); ++i) {
      t1.insert(t1.end(), {id(chain[i + 1]), id(chain[i]), v});
      t1_alive.push_back(1);
      hold(uint32_t(t1_alive.size() - 1));
    }
  }
  std::vector<uint32_t> seg_edges;
  std::vector<int32_t> seg_tags;
  for (size_t t = 0; t < f.tri.size() / 3; ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t g = f.tri_tag[3 * t + size_t(k)];
      if (g < 0) continue;
      seg_edges.insert(seg_edges.end(), {f.tri[3 * t + size_t((k + 1) % 3)], f.tri[3 * t + size_t((k + 2) % 3)]});
      seg_tags.push_back(g);
    }
  for (size_t t = 0; t < t1_alive.size(); ++t)
    if (t1_alive[t]) tri.insert(tri.end(), t1.begin() + 3 * long(t), t1.begin() + 3 * long(t) + 3);
  Result<Triangulation> merged = build_triangulation(std::move(all), std::move(tri), seg_edges, seg_tags);
  if (!merged.ok()) return Status(merged.status().code(), "coupling: " + merged.status().message());
  // The input's points on no segment: inserted, Euclidean.
  Triangulation& m = merged.value();
  Kernel kernel(m);
  for (uint32_t v : domain.free_points) {
    uint32_t start = 0;
    while (start < m.num_slots() && !m.alive(start)) ++start;
    Location loc = kernel.locate(m.point(v), start);
    if (loc.kind == Location::Outside) {
      // The domain is not convex: a walk may leave it; look at every triangle instead.
      loc.t = kNone;
      for (uint32_t t = 0; t < m.num_slots() && loc.t == kNone; ++t)
        if (m.alive(t)) {
          const Location l = kernel.locate(m.point(v), t);
          if (l.kind != Location::Outside) loc = l;
        }
    }
    if (kernel.insert_vertex(v, loc) == kNone)
      return Status(Error::InvalidArgument, "point " + std::to_string(v + 1) + " (on no segment) could not be inserted");
    ++st.free_points;
  }
  return merged;
}

}  // namespace anitet::mesh2d
