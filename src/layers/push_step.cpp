// The push step of stage 1 (see layers.hpp): every vertex of the layer's starting front leaves
// the front, replaced by a new point joined to its star.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include <tbb/parallel_invoke.h>

#include "layers/geometry.hpp"
#include "layers/layer_builder.hpp"
#include "predicates/predicates.hpp"

namespace anitet::layers {

namespace {

double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

double signed_volume(const double* a, const double* b, const double* c, const double* d) {
  const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double e3[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return e1[0] * (e2[1] * e3[2] - e2[2] * e3[1]) - e1[1] * (e2[0] * e3[2] - e2[2] * e3[0]) +
         e1[2] * (e2[0] * e3[1] - e2[1] * e3[0]);
}

}  // namespace

const double* LayerBuilder::frame_of(uint32_t a) const {
  if (sizing_.isotropic()) return nullptr;  // (the pipeline's default: no query per vertex)
  if (frame_state_.size() <= a) {
    frame_state_.resize(size_t(a) + 1, 0);
    frame_.resize(size_t(a) + 1);
  }
  if (frame_state_[a] == 0) {
    double m[6];
    sizing_.metric(mesh_.point(a), m);
    frame_state_[a] = metric_is_isotropic(m) ? 1 : 2;
    if (frame_state_[a] == 2) metric_factor(m, frame_[a].data());
  }
  return frame_state_[a] == 2 ? frame_[a].data() : nullptr;
}

std::array<double, 3> LayerBuilder::into_frame(uint32_t a, const double d[3]) const {
  std::array<double, 3> out = {d[0], d[1], d[2]};
  const double* u = frame_of(a);
  if (!u) return out;
  apply_factor(u, d, out.data());
  const double len = std::sqrt(dot3(out.data(), out.data()));
  if (len > 0.0)
    for (double& x : out) x /= len;
  return out;
}

void LayerBuilder::out_of_frame(uint32_t a, double d[3]) const {
  const double* u = frame_of(a);
  if (!u) return;
  const double dm[3] = {d[0], d[1], d[2]};
  solve_factor(u, dm, d);
  const double len = std::sqrt(dot3(d, d));
  if (len > 0.0)
    for (int k = 0; k < 3; ++k) d[k] /= len;
}

void LayerBuilder::frame_normal(uint32_t a, const double* p0, const double* p1, const double* p2,
                                double n[3]) const {
  const double* u = frame_of(a);
  if (!u) {
    unit_normal(p0, p1, p2, n);
    return;
  }
  double q[3][3];
  apply_factor(u, p0, q[0]);
  apply_factor(u, p1, q[1]);
  apply_factor(u, p2, q[2]);
  unit_normal(q[0], q[1], q[2], n);
}

void LayerBuilder::star_normals(uint32_t a, const std::vector<uint32_t>& star,
                                std::vector<double>& normals, std::vector<double>& weights) const {
  star_normals(a, star, normals, &weights);
}

void LayerBuilder::star_normals(uint32_t a, const std::vector<uint32_t>& star,
                                std::vector<double>& normals) const {
  star_normals(a, star, normals, nullptr);
}

void LayerBuilder::star_normals(uint32_t a, const std::vector<uint32_t>& star,
                                std::vector<double>& normals, std::vector<double>* weights) const {
  normals.assign(3 * star.size(), 0.0);
  if (weights) weights->assign(star.size(), 0.0);
  const double* u = frame_of(a);
  double q[3][3];
  for (size_t i = 0; i < star.size(); ++i) {
    const uint32_t* t = front_.tri(star[i]);
    int k = 0;
    while (t[k] != a) ++k;
    const double* p[3] = {mesh_.point(a), mesh_.point(t[(k + 1) % 3]), mesh_.point(t[(k + 2) % 3])};
    if (u)
      for (int j = 0; j < 3; ++j) {
        apply_factor(u, p[j], q[j]);
        p[j] = q[j];
      }
    unit_normal(p[0], p[1], p[2], &normals[3 * i]);
    for (int j = 0; j < 3; ++j) normals[3 * i + j] = -normals[3 * i + j];
    if (weights) (*weights)[i] = corner_angle(p[0], p[1], p[2]);
  }
}

double LayerBuilder::clearance(const double p[3], const double d[3], double max_dist,
                               const std::vector<uint32_t>& skip) const {
  Box3 box;
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = std::min(p[k], p[k] + max_dist * d[k]);
    box.hi[k] = std::max(p[k], p[k] + max_dist * d[k]);
  }
  double best = std::numeric_limits<double>::infinity();
  front_.near(box, [&](uint32_t f) {
    const uint32_t* t = front_.tri(f);
    for (int k = 0; k < 3; ++k)
      if (std::find(skip.begin(), skip.end(), t[k]) != skip.end()) return true;
    best = std::min(best, ray_triangle(p, d, mesh_.point(t[0]), mesh_.point(t[1]),
                                       mesh_.point(t[2])));
    return true;
  });
  return best;
}

bool LayerBuilder::keeps_plans_visible(int halvings) {
  // After a few halvings only plain visibility is required, so that a neighbour whose margin
  // is exactly at its limit cannot stall the push.
  constexpr int kStrictHalvings = 12;
  replans_.clear();
  std::vector<double> normals, weights;
  for (uint32_t f : added_) {
    if (!front_.alive(f)) continue;  // closed again within the push
    const uint32_t* t = front_.tri(f);
    for (int k = 0; k < 3; ++k) {
      const uint32_t u = t[k];
      if (u >= plan_.size() || !plan_[u].valid || !plan_[u].waiting) continue;
      const Plan& p = plan_[u];
      const double need = halvings < kStrictHalvings ? p.keep : 0.0;
      star_normals(u, front_.star(u), normals);
      if (star_margin(normals, into_frame(u, p.d).data()) > need) continue;
      // The planned direction no longer sees u's new star well: look for another that does.
      star_normals(u, front_.star(u), normals, weights);
      Replan r;
      r.v = u;
      bool improved = false;
      if (!(visible_direction(normals, weights, r.d, &improved) > need)) return false;
      out_of_frame(u, r.d);
      replans_.push_back(r);
    }
  }
  return true;
}

double LayerBuilder::sized_height(uint32_t a, const double d[3]) const {
  if (bl_index_ >= 0) return bl_nominal();
  double m[6];
  sizing_.metric(mesh_.point(a), m);
  return opt_.push_height / std::max(metric_norm(m, d), 1e-300);
}

double LayerBuilder::target_height(uint32_t a, const double d[3]) const {
  if (bl_index_ >= 0) return bl_height(a, d);
  const double target = sized_height(a, d);
  // Share the free distance along d with the front across: both sides still have `remaining`
  // layers to build (this one included) and the region left inside needs room too, so a layer
  // takes at most 1 / (2 remaining + 1) of it. Thin parts get thinner layers from the first one
  // on, instead of a last layer squeezed flat.
  const double share = 1.0 / (2.0 * remaining_layers_ + 1.0);
  // The front across, not the walls of a local dent: triangles touching a's neighbours are
  // skipped (the exact test keeps the push off them).
  std::vector<uint32_t> ring;
  for (uint32_t f : front_.star(a)) ring.insert(ring.end(), front_.tri(f), front_.tri(f) + 3);
  std::sort(ring.begin(), ring.end());
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  return std::min(target, share * clearance(mesh_.point(a), d, target / share, ring));
}

Status LayerBuilder::push_step(const std::vector<uint32_t>& layer_vertices) {
  // A BL layer's junction vertices first: they go to their columns' fixed points, and the
  // others plan on the front they leave.
  std::vector<uint32_t> vertices = layer_vertices;
  if (bl_index_ >= 0) push_junctions(vertices);
  plan_.assign(mesh_.num_vertices(), Plan());
  touched_plans_.clear();
  // The plans read the front only, each vertex's its own: on both cores. (frame_of's cache is
  // filled first: it is the one thing they would write.)
  if (!sizing_.isotropic())
    for (uint32_t v : vertices) frame_of(v);
  for_each_index(vertices.size(), [&](size_t i) {
    const uint32_t v = vertices[i];
    std::vector<double> normals, weights;
    star_normals(v, front_.star(v), normals, weights);
    Plan& p = plan_[v];
    bool improved = false;
    const double margin = visible_direction(normals, weights, p.d, &improved);
    out_of_frame(v, p.d);
    p.valid = margin > 0.0;
    p.waiting = true;
    if (p.valid) {
      p.height = target_height(v, p.d);
      p.size = sized_height(v, p.d);
    }
  });
  std::vector<uint32_t> order, deferred;
  for (uint32_t v : vertices) (plan_[v].valid ? order : deferred).push_back(v);
  if (bl_index_ >= 0)
    plan_boundary_layer(vertices);
  else
    plan_targets(vertices);
  for_each_index(order.size(), [&](size_t i) {
    const uint32_t v = order[i];
    Plan& p = plan_[v];
    std::vector<double> normals;
    star_normals(v, front_.star(v), normals);
    p.keep = opt_.keep_margin * std::min(star_margin(normals, into_frame(v, p.d).data()), 0.5);
  });
  out_.stats.deferred_pushes += deferred.size();
  // Ordinary layers of a large front: most planned pushes on two cores.
  // (Not BL layers, nor after them: the wall flags and BL records are not merged.)
  if (bl_index_ < 0 && wall_.empty() && opt_.push_tasks_min_vertices > 0 &&
      order.size() >= opt_.push_tasks_min_vertices) {
    Result<std::vector<uint32_t>> rest = push_sides(order);
    if (!rest.ok()) return rest.status();
    order = std::move(rest).value();
  }
  order.insert(order.end(), deferred.begin(), deferred.end());
  for (uint32_t v : order)
    if (Status st = push_one(v); !st.ok()) return st;
  return Status::success();
}

Status LayerBuilder::push_one(uint32_t v) {
  // A BL height cut to a sliver of h0 r^i (fronts colliding) stops the vertex for this layer
  // (BoundaryLayerOptions::min_height_ratio), like a vertex no push can take off.
  if (bl_index_ >= 0 && v >= s_.num_vertices() && plan_[v].valid &&
      plan_[v].height < opt_.boundary_layer.min_height_ratio * bl_nominal()) {
    plan_[v].waiting = false;
    ++out_.stats.stopped_vertices;
    mark_bl_reduced(v);
    return Status::success();
  }
  Status st = push_vertex(v, layer_);
  if (st.ok()) return st;
  // An input vertex must leave the front (S hidden). A later front vertex whose star no push
  // can take off stays on the front for this layer: its neighbours' tets join it, every tet
  // already built was checked, so the front stays valid. Reported (BL: as reduced).
  if (v < s_.num_vertices()) return st;
  ++out_.stats.stopped_vertices;
  if (bl_index_ >= 0) mark_bl_reduced(v);
  return Status::success();
}

std::vector<std::pair<uint32_t, uint32_t>> LayerBuilder::planned_edges(
    const std::vector<uint32_t>& vertices) const {
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  for (uint32_t v : vertices) {
    if (!plan_[v].valid) continue;
    for (uint32_t f : front_.star(v)) {
      const uint32_t* t = front_.tri(f);
      for (int k = 0; k < 3; ++k)
        if (t[k] == v && t[(k + 1) % 3] > v && plan_[t[(k + 1) % 3]].valid)
          edges.emplace_back(v, t[(k + 1) % 3]);
    }
  }
  return edges;
}

void LayerBuilder::plan_targets(const std::vector<uint32_t>& vertices) {
  // The layer's front edges between planned vertices.
  const std::vector<std::pair<uint32_t, uint32_t>> edges = planned_edges(vertices);
  limit_gradation(edges, opt_.height_gradation, opt_.gradation_rings);
  // Tangential smoothing of the target points v + height d over the edge graph: evens out the
  // next front's triangles. A smoothed target is kept only if it still sees v's whole star.
  const size_t n = plan_.size();
  std::vector<double> target(3 * n, 0.0), sum(3 * n, 0.0);
  std::vector<uint32_t> count(n, 0);
  for (uint32_t v : vertices)
    if (plan_[v].valid)
      for (int k = 0; k < 3; ++k) target[3 * v + k] = mesh_.point(v)[k] + plan_[v].height * plan_[v].d[k];
  std::vector<double> normals, weights;
  for (int it = 0; it < opt_.smoothing_passes; ++it) {
    std::fill(sum.begin(), sum.end(), 0.0);
    std::fill(count.begin(), count.end(), 0u);
    for (const auto& [u, v] : edges)
      for (int k = 0; k < 3; ++k) {
        sum[3 * u + k] += target[3 * v + k];
        sum[3 * v + k] += target[3 * u + k];
      }
    for (const auto& [u, v] : edges) ++count[u], ++count[v];
    for (uint32_t v : vertices) {
      if (!plan_[v].valid || count[v] == 0) continue;
      const double* d = plan_[v].d;
      double move[3], along = 0.0;
      for (int k = 0; k < 3; ++k) {
        move[k] = 0.5 * (sum[3 * v + k] / count[v] - target[3 * v + k]);
        along += move[k] * d[k];
      }
      double next[3], disp[3];
      for (int k = 0; k < 3; ++k) {
        next[k] = target[3 * v + k] + move[k] - along * d[k];
        disp[k] = next[k] - mesh_.point(v)[k];
      }
      const double len = std::sqrt(dot3(disp, disp));
      if (!(len > 0.0)) continue;
      const double dir[3] = {disp[0] / len, disp[1] / len, disp[2] / len};
      star_normals(v, front_.star(v), normals);
      if (star_margin(normals, into_frame(v, dir).data()) < 0.5 * star_margin(normals, into_frame(v, d).data()))
        continue;
      std::copy_n(next, 3, &target[3 * v]);
    }
  }
  for (uint32_t v : vertices) {
    if (!plan_[v].valid) continue;
    double disp[3];
    for (int k = 0; k < 3; ++k) disp[k] = target[3 * v + k] - mesh_.point(v)[k];
    const double len = std::sqrt(dot3(disp, disp));
    if (!(len > 0.0)) continue;
    for (int k = 0; k < 3; ++k) plan_[v].d[k] = disp[k] / len;
    plan_[v].height = len;
  }
}

void LayerBuilder::limit_gradation(const std::vector<std::pair<uint32_t, uint32_t>>& edges,
                                   double g, int rings) {
  // Heights only go down: h_u <= g h_v across the edges, propagated `rings` edges away from a
  // low vertex, so that a neighbour capped by the front across or by a dent does not leave a
  // cliff in the next front (the flattest prism tets). Not further: one vertex capped very low
  // (a fold of the front just beside it) would otherwise flatten a whole region.
  if (!(g > 1.0) || edges.empty()) return;
  std::vector<double> next(plan_.size());
  for (int pass = 0; pass < rings; ++pass) {
    for (size_t v = 0; v < plan_.size(); ++v) next[v] = plan_[v].height;
    // A vertex capped far below its own size (a fold of the front right beside it) is a
    // local defect: it limits its neighbours only down to a quarter of its size.
    auto source = [&](uint32_t v) { return std::max(plan_[v].height, 0.25 * plan_[v].size); };
    for (const auto& [u, v] : edges) {
      next[u] = std::min(next[u], g * source(v));
      next[v] = std::min(next[v], g * source(u));
    }
    for (size_t v = 0; v < plan_.size(); ++v) plan_[v].height = next[v];
  }
}

bool LayerBuilder::join_to_front(const std::vector<uint32_t>& part, uint32_t apex) {
  front_.begin();
  added_.clear();
  // One octree query for the whole cone: its tets lie in the box of the part's triangles (the
  // front keeps each one's box) and the apex. Each tet then scans that list and the triangles the
  // cone's earlier tets added (a query per tet walked the octree's nodes again, cache misses
  // mostly).
  Box3 cone = box_around(mesh_.point(apex), 0.0);
  for (uint32_t f : part)
    for (int k = 0; k < 3; ++k) {
      cone.lo[k] = std::min(cone.lo[k], front_.box(f).lo[k]);
      cone.hi[k] = std::max(cone.hi[k], front_.box(f).hi[k]);
    }
  // A push task's cone must stay on its side of the cut (push_sides chose its vertices so).
  if (cut_axis_ >= 0 && (low_side_ ? !(cone.hi[cut_axis_] < cut_) : !(cone.lo[cut_axis_] > cut_)))
    return false;
  near_.clear();
  front_.near(cone, [&](uint32_t f) {
    near_.push_back(f);
    return true;
  });
  for (uint32_t f : part) {
    const uint32_t* t = front_.tri(f);
    const uint32_t v[4] = {t[0], t[2], t[1], apex};
    uint32_t closing[4];
    if (!tet_fits(front_, mesh_.xyz, v, closing, fit_, near_)) return false;
    const size_t added_before = added_.size();
    commit_tet(v, closing);
    near_.insert(near_.end(), added_.begin() + std::ptrdiff_t(added_before), added_.end());
  }
  return true;
}

bool LayerBuilder::cone_fits_near(uint32_t a, const std::vector<uint32_t>& part, const double d[3],
                                  double scale) {
  // A temporary vertex at a + scale d, joined to `part` tet by tet on the real front, then
  // everything undone.
  const double* pa = mesh_.point(a);
  const double p[3] = {pa[0] + scale * d[0], pa[1] + scale * d[1], pa[2] + scale * d[2]};
  const uint32_t probe = mesh_.add_vertex(p);
  const size_t tets_before = mesh_.num_tet_slots();
  const bool fits = join_to_front(part, probe);
  front_.rollback();
  truncate_tets(tets_before);
  mesh_.xyz.resize(mesh_.xyz.size() - 3);
  mesh_.vflags.pop_back();
  return fits;
}

std::vector<uint32_t> LayerBuilder::visible_run(uint32_t a, const std::vector<uint32_t>& star,
                                                double scale, double d[3]) {
  // Order the star as a fan: triangle (a, x, y) is followed by the one starting with (a, y).
  const size_t n = star.size();
  std::vector<uint32_t> fan;
  fan.reserve(n);
  std::vector<char> used(n, 0);
  auto corner_after = [&](uint32_t f, int step) {
    const uint32_t* t = front_.tri(f);
    int k = 0;
    while (t[k] != a) ++k;
    return t[(k + step) % 3];
  };
  fan.push_back(star[0]);
  used[0] = 1;
  while (fan.size() < n) {
    const uint32_t y = corner_after(fan.back(), 2);
    size_t next = n;
    for (size_t i = 0; i < n && next == n; ++i)
      if (!used[i] && corner_after(star[i], 1) == y) next = i;
    if (next == n) break;  // not a single fan: keep what is ordered
    used[next] = 1;
    fan.push_back(star[next]);
  }
  const size_t m = fan.size();
  std::vector<double> normals, weights;
  // Longest runs first. A run is taken when one direction sees it (and, at an end edge where the
  // region's dihedral angle is below pi, the neighbour across: the run's side walls contain the
  // line from a along d and must stay in the region) and when the cone of tets over it, built
  // very close to a, fits exactly: then the halvings of push_part end too. A single triangle is
  // seen along its own normal.
  // Lengths m-1, m-2, ... one by one for small fans, then shrinking geometrically (large CAD
  // fans would otherwise cost m^2 direction searches).
  for (size_t len = m - 1; len >= 1; len = len > 12 ? len * 7 / 8 : len - 1) {
    std::vector<std::pair<double, size_t>> starts;
    std::vector<double> dirs(3 * m);
    for (size_t s = 0; s < m; ++s) {
      std::vector<uint32_t> run;
      for (size_t i = 0; i < len; ++i) run.push_back(fan[(s + i) % m]);
      star_normals(a, run, normals, weights);
      const uint32_t ends[2][2] = {{fan[s], fan[(s + m - 1) % m]},
                                   {fan[(s + len - 1) % m], fan[(s + len) % m]}};
      for (const auto& e : ends) {
        const uint32_t* t = front_.tri(e[0]);
        const uint32_t* o = front_.tri(e[1]);
        uint32_t far = o[0];
        for (int k = 0; k < 3; ++k)
          if (o[k] != t[0] && o[k] != t[1] && o[k] != t[2]) far = o[k];
        if (predicates::orient3d(mesh_.point(t[0]), mesh_.point(t[1]), mesh_.point(t[2]),
                                 mesh_.point(far)) < 0) {
          double nb[3];
          frame_normal(a, mesh_.point(o[0]), mesh_.point(o[1]), mesh_.point(o[2]), nb);
          for (int k = 0; k < 3; ++k) normals.push_back(-nb[k]);
          weights.push_back(0.0);
        }
      }
      bool improved = false;
      const double margin = visible_direction(normals, weights, &dirs[3 * s], &improved);
      out_of_frame(a, &dirs[3 * s]);
      if (margin > 0.0) starts.emplace_back(margin, s);
    }
    std::sort(starts.rbegin(), starts.rend());
    for (const auto& [margin, s] : starts) {
      std::vector<uint32_t> run;
      for (size_t i = 0; i < len; ++i) run.push_back(fan[(s + i) % m]);
      if (!cone_fits_near(a, run, &dirs[3 * s], 1e-6 * scale)) continue;
      std::copy_n(&dirs[3 * s], 3, d);
      return run;
    }
  }
  return {};
}

bool LayerBuilder::stops_instead_of_partial(uint32_t a) const {
  // With a boundary layer, a point that is not an input vertex whose whole star cannot be pushed
  // at least min_height_ratio of the planned length (push_part) stops for this layer: partial
  // pushes would leave its children clustered 1e-8 apart on the front (the airplane's 15 layers).
  return !wall_.empty() && a >= s_.num_vertices();
}

Status LayerBuilder::whole_push_failed(uint32_t a, int layer) const {
  return Status(Error::Internal, "layers: layer " + std::to_string(layer) + ": vertex " + std::to_string(a) +
                                     ": no push of its star fits above the least height");
}

Status LayerBuilder::push_vertex(uint32_t a, int layer) {
  if (a < plan_.size()) plan_[a].waiting = false;
  std::vector<double> normals, weights;
  // A whole-star push that does not fit even after max_halvings (a front across touching a's
  // cone at every height, in floating point) falls back to partial pushes of visible runs,
  // each checked to fit very close to a first.
  bool whole_failed = false;
  for (int round = 0;; ++round) {
    const std::vector<uint32_t> star = front_.star(a);
    if (star.empty()) return Status::success();
    if (size_t(round) > 2 * star.size() + 8)
      return Status(Error::Internal, "layers: layer " + std::to_string(layer) + ": vertex " +
                                         std::to_string(a) + " at " + point_text(mesh_.point(a)) +
                                         ": its front star could not be taken off in " +
                                         std::to_string(round) + " partial pushes");
    // The planned displacement, while it sees the star (the neighbours' pushes keep it so unless
    // they had to re-plan); else the best direction of the star as it is now.
    if (!whole_failed && round == 0) {
      const int planned = planned_push(a, star, layer);
      if (planned > 0) return Status::success();
      if (planned == 0) {
        if (stops_instead_of_partial(a)) return whole_push_failed(a, layer);
        whole_failed = true;
        ++out_.stats.push_fallbacks;
        continue;
      }
    }
    star_normals(a, star, normals, weights);  // (the angles weigh the directions)
    double d[3];
    bool improved = false;
    const double margin = visible_direction(normals, weights, d, &improved);
    out_of_frame(a, d);
    if (improved) ++out_.stats.direction_fixes;
    if (!whole_failed && margin > 0.0) {
      const double h = target_height(a, d);
      const double disp[3] = {h * d[0], h * d[1], h * d[2]};
      if (push_part(a, star, disp, layer).ok()) return Status::success();
      if (stops_instead_of_partial(a)) return whole_push_failed(a, layer);
      whole_failed = true;
      ++out_.stats.push_fallbacks;
      continue;
    }
    // No direction sees the whole star: take off the longest visible run of it, and go on.
    // (Not a BL vertex above the wall: its later push along the same plan left collinear
    // children, flat tets 4e-7 thick on the airplane's wings.)
    if (stops_instead_of_partial(a)) return whole_push_failed(a, layer);
    double m[6];
    sizing_.metric(mesh_.point(a), m);
    const double size = 1.0 / std::max(metric_norm(m, d), 1e-300);
    const std::vector<uint32_t> run = visible_run(a, star, size, d);
    if (run.empty())
      return Status(Error::Internal, "layers: layer " + std::to_string(layer) + ": vertex " +
                                         std::to_string(a) + " at " + point_text(mesh_.point(a)) +
                                         ": no part of its front star is visible");
    ++out_.stats.partial_pushes;
    const double h = target_height(a, d);
    const double disp[3] = {h * d[0], h * d[1], h * d[2]};
    Status st = push_part(a, run, disp, layer);
    if (!st.ok()) return st;
  }
}

bool LayerBuilder::best_apex(uint32_t a, const std::vector<uint32_t>& part, double disp[3],
                             double searched[3]) const {
  const double* pa = mesh_.point(a);
  double m[6], u[9];
  sizing_.metric(pa, m);
  metric_factor(m, u);
  // The cone's tets, and the tets that waiting neighbours will build on the cone's outer faces
  // from their planned points: the apex is chosen for both.
  std::vector<const double*> own;     // 3 per cone tet: its base, in positive-tet order
  std::vector<const double*> future;  // 3 per future tet: x, y of the outer face, planned point
  std::vector<double> planned;
  planned.reserve(6 * part.size());
  for (uint32_t f : part) {
    const uint32_t* t = front_.tri(f);
    own.insert(own.end(), {mesh_.point(t[0]), mesh_.point(t[2]), mesh_.point(t[1])});
    int k = 0;
    while (t[k] != a) ++k;
    const uint32_t x = t[(k + 1) % 3], y = t[(k + 2) % 3];
    for (uint32_t c : {x, y}) {
      if (c >= plan_.size() || !plan_[c].valid || !plan_[c].waiting) continue;
      const Plan& p = plan_[c];
      for (int j = 0; j < 3; ++j) planned.push_back(mesh_.point(c)[j] + p.height * p.d[j]);
      future.insert(future.end(), {mesh_.point(x), mesh_.point(y), nullptr});
    }
  }
  for (size_t i = 0; 3 * i < future.size(); ++i) future[3 * i + 2] = &planned[3 * i];
  // The smallest radius ratio (in the metric at a) over both sets; -1 when a cone tet is not
  // positive (floating point: a choice only, the exact test decides), 0 for a future tet (its
  // neighbour would have to re-plan or shorten this push: see keeps_plans_visible).
  // A candidate is kept only when it beats the best so far (by 1e-9): once one tet is at or
  // below that bar the rest cannot change the verdict, so the scan stops there (`stop`).
  // The radius ratios are measured on the points mapped by u (radius_ratio_in's values): the
  // fixed points are mapped once here, the candidate once per call.
  std::vector<std::array<double, 3>> own_u(own.size()), future_u(future.size());
  for (size_t i = 0; i < own.size(); ++i) apply_factor(u, own[i], own_u[i].data());
  for (size_t i = 0; i < future.size(); ++i) apply_factor(u, future[i], future_u[i].data());
  auto quality = [&](const double* p, double stop) {
    double pu[3];
    apply_factor(u, p, pu);
    double q = 1.0;
    for (size_t i = 0; i < own.size() && q > stop; i += 3)
      q = std::min(q, signed_volume(own[i], own[i + 1], own[i + 2], p) > 0.0
                          ? radius_ratio(own_u[i].data(), own_u[i + 1].data(), own_u[i + 2].data(), pu)
                          : -1.0);
    for (size_t i = 0; i < future.size() && q > stop; i += 3) {
      const double *x = future[i], *y = future[i + 1], *at = future[i + 2];
      q = std::min(q, signed_volume(p, y, x, at) > 0.0
                          ? radius_ratio(pu, future_u[i + 1].data(), future_u[i].data(), future_u[i + 2].data())
                          : 0.0);
    }
    return q;
  };
  // Along disp first (a few fractions), then, for a poor result only (hard stars: an edge-on
  // triangle), a small pattern search in space around the best point.
  double best = -2.0, best_p[3] = {pa[0] + disp[0], pa[1] + disp[1], pa[2] + disp[2]};
  for (double scale : {1.0, 0.8, 0.65, 0.5, 0.4, 0.3, 0.2}) {
    // Far below the plan the cone may suit a poor neighbour better, but the height jump it
    // leaves makes flat tets in this layer's prisms and the next.
    if (scale < opt_.min_height_fraction) break;
    const double p[3] = {pa[0] + scale * disp[0], pa[1] + scale * disp[1], pa[2] + scale * disp[2]};
    const double q = quality(p, best + 1e-9);
    if (q > best + 1e-9) {
      best = q;
      std::copy_n(p, 3, best_p);
    }
  }
  for (int k = 0; k < 3; ++k) disp[k] = best_p[k] - pa[k];
  constexpr double kPoor = 0.3;
  bool moved_off = false;
  // The search stays near the plan: a point far beyond or beside it may suit this cone and the
  // planned neighbours, but it makes the next front uneven and the next layer's tets flat.
  const double plan_len = std::sqrt(dot3(disp, disp));
  const double axis[3] = {disp[0] / std::max(plan_len, 1e-300), disp[1] / std::max(plan_len, 1e-300),
                          disp[2] / std::max(plan_len, 1e-300)};
  auto near_plan = [&](const double* p) {
    const double rel[3] = {p[0] - pa[0], p[1] - pa[1], p[2] - pa[2]};
    const double along = dot3(rel, axis);
    const double side2 = std::max(dot3(rel, rel) - along * along, 0.0);
    return along <= 1.25 * plan_len && along >= 0.3 * plan_len &&
           side2 <= 0.35 * 0.35 * plan_len * plan_len;
  };
  if (best > 0.0 && best < kPoor) {
    double step = 0.25 * plan_len;
    const double stop = 0.02 * step;
    for (int it = 0; it < 60 && step > stop; ++it) {
      bool moved = false;
      for (int k = 0; k < 3; ++k)
        for (int sign = -1; sign <= 1; sign += 2) {
          double p[3] = {best_p[0], best_p[1], best_p[2]};
          p[k] += sign * step;
          if (!near_plan(p)) continue;
          const double q = quality(p, best + 1e-9);
          if (q > best + 1e-9) {
            best = q;
            std::copy_n(p, 3, best_p);
            moved = moved_off = true;
          }
        }
      if (!moved) step *= 0.5;
    }
  }
  for (int k = 0; k < 3; ++k) searched[k] = best_p[k] - pa[k];
  return moved_off;
}

Status LayerBuilder::push_part(uint32_t a, const std::vector<uint32_t>& part,
                               const double disp[3], int layer) {
  double pa[3];
  std::copy_n(mesh_.point(a), 3, pa);
  const uint32_t moved = mesh_.add_vertex(pa);
  out_.vertex_origin.resize(mesh_.num_vertices(), TetMesh::kNone);
  out_.vertex_origin[moved] = a;
  ++out_.stats.new_vertices;
  ++out_.stats.pushes;
  // Displacements to try: the searched apex first (when the search moved it off the line),
  // then the best point along disp, shrunk until everything fits.
  double start[3] = {disp[0], disp[1], disp[2]}, searched[3];
  bool have_searched = false;
  if (opt_.choose_height && bl_index_ < 0) have_searched = best_apex(a, part, start, searched);
  std::vector<uint32_t> columns;
  for (uint32_t f : part) columns.push_back(column_of(f));
  // With a boundary layer, a point that is not an input vertex is not shrunk below
  // min_height_ratio of h0 r^i (BL layers) or of its planned length (the ordinary layers on
  // them): on the airplane's 15 layers, pushes halved 10 to 19 times made cells 1e-7 h thick
  // (checkMesh's aspect ratio 3e7), whose locked BL vertices no later stage can move. The push
  // fails instead, and push_one stops the vertex for this layer.
  const double start_length = std::sqrt(dot3(start, start));
  const double min_length = wall_.empty() || a < s_.num_vertices() ? 0.0
                            : opt_.boundary_layer.min_height_ratio * (bl_index_ >= 0 ? bl_nominal() : start_length);
  double scale = 1.0;
  for (int halvings = have_searched ? -1 : 0; halvings <= opt_.max_halvings; ++halvings) {
    if (halvings >= 0 && scale * start_length < min_length) break;
    double* p = &mesh_.xyz[3 * size_t(moved)];
    for (int k = 0; k < 3; ++k) p[k] = pa[k] + (halvings < 0 ? searched[k] : scale * start[k]);
    if (halvings >= 0) scale *= opt_.shrink;
    const size_t tets_before = mesh_.num_tet_slots();
    bool fits = join_to_front(part, moved);
    if (fits && !keeps_plans_visible(std::max(halvings, 0))) {
      fits = false;
      ++out_.stats.lookahead_halvings;
    }
    if (fits) {
      front_.commit();
      for (const Replan& r : replans_) {
        std::copy_n(r.d, 3, plan_[r.v].d);
        touched_plans_.push_back(r.v);
      }
      auto& st = out_.stats;
      st.replans += replans_.size();
      st.push_tets += mesh_.num_tet_slots() - tets_before;
      const size_t shrunk = size_t(std::max(halvings, 0));
      st.push_halvings += shrunk;
      if (shrunk > 0) {
        ++st.pushes_halved;
        for (uint32_t c : columns) column_halved_[c] = 1;
      }
      if (bl_index_ >= 0) record_bl_push(a, moved);
      if (a < wall_.size() && wall_[a]) {
        wall_.resize(mesh_.num_vertices(), 0);
        wall_[moved] = 1;
      }
      st.max_push_halvings = std::max(st.max_push_halvings, shrunk);
      return Status::success();
    }
    front_.rollback();
    truncate_tets(tets_before);
  }
  // The new vertex is the last one (probes are removed after use): take it back.
  mesh_.xyz.resize(mesh_.xyz.size() - 3);
  mesh_.vflags.pop_back();
  out_.vertex_origin.resize(mesh_.num_vertices());
  --out_.stats.new_vertices;
  --out_.stats.pushes;
  return Status(Error::Internal, "layers: layer " + std::to_string(layer) + ": vertex " +
                                     std::to_string(a) + " at " + point_text(pa) +
                                     ": no pushed position fits after " +
                                     std::to_string(opt_.max_halvings) + " halvings");
}

Result<std::vector<uint32_t>> LayerBuilder::push_sides(const std::vector<uint32_t>& order) {
  // A push reads and changes the front within its reach: its star (the triangles it removes and
  // the cone's box, apex included: best_apex stays within 1.31 planned heights of the vertex) and
  // its neighbours' stars (the look-ahead of keeps_plans_visible, Front::find). Vertices whose
  // reach lies strictly on one side of the cut go to that side's task: then the two tasks never
  // touch the same triangle, plan or vertex, and each one's copy of its side holds every triangle
  // its queries can meet. (Later pushes on a side stay within their own reach, on that side too.)
  // (Each front vertex's star box first: a reach is the union of a few of them.)
  std::vector<Box3> star_box;
  auto measure_star_boxes = [&] {
    star_box.resize(mesh_.num_vertices());
    for_each_index(star_box.size(), [&](size_t u) {
      const std::vector<uint32_t>& star = front_.star(uint32_t(u));
      if (star.empty()) return;
      Box3& b = star_box[u];
      b = front_.box(star[0]);
      for (uint32_t g : star)
        for (int j = 0; j < 3; ++j) {
          b.lo[j] = std::min(b.lo[j], front_.box(g).lo[j]);
          b.hi[j] = std::max(b.hi[j], front_.box(g).hi[j]);
        }
    });
  };
  std::vector<Box3> reach(order.size());
  auto measure_reach = [&](size_t i) {
    const uint32_t v = order[i];
    Box3& r = reach[i];
    r = box_around(mesh_.point(v), 1.5 * plan_[v].height);
    for (uint32_t f : front_.star(v)) {
      const uint32_t* t = front_.tri(f);
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j) {
          r.lo[j] = std::min(r.lo[j], star_box[t[k]].lo[j]);
          r.hi[j] = std::max(r.hi[j], star_box[t[k]].hi[j]);
        }
    }
  };
  measure_star_boxes();
  for_each_index(order.size(), measure_reach);
  // The cut: among planes across each axis at the 30th to 70th percentiles of the vertices, the one
  // with the least of twice the reach band's size (its pushes go one by one, with the wider
  // reaches) plus the larger side's (its task's): the band's size alone left the two tasks
  // unbalanced, one core idle while the other finished. (A cut through a feature of long triangles
  // puts many vertices in the band, and the worst tets of a layer can end up there.)
  int axis = 0;
  double cut = 0.0;
  size_t best_cost = 2 * order.size() + 1;
  std::vector<double> coord(order.size());
  for (int k = 0; k < 3; ++k) {
    for (size_t i = 0; i < order.size(); ++i) coord[i] = mesh_.point(order[i])[k];
    std::sort(coord.begin(), coord.end());
    for (int q = 60; q <= 140; q += 5) {  // in half percents
      const double c = coord[coord.size() * size_t(q) / 200];
      size_t below = 0, above = 0;
      for (const Box3& r : reach) {
        below += r.hi[k] < c;
        above += r.lo[k] > c;
      }
      const size_t cost = 2 * (order.size() - below - above) + std::max(below, above);
      if (cost < best_cost) {
        best_cost = cost;
        axis = k;
        cut = c;
      }
    }
  }
  std::vector<uint8_t> side(order.size(), 2);  // 0 low, 1 high, 2 neither
  auto find_sides = [&](bool measure_again) {
    if (measure_again) measure_star_boxes();
    for_each_index(order.size(), [&](size_t i) {
      if (side[i] == 3) return;  // (pushed already)
      if (measure_again) measure_reach(i);
      side[i] = reach[i].hi[axis] < cut ? 0 : reach[i].lo[axis] > cut ? 1 : 2;
    });
  };
  find_sides(false);
  // The vertices across the cut are pushed first, one by one, while their neighbours wait (pushed
  // after the tasks, squeezed between their neighbours' cones, they left much worse tets). Their
  // cones change the reach of the vertices next to them: measured again after.
  size_t sides[3] = {0, 0, 0};
  for (uint8_t k : side) ++sides[k];
  if (sides[0] == 0 || sides[1] == 0) return order;
  // (A few rounds: a cone pushed first can carry its neighbours' reach across; they go next.)
  for (int round = 0; round < 4; ++round) {
    bool any = false;
    for (size_t i = 0; i < order.size(); ++i)
      if (side[i] == 2) {
        if (Status st = push_one(order[i]); !st.ok()) return st;
        side[i] = 3;
        any = true;
      }
    if (!any) break;
    find_sides(true);
  }

