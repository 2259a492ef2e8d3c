// After a layer: the new front vertices that carry a poor tet are moved further into the region
// when that improves their worst tet (height jumps between neighbours, pushes shrunk to fit and
// grazing stars are the usual causes).
//
// Why a move stays valid: moving v from p to p' is done only when (1) the cone of tets from p'
// over v's front star fits on the front now (the exact test of every push: the cone lies in the
// region and the front beyond it is a valid closed surface), and (2) every tet of v stays positive
// (exact) with v at p'. Then T1 plus the cone is valid, and collapsing the edge v p' onto p' (the
// cone's tets vanish, v's other tets take p' with a positive orientation) leaves a valid mesh
// whose inner boundary is the cone's outer boundary, already checked. The audit (layers_check)
// checks the result independently anyway.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/closest_point.hpp"
#include "layers/geometry.hpp"
#include "layers/layer_builder.hpp"
#include "predicates/predicates.hpp"

namespace anitet::layers {

namespace {

double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

double LayerBuilder::clear_distance(uint32_t v, const double at[3], double within, double stop_below) const {
  std::vector<uint32_t> ring;
  for (uint32_t f : front_.star(v)) ring.insert(ring.end(), front_.tri(f), front_.tri(f) + 3);
  std::sort(ring.begin(), ring.end());
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  const Box3 box = box_around(at, within);
  double best = within;
  front_.near(box, [&](uint32_t f) {
    const uint32_t* t = front_.tri(f);
    for (int k = 0; k < 3; ++k)
      if (std::binary_search(ring.begin(), ring.end(), t[k])) return true;
    best = std::min(best, point_triangle_distance(at, mesh_.point(t[0]), mesh_.point(t[1]),
                                                  mesh_.point(t[2])));
    return !(best < stop_below);
  });
  return best;
}

bool LayerBuilder::keeps_clear(uint32_t v, const double to[3], double gap) const {
  // The front beyond v's ring must stay `gap` away from v's new position: a move that brings
  // the front close to touching itself would leave the next layer no room there.
  return !(clear_distance(v, to, gap, gap) < gap);
}

double LayerBuilder::worst_tet_with(uint32_t v, const double* at, const std::vector<uint32_t>& tets,
                                    double stop_at, size_t* stopped_at) const {
  double worst = 1.0;
  for (size_t j = 0; j < tets.size(); ++j) {
    const uint32_t t = tets[j];
    const double* p[4];
    for (int i = 0; i < 4; ++i) {
      const uint32_t u = mesh_.vertex(t, i);
      p[i] = u == v ? at : mesh_.point(u);
    }
    const double e1[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const double e2[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const double e3[3] = {p[3][0] - p[0][0], p[3][1] - p[0][1], p[3][2] - p[0][2]};
    const double vol = e1[0] * (e2[1] * e3[2] - e2[2] * e3[1]) -
                       e1[1] * (e2[0] * e3[2] - e2[2] * e3[0]) +
                       e1[2] * (e2[0] * e3[1] - e2[1] * e3[0]);
    if (vol > 0.0) worst = std::min(worst, radius_ratio(p[0], p[1], p[2], p[3]));
    if (!(vol > 0.0) || worst <= stop_at) {
      if (stopped_at) *stopped_at = j;
      return vol > 0.0 ? worst : -1.0;
    }
  }
  if (stopped_at) *stopped_at = tets.size();
  return worst;
}

void LayerBuilder::compass_search(uint32_t v, const std::vector<uint32_t>& tets, double step, double stop,
                                  std::array<double, 3>& best, double& best_q) const {
  // The tet that stopped the last trial is measured first in the next: trials near each other
  // usually fail on the same tet. (A min does not depend on the order.)
  std::vector<uint32_t> order = tets;
  while (step > stop) {
    bool moved = false;
    for (int k = 0; k < 3; ++k)
      for (double sign : {-1.0, 1.0}) {
        std::array<double, 3> c = best;
        c[size_t(k)] += sign * step;
        size_t stopped = 0;
        const double q = worst_tet_with(v, c.data(), order, best_q + 1e-6, &stopped);
        if (stopped > 0 && stopped < order.size()) std::swap(order[0], order[stopped]);
        if (q > best_q + 1e-6) {
          best_q = q;
          best = c;
          moved = true;
        }
      }
    if (!moved) step *= 0.5;
  }
}

bool LayerBuilder::relocate_if_valid(uint32_t v, const double to[3],
                                     const std::vector<uint32_t>& tets) {
  for (uint32_t t : tets) {
    const double* p[4];
    for (int i = 0; i < 4; ++i) {
      const uint32_t u = mesh_.vertex(t, i);
      p[i] = u == v ? to : mesh_.point(u);
    }
    if (predicates::orient3d(p[0], p[1], p[2], p[3]) <= 0) return false;
  }
  const std::vector<uint32_t> star = front_.star(v);
  const double* pv = mesh_.point(v);
  const double d[3] = {to[0] - pv[0], to[1] - pv[1], to[2] - pv[2]};
  if (!cone_fits_near(v, star, d, 1.0)) return false;
  // Re-index v's front triangles around the new position (the octree holds their boxes).
  struct Saved {
    uint32_t a, b, c, owner;
  };
  std::vector<Saved> saved;
  for (uint32_t f : star) {
    const uint32_t* t = front_.tri(f);
    saved.push_back({t[0], t[1], t[2], front_.owner(f)});
  }
  for (uint32_t f : star) front_.remove(f);
  std::copy_n(to, 3, &mesh_.xyz[3 * size_t(v)]);
  for (const Saved& s : saved) front_.add(s.a, s.b, s.c, s.owner);
  return true;
}

bool LayerBuilder::candidate_moves(uint32_t v, const std::vector<uint32_t>& tets, double below,
                                   Improvement& out) const {
  out.ranked.clear();
  const std::vector<uint32_t>& star = front_.star(v);
  if (star.empty() || tets.empty()) return false;
  const double* p = mesh_.point(v);
  const double now = worst_tet_with(v, p, tets);
  if (now >= below) return false;
  // Candidates: along the direction that sees the star best, at fractions of the mean front
  // edge at v, and towards the mean of the front neighbours lifted by that edge.
  std::vector<double> normals, weights;
  star_normals(v, star, normals, weights);
  double d[3];
  bool improved = false;
  if (!(visible_direction(normals, weights, d, &improved) > 0.0)) return false;
  out_of_frame(v, d);
  double edge = 0.0, mean[3] = {0, 0, 0};
  size_t count = 0;
  for (uint32_t f : star) {
    const uint32_t* t = front_.tri(f);
    for (int k = 0; k < 3; ++k)
      if (t[k] == v) {
        const double* q = mesh_.point(t[(k + 1) % 3]);
        const double e[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
        edge += std::sqrt(dot3(e, e));
        for (int j = 0; j < 3; ++j) mean[j] += q[j];
        ++count;
      }
  }
  if (count == 0) return false;
  edge /= double(count);
  for (double& x : mean) x /= double(count);
  out.edge = edge;
  std::vector<std::array<double, 3>> candidates;
  // A cliff: v pushed much less than its neighbours (shrunk to fit): its own push line, at
  // fractions of their mean push height.
  const uint32_t o = out_.vertex_origin[v];
  double nb_height = 0.0;
  size_t nb_count = 0;
  for (uint32_t f : star) {
    const uint32_t* t = front_.tri(f);
    for (int k = 0; k < 3; ++k) {
      const uint32_t u = t[k];
      if (u == v || u >= out_.vertex_origin.size() || out_.vertex_origin[u] == TetMesh::kNone)
        continue;
      const double* q = mesh_.point(u);
      const double* qo = mesh_.point(out_.vertex_origin[u]);
      const double e[3] = {q[0] - qo[0], q[1] - qo[1], q[2] - qo[2]};
      nb_height += std::sqrt(dot3(e, e));
      ++nb_count;
    }
  }
  if (o != TetMesh::kNone && nb_count > 0) {
    const double* po = mesh_.point(o);
    double u[3] = {p[0] - po[0], p[1] - po[1], p[2] - po[2]};
    const double len = std::sqrt(dot3(u, u));
    nb_height /= double(nb_count);
    if (len > 0.0 && nb_height > len)
      for (double w : {0.25, 0.5, 0.75, 1.0}) {
        const double h = len + w * (nb_height - len);
        candidates.push_back({po[0] + h * u[0] / len, po[1] + h * u[1] / len, po[2] + h * u[2] / len});
      }
  }
  for (double s : {0.02, 0.05, 0.1, 0.2, 0.35, 0.5})
    candidates.push_back({p[0] + s * edge * d[0], p[1] + s * edge * d[1], p[2] + s * edge * d[2]});
  for (double s : {0.0, 0.1, 0.25}) {
    const double rel[3] = {mean[0] - p[0], mean[1] - p[1], mean[2] - p[2]};
    const double along = dot3(rel, d);
    for (double w : {0.5, 1.0})
      candidates.push_back({p[0] + w * (rel[0] - along * d[0]) + s * edge * d[0],
                            p[1] + w * (rel[1] - along * d[1]) + s * edge * d[1],
                            p[2] + w * (rel[2] - along * d[2]) + s * edge * d[2]});
  }
  // And a compass search on the worst tet from the best of them.
  {
    std::array<double, 3> best = {p[0], p[1], p[2]};
    double best_q = now;
    for (const auto& c : candidates) {
      const double q = worst_tet_with(v, c.data(), tets, best_q);
      if (q > best_q) {
        best_q = q;
        best = c;
      }
    }
    compass_search(v, tets, 0.1 * edge, 0.005 * edge, best, best_q);
    candidates.push_back(best);
  }
  // Best first; each candidate's worst tet computed once, not at every comparison. Only those
  // beating `now` by 0.01 are kept, so a candidate's scan stops at its first tet at or below
  // that bar (its value then sorts it among the ones dropped).
  const double bar = now + 0.01;
  out.ranked.reserve(candidates.size());
  for (const auto& c : candidates) out.ranked.push_back({worst_tet_with(v, c.data(), tets, bar), c});
  std::sort(out.ranked.begin(), out.ranked.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  while (!out.ranked.empty() && !(out.ranked.back().first > bar)) out.ranked.pop_back();
  return true;
}

void LayerBuilder::improve_layer(uint32_t first_new_vertex, double below) {
  if (opt_.improve_passes <= 0 || first_new_vertex >= mesh_.num_vertices()) return;
  const uint32_t n = uint32_t(mesh_.num_vertices()) - first_new_vertex;
  std::vector<std::vector<uint32_t>> tets(n);
  for (uint32_t t = 0; t < mesh_.num_tet_slots(); ++t) {
    if (out_.tet_layer[t] != layer_) continue;
    for (int i = 0; i < 4; ++i) {
      const uint32_t u = mesh_.vertex(t, i);
      if (u >= first_new_vertex) tets[u - first_new_vertex].push_back(t);
    }
  }
  // Each pass measures every vertex's candidate moves from the positions at its start, on both
  // cores (reads only: frame_of's cache, the one thing they would write, is filled first), then
  // moves the vertices one by one in order. A vertex next to one moved earlier in the pass (a
  // vertex of its tets or of its front star) is measured again at its turn: so every vertex
  // sees exactly what the one-by-one pass would, on any number of threads.
  if (!sizing_.isotropic())
    for (uint32_t i = 0; i < n; ++i) frame_of(first_new_vertex + i);
  std::vector<Improvement> planned(n);
  std::vector<uint8_t> wants(n), moved_now(n);
  auto moved_near = [&](uint32_t i) {
    auto moved = [&](uint32_t u) { return u >= first_new_vertex && moved_now[u - first_new_vertex]; };
    for (uint32_t t : tets[i])
      for (int k = 0; k < 4; ++k)
        if (moved(mesh_.vertex(t, k))) return true;
    for (uint32_t f : front_.star(first_new_vertex + i))
      for (int k = 0; k < 3; ++k)
        if (moved(front_.tri(f)[k])) return true;
    return false;
  };
  Improvement again;
  for (int pass = 0; pass < opt_.improve_passes; ++pass) {
    std::fill(moved_now.begin(), moved_now.end(), 0);
    for_each_index(n, [&](size_t i) {
      wants[i] = candidate_moves(first_new_vertex + uint32_t(i), tets[i], below, planned[i]);
    });
    size_t moved = 0;
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t v = first_new_vertex + i;
      const Improvement* e = &planned[i];
      if (moved > 0 && moved_near(i)) {
        if (!candidate_moves(v, tets[i], below, again)) continue;
        e = &again;
      } else if (!wants[i]) {
        continue;
      }
      if (e->ranked.empty()) continue;
      const double clear_now = clear_distance(v, mesh_.point(v), e->edge);
      for (const auto& [q, c] : e->ranked) {
        if (!keeps_clear(v, c.data(), std::min(0.5 * e->edge, 0.7 * clear_now))) continue;
        if (relocate_if_valid(v, c.data(), tets[i])) {
          ++moved;
          moved_now[i] = 1;
          ++out_.stats.improved_vertices;
          break;
        }
      }
    }
    if (moved == 0) break;
  }
}

void LayerBuilder::smooth_interior(int passes) {
  if (passes <= 0) return;
  const uint32_t nv = uint32_t(mesh_.num_vertices());
  std::vector<std::vector<uint32_t>> tets(nv);
  std::vector<uint8_t> movable(nv, 0);
  for (uint32_t v = uint32_t(s_.num_vertices()); v < nv; ++v) movable[v] = front_.star(v).empty();
  for (uint32_t t = 0; t < mesh_.num_tet_slots(); ++t) {
    const bool bl = t < mesh_.tet_region.size() && mesh_.tet_region[t] != 0;
    for (int i = 0; i < 4; ++i) {
      const uint32_t u = mesh_.vertex(t, i);
      tets[u].push_back(t);
      if (bl) movable[u] = 0;  // BL heights stay as built
    }
  }
  for (int pass = 0; pass < passes; ++pass) {
    size_t moved = 0;
    for (uint32_t v = 0; v < nv; ++v) {
      if (!movable[v] || tets[v].empty()) continue;
      const double* p = mesh_.point(v);
      double best_q = worst_tet_with(v, p, tets[v]);
      if (best_q >= opt_.improve_below) continue;
      // From the centroid of the star's other vertices (or v when that is worse), a compass
      // search on the worst tet, with steps from a tenth of the mean edge at v.
      std::array<double, 3> best = {p[0], p[1], p[2]}, mean = {0, 0, 0};
      double edge = 0.0;
      size_t count = 0;
      for (uint32_t t : tets[v])
        for (int i = 0; i < 4; ++i) {
          const uint32_t u = mesh_.vertex(t, i);
          if (u == v) continue;
          const double* q = mesh_.point(u);
          const double e[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
          edge += std::sqrt(dot3(e, e));
          for (int k = 0; k < 3; ++k) mean[size_t(k)] += q[k];
          ++count;
        }
      if (count == 0) continue;
      edge /= double(count);
      for (double& x : mean) x /= double(count);
      const double start_q = best_q;
      if (const double q = worst_tet_with(v, mean.data(), tets[v], best_q); q > best_q) {
        best_q = q;
        best = mean;
      }
      compass_search(v, tets[v], 0.1 * edge, 0.002 * edge, best, best_q);
      if (!(best_q > start_q + 1e-3)) continue;
      bool positive = true;
      for (size_t j = 0; j < tets[v].size() && positive; ++j) {
        const uint32_t t = tets[v][j];
        const double* q[4];
        for (int i = 0; i < 4; ++i) {
          const uint32_t u = mesh_.vertex(t, i);
          q[i] = u == v ? best.data() : mesh_.point(u);
        }
        positive = predicates::orient3d(q[0], q[1], q[2], q[3]) > 0;
      }
      if (!positive) continue;
      std::copy_n(best.data(), 3, &mesh_.xyz[3 * size_t(v)]);
      ++moved;
      ++out_.stats.smoothed_vertices;
    }
    if (moved == 0) break;
  }
}

}  // namespace anitet::layers
