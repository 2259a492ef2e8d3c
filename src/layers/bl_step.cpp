// Boundary-layer mode of stage 1 (see BoundaryLayerOptions in layers.hpp): the wall vertices are
// pushed by the ordinary push step, with smoothed normals and the heights h0 r^i instead of the
// sizing field's, reduced where needed. Validity is still decided by the exact fit test alone.
#include <algorithm>
#include <cmath>
#include <string>

#include "layers/geometry.hpp"
#include "layers/layer_builder.hpp"

namespace anitet {

int boundary_layer_count(const BoundaryLayerOptions& bl) {
  if (bl.layers > 0) return bl.layers;
  int n = 0;
  double total = 0.0, h = bl.first_height;
  while (total < bl.total_thickness && n < 1000) {
    total += h;
    h *= bl.growth;
    ++n;
  }
  return n;
}

namespace layers {

namespace {

double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

Status LayerBuilder::setup_boundary_layer() {
  const BoundaryLayerOptions& bl = opt_.boundary_layer;
  if (!bl.enabled()) return Status::success();
  const size_t nv = s_.num_vertices(), nt = s_.num_triangles();
  wall_.assign(nv, 0);
  wall_triangle_.assign(nt, 0);
  std::vector<int32_t> other(nv, 0);
  std::vector<uint8_t> has_other(nv, 0);
  size_t wall_triangles = 0;
  for (size_t t = 0; t < nt; ++t) {
    const bool wall = std::find(bl.wall_patches.begin(), bl.wall_patches.end(), s_.patch[t]) !=
                      bl.wall_patches.end();
    wall_triangle_[t] = wall ? 1 : 0;
    wall_triangles += wall ? 1 : 0;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = s_.tri[3 * t + k];
      if (wall) {
        wall_[v] = 1;
      } else if (!has_other[v]) {
        has_other[v] = 1;
        other[v] = s_.patch[t];
      }
    }
  }
  // A wall label no triangle has would be dropped without a word (a typo, another file's label).
  for (int32_t label : bl.wall_patches)
    if (std::find(s_.patch.begin(), s_.patch.end(), label) == s_.patch.end())
      return Status(Error::InvalidArgument,
                    "layers: boundary layer: no triangle has the wall patch label " + std::to_string(label));
  if (wall_triangles == 0) return Status(Error::InvalidArgument, "layers: no triangle carries a wall patch label");
  if (!bl.column_next.empty() && bl.column_next.size() != nv)
    return Status(Error::InvalidArgument, "layers: boundary layer: column_next must have one entry per vertex");
  // A wall vertex on another patch needs its junction column (the slide patches, set up by
  // slide_boundary_layer): without one its prisms would have no side faces to stand on.
  for (size_t v = 0; v < nv; ++v)
    if (wall_[v] && has_other[v] && (bl.column_next.empty() || bl.column_next[v] == TetMesh::kNone))
      return Status(Error::InvalidArgument,
                    "layers: boundary layer: vertex " + std::to_string(v) + " at " + point_text(s_.point(v)) +
                        " is on a wall patch and on patch " + std::to_string(other[v]) +
                        ": a wall may meet another patch only where the layers slide along it (make it a slide "
                        "patch: --bl-slide-patches " + std::to_string(other[v]) + ")");
  bl_layers_ = boundary_layer_count(bl);
  bl_reduced_root_.assign(nv, 0);
  out_.stats.bl_wall_vertices = size_t(std::count(wall_.begin(), wall_.end(), 1));
  return Status::success();
}

void LayerBuilder::push_junctions(std::vector<uint32_t>& vertices) {
  const std::vector<uint32_t>& next = opt_.boundary_layer.column_next;
  if (next.empty()) return;
  // In increasing id order, as the slide patches' band triangles were cut for (slide_patches.hpp).
  std::vector<uint32_t> junctions, others;
  for (uint32_t v : vertices) (v < next.size() && next[v] != TetMesh::kNone ? junctions : others).push_back(v);
  std::sort(junctions.begin(), junctions.end());
  for (uint32_t a : junctions) push_junction(a, next[a]);
  vertices = std::move(others);
}

void LayerBuilder::push_junction(uint32_t a, uint32_t next) {
  // The cone from the column's next point over a's wall-side star; the band triangles holding
  // that point are closed by its tets. A slide triangle without it (the neighbouring column did
  // not move up) leaves the column waiting, as a push that does not fit.
  std::vector<uint32_t> part;
  bool closable = true;
  for (uint32_t f : front_.star(a)) {
    const uint32_t* t = front_.tri(f);
    if (t[0] == next || t[1] == next || t[2] == next) continue;
    if (front_.owner(f) == Front::kNone && !wall_triangle_[f]) closable = false;
    part.push_back(f);
  }
  const size_t tets_before = mesh_.num_tet_slots();
  auto& st = out_.stats;
  if (closable && join_to_front(part, next) && front_.star(a).empty()) {
    front_.commit();
    st.push_tets += mesh_.num_tet_slots() - tets_before;
    ++st.pushes;
    ++st.bl_junction_pushes;
    out_.vertex_origin.resize(mesh_.num_vertices(), TetMesh::kNone);
    out_.vertex_origin[next] = a;
    wall_[next] = 1;
    record_bl_push(a, next);
    return;
  }
  if (closable) {
    front_.rollback();
    truncate_tets(tets_before);
  }
  ++st.bl_junction_stops;
  mark_bl_reduced(a);
}

double LayerBuilder::bl_nominal() const {
  const BoundaryLayerOptions& bl = opt_.boundary_layer;
  return bl.first_height * std::pow(bl.growth, bl_index_);
}

double LayerBuilder::bl_height(uint32_t a, const double d[3]) const {
  const BoundaryLayerOptions& bl = opt_.boundary_layer;
  double h = bl_nominal();
  // Grazing: the prisms on the triangles that d barely sees are flat; lower them with the
  // margin (a partial push of a star no direction sees gets a tenth).
  std::vector<double> normals, weights;
  star_normals(a, front_.star(a), normals, weights);
  const double margin = star_margin(normals, into_frame(a, d).data());
  if (margin < bl.grazing_margin) h *= std::clamp(margin / bl.grazing_margin, 0.1, 1.0);
  else if (bl.mitre && margin < 1.0) h /= std::max(margin, bl.mitre_min_cosine);
  // Fronts colliding: the rest of the BL (this layer and the ones after it, at full height)
  // may fill only a share of the free distance across, which the front there shares too.
  double rest = 0.0;
  for (int j = bl_index_; j < bl_layers_; ++j) rest += bl.first_height * std::pow(bl.growth, j);
  std::vector<uint32_t> ring;
  for (uint32_t f : front_.star(a)) ring.insert(ring.end(), front_.tri(f), front_.tri(f) + 3);
  std::sort(ring.begin(), ring.end());
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  const double free = clearance(mesh_.point(a), d, rest / bl.gap_share, ring);
  if (bl.gap_share * free < rest) h *= bl.gap_share * free / rest;
  return h;
}

void LayerBuilder::plan_boundary_layer(const std::vector<uint32_t>& vertices) {
  const BoundaryLayerOptions& bl = opt_.boundary_layer;
  const std::vector<std::pair<uint32_t, uint32_t>> edges = planned_edges(vertices);
  // Normal smoothing: each direction moves towards its neighbours' mean, kept only while it
  // still sees its own star with half the margin it started with.
  std::vector<double> start_margin(plan_.size(), 0.0), normals, weights;
  for (uint32_t v : vertices)
    if (plan_[v].valid) {
      star_normals(v, front_.star(v), normals, weights);
      start_margin[v] = star_margin(normals, into_frame(v, plan_[v].d).data());
    }
  std::vector<double> sum(3 * plan_.size(), 0.0);
  for (int pass = 0; pass < bl.normal_smoothing; ++pass) {
    std::fill(sum.begin(), sum.end(), 0.0);
    for (const auto& [u, v] : edges)
      for (int k = 0; k < 3; ++k) {
        sum[3 * u + k] += plan_[v].d[k];
        sum[3 * v + k] += plan_[u].d[k];
      }
    for (uint32_t v : vertices) {
      if (!plan_[v].valid) continue;
      double d[3];
      for (int k = 0; k < 3; ++k) d[k] = plan_[v].d[k] + sum[3 * v + k];
      const double len = std::sqrt(dot3(d, d));
      if (!(len > 0.0)) continue;
      for (int k = 0; k < 3; ++k) d[k] /= len;
      star_normals(v, front_.star(v), normals, weights);
      if (star_margin(normals, into_frame(v, d).data()) >= 0.5 * start_margin[v]) std::copy_n(d, 3, plan_[v].d);
    }
  }
  for (uint32_t v : vertices)
    if (plan_[v].valid) plan_[v].height = bl_height(v, plan_[v].d);
  limit_gradation(edges, bl.gradation, bl.gradation_rings);
}

void LayerBuilder::mark_bl_reduced(uint32_t v) {
  // (Junction columns' points are surface vertices with an origin too.)
  uint32_t root = v;
  while (root < out_.vertex_origin.size() && out_.vertex_origin[root] != TetMesh::kNone)
    root = out_.vertex_origin[root];
  if (root < bl_reduced_root_.size()) bl_reduced_root_[root] = 1;
}

void LayerBuilder::record_bl_push(uint32_t a, uint32_t moved) {
  const double* p = mesh_.point(a);
  const double* q = mesh_.point(moved);
  const double e[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
  const double ratio = std::sqrt(dot3(e, e)) / bl_nominal();
  auto& st = out_.stats;
  ++st.bl_pushes;
  st.bl_min_height_ratio = std::min(st.bl_min_height_ratio, ratio);
  if (ratio < 0.9) {
    ++st.bl_reduced_pushes;
    mark_bl_reduced(a);
  } else {
    st.bl_max_height_error = std::max(st.bl_max_height_error, std::abs(ratio - 1.0));
  }
}

}  // namespace layers
}  // namespace anitet