  const uint32_t nv0 = uint32_t(mesh_.num_vertices());
  std::vector<uint32_t> mine[2];
  for (size_t i = 0; i < order.size(); ++i)
    if (side[i] < 2) mine[side[i]].push_back(order[i]);
  std::unique_ptr<LayerBuilder> task[2];  // (the task constructor is private: no make_unique)
  std::vector<uint32_t> given_back[2];
  auto run_side = [&](int k) {
    if (mine[k].empty()) return;
    task[k].reset(new LayerBuilder(*this, axis, cut, k == 0));
    for (uint32_t v : mine[k])
      if (!task[k]->push_planned(v)) given_back[k].push_back(v);
  };
  tbb::parallel_invoke([&] { run_side(0); }, [&] { run_side(1); });
  for (int k = 0; k < 2; ++k)
    if (task[k]) merge_side(*task[k], nv0);
  // What is left, in the layer's order: the vertices whose reach crosses the cut now, and those
  // whose planned push did not fit (push_vertex tries its other ways on them).
  for (int k = 0; k < 2; ++k) std::sort(given_back[k].begin(), given_back[k].end());
  std::vector<uint32_t> rest;
  for (size_t i = 0; i < order.size(); ++i)
    if (side[i] == 2 || (side[i] < 2 && std::binary_search(given_back[side[i]].begin(),
                                                             given_back[side[i]].end(), order[i])))
      rest.push_back(order[i]);
  return rest;
}

int LayerBuilder::planned_push(uint32_t a, const std::vector<uint32_t>& star, int layer) {
  if (a >= plan_.size() || !plan_[a].valid) return -1;
  const Plan& p = plan_[a];
  std::vector<double> normals;
  star_normals(a, star, normals);
  if (!(star_margin(normals, into_frame(a, p.d).data()) > 0.0)) return -1;
  const double disp[3] = {p.height * p.d[0], p.height * p.d[1], p.height * p.d[2]};
  return push_part(a, star, disp, layer).ok() ? 1 : 0;
}

bool LayerBuilder::push_planned(uint32_t a) {
  Plan& p = plan_[a];
  p.waiting = false;
  touched_plans_.push_back(a);
  const std::vector<uint32_t> star = front_.star(a);
  if (star.empty()) return true;  // (closed by its neighbours' pushes)
  if (planned_push(a, star, layer_) > 0) return true;
  p.waiting = true;
  return false;
}

void LayerBuilder::merge_side(const LayerBuilder& w, uint32_t nv0) {
  // The task's vertices follow the ones already here (an earlier task's).
  const uint32_t shift = uint32_t(mesh_.num_vertices()) - nv0;
  auto vertex = [&](uint32_t v) { return v < nv0 ? v : v + shift; };
  for (uint32_t v = nv0; v < w.mesh_.num_vertices(); ++v) mesh_.add_vertex(w.mesh_.point(v), w.mesh_.vflags[v]);
  out_.vertex_origin.resize(mesh_.num_vertices(), TetMesh::kNone);
  for (uint32_t v = nv0; v < w.mesh_.num_vertices(); ++v) out_.vertex_origin[vertex(v)] = w.out_.vertex_origin[v];
  std::vector<uint32_t> tet(w.mesh_.num_tet_slots());
  for (uint32_t t = 0; t < w.mesh_.num_tet_slots(); ++t) {
    const uint32_t* q = &w.mesh_.tet_v[4 * size_t(t)];
    tet[t] = mesh_.new_tet(vertex(q[0]), vertex(q[1]), vertex(q[2]), vertex(q[3]), w.mesh_.tet_region[t]);
    mesh_.tet_flags[tet[t]] = w.mesh_.tet_flags[t];
    out_.tet_layer.push_back(w.out_.tet_layer[t]);
    out_.tet_column.push_back(w.out_.tet_column[t]);
  }
  // Front: the copied triangles the task closed go, then its own open ones come (in slot order).
  for (uint32_t f : w.copied_slots_)
    if (!w.front_.alive(f)) front_.remove(f);
  for (uint32_t f = uint32_t(w.base_slots_); f < w.front_.num_slots(); ++f) {
    if (!w.front_.alive(f)) continue;
    const uint32_t* t = w.front_.tri(f);
    front_.add(vertex(t[0]), vertex(t[1]), vertex(t[2]), tet[w.front_.owner(f) - w.tet_base_]);
  }
  for (uint32_t v : w.touched_plans_) plan_[v] = w.plan_[v];
  for (size_t c = 0; c < column_halved_.size(); ++c) column_halved_[c] |= w.column_halved_[c];
  fit_.tests += w.fit_.tests;
  fit_.candidates += w.fit_.candidates;
  fit_.tri_tests += w.fit_.tri_tests;
  LayersStats& st = out_.stats;
  const LayersStats& ws = w.out_.stats;
  st.new_vertices += ws.new_vertices;
  st.pushes += ws.pushes;
  st.push_tets += ws.push_tets;
  st.push_halvings += ws.push_halvings;
  st.pushes_halved += ws.pushes_halved;
  st.max_push_halvings = std::max(st.max_push_halvings, ws.max_push_halvings);
  st.lookahead_halvings += ws.lookahead_halvings;
  st.replans += ws.replans;
  st.task_pushes += ws.pushes;
}

}  // namespace anitet::layers
