#include "layers/layers.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <unordered_map>

#include "layers/front.hpp"
#include "layers/geometry.hpp"
#include "layers/layer_builder.hpp"
#include "layers/tet_fit.hpp"

namespace anitet::layers {

std::string point_text(const double* p) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return s.str();
}

namespace {

// Cheap structural preconditions; the full validation (self-intersections...) is validate/'s job.
Status check_input(const SurfaceMesh& s) {
  const size_t nv = s.num_vertices(), nt = s.num_triangles();
  if (s.xyz.size() != 3 * nv || s.tri.size() != 3 * nt)
    return Status(Error::InvalidArgument, "surface arrays have inconsistent sizes");
  if (nt == 0) return Status(Error::EmptyInput, "the surface has no triangle");
  if (nv >= TetMesh::kGhost) return Status(Error::InvalidArgument, "too many vertices");
  std::unordered_map<uint64_t, uint32_t> directed;
  directed.reserve(3 * nt);
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t* v = &s.tri[3 * t];
    for (int k = 0; k < 3; ++k) {
      if (v[k] >= nv)
        return Status(Error::BadIndex, "triangle " + std::to_string(t) + " refers to vertex " +
                                           std::to_string(v[k]) + " which does not exist");
      if (!std::isfinite(s.xyz[3 * v[k]]) || !std::isfinite(s.xyz[3 * v[k] + 1]) ||
          !std::isfinite(s.xyz[3 * v[k] + 2]))
        return Status(Error::InvalidArgument, "vertex " + std::to_string(v[k]) + " is not finite");
    }
    double n[3];
    if (!(unit_normal(s.point(v[0]), s.point(v[1]), s.point(v[2]), n) > 0.0))
      return Status(Error::InvalidArgument, "triangle " + std::to_string(t) + " is degenerate");
    for (int k = 0; k < 3; ++k) {
      const uint64_t key = (uint64_t(v[k]) << 32) | v[(k + 1) % 3];
      if (!directed.emplace(key, uint32_t(t)).second)
        return Status(Error::InvalidArgument, "edge (" + std::to_string(v[k]) + ", " +
                                                  std::to_string(v[(k + 1) % 3]) +
                                                  ") is used twice in the same direction");
    }
  }
  for (const auto& [key, t] : directed) {
    const uint64_t twin = (key << 32) | (key >> 32);
    if (directed.find(twin) == directed.end())
      return Status(Error::InvalidArgument, "the surface is not closed: edge (" +
                                                std::to_string(key >> 32) + ", " +
                                                std::to_string(key & 0xffffffffu) + ") of triangle " +
                                                std::to_string(t) + " has no opposite edge");
  }
  return Status::success();
}

Box3 surface_bounds(const SurfaceMesh& s) {
  Box3 b;
  for (int k = 0; k < 3; ++k) {
    b.lo[k] = std::numeric_limits<double>::infinity();
    b.hi[k] = -b.lo[k];
  }
  for (uint32_t v : s.tri)
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = std::min(b.lo[k], s.xyz[3 * size_t(v) + k]);
      b.hi[k] = std::max(b.hi[k], s.xyz[3 * size_t(v) + k]);
    }
  return b;
}

}  // namespace

LayerBuilder::LayerBuilder(const SurfaceMesh& s, const SizingField& sizing,
                           const LayersOptions& options, LayersOutput& out)
    : s_(s), sizing_(sizing), opt_(options), out_(out), mesh_(out.mesh),
      front_(out.mesh.xyz, surface_bounds(s)) {}

namespace {

// A push task's starting output: main's vertices (the task adds its own after them), no tets.
LayersOutput task_output(const LayersOutput& main) {
  LayersOutput out;
  out.mesh.xyz = main.mesh.xyz;
  out.mesh.vflags = main.mesh.vflags;
  out.vertex_origin = main.vertex_origin;
  return out;
}

}  // namespace

LayerBuilder::LayerBuilder(const LayerBuilder& main, int axis, double cut, bool low_side)
    : own_out_(task_output(main.out_)), s_(main.s_), sizing_(main.sizing_), opt_(main.opt_),
      out_(own_out_), mesh_(own_out_.mesh), front_(main.front_, own_out_.mesh.xyz, axis, cut, low_side),
      plan_(main.plan_), remaining_layers_(main.remaining_layers_), layer_(main.layer_),
      bl_index_(main.bl_index_), bl_layers_(main.bl_layers_), column_halved_(main.column_halved_),
      frame_state_(main.frame_state_), frame_(main.frame_), cut_axis_(axis), cut_(cut),
      low_side_(low_side), tet_base_(uint32_t(main.mesh_.num_tet_slots())),
      base_tet_column_(&main.out_.tet_column), base_slots_(main.front_.num_slots()) {
  for (uint32_t f = 0; f < base_slots_; ++f)
    if (front_.alive(f)) copied_slots_.push_back(f);
}

uint32_t LayerBuilder::column_of(uint32_t f) const {
  const uint32_t owner = front_.owner(f);
  if (owner == Front::kNone) return f;
  // A push task's front holds main's tets (below tet_base_) and its own.
  if (owner < tet_base_) return (*base_tet_column_)[owner];
  return out_.tet_column[owner - tet_base_];
}

void LayerBuilder::commit_tet(const uint32_t v[4], const uint32_t closing[4]) {
  // Facet 3 is the base: the front triangle the tet is built on (face step and push step).
  const uint32_t column = closing[3] == Front::kNone ? 0u : column_of(closing[3]);
  const uint32_t t = mesh_.new_tet(v[0], v[1], v[2], v[3],
                                   bl_index_ >= 0 ? opt_.boundary_layer.region : 0);
  out_.tet_layer.push_back(uint16_t(layer_));
  out_.tet_column.push_back(column);
  for (int i = 0; i < 4; ++i) {
    if (closing[i] != Front::kNone) {
      // An input triangle leaving the front: it is a facet of T1's boundary, a constraint.
      if (front_.owner(closing[i]) == Front::kNone) mesh_.set_facet_protected(t, i, true);
      front_.remove(closing[i]);
    } else {
      // kFacetVertex lists the facet with its normal into the tet: away from the region, as the
      // front's convention wants.
      added_.push_back(front_.add(v[kFacetVertex[i][0]], v[kFacetVertex[i][1]],
                                  v[kFacetVertex[i][2]], t + tet_base_));
    }
  }
}

void LayerBuilder::truncate_tets(size_t n) {
  mesh_.tet_v.resize(4 * n);
  mesh_.tet_adj.resize(4 * n);
  mesh_.tet_flags.resize(n);
  mesh_.tet_region.resize(n);
  out_.tet_layer.resize(n);
  out_.tet_column.resize(n);
}

Status LayerBuilder::face_tet(uint32_t f, int layer) {
  added_.clear();  // (only the push step reads it)
  const uint32_t a = front_.tri(f)[0], b = front_.tri(f)[1], c = front_.tri(f)[2];
  double pa[3], pb[3], pc[3], n[3], mid[3];
  std::copy_n(mesh_.point(a), 3, pa);
  std::copy_n(mesh_.point(b), 3, pb);
  std::copy_n(mesh_.point(c), 3, pc);
  unit_normal(pa, pb, pc, n);
  double into[3];
  for (int k = 0; k < 3; ++k) {
    into[k] = -n[k];
    mid[k] = (pa[k] + pb[k] + pc[k]) / 3.0;
  }
  // Height of the regular tet on the base, measured in the metric at the centroid.
  double m[6], u[9];
  sizing_.metric(mid, m);
  metric_factor(m, u);
  const double mean_edge = (metric_edge_length(m, pa, pb) + metric_edge_length(m, pb, pc) +
                            metric_edge_length(m, pc, pa)) / 3.0;
  const double reg = std::sqrt(2.0 / 3.0) * mean_edge / metric_norm(m, into);
  double eps = 0.0, best = -1.0;
  for (double scale : {0.7, 0.85, 1.0, 1.15, 1.3}) {
    const double h = scale * opt_.face_height * reg;
    const double p[3] = {mid[0] + h * into[0], mid[1] + h * into[1], mid[2] + h * into[2]};
    const double q = radius_ratio_in(u, pa, pc, pb, p);
    if (q > best) {
      best = q;
      eps = h;
    }
  }
  // Leave room for the front across (see target_height in push_step.cpp).
  const double share = 1.0 / (2.0 * remaining_layers_ + 1.0);
  eps = std::min(eps, share * clearance(mid, into, eps / share, {a, b, c}));
  const uint32_t apex = mesh_.add_vertex(mid);
  ++out_.stats.new_vertices;
  ++out_.stats.faces;
  for (int halvings = 0; halvings <= opt_.max_halvings; ++halvings) {
    double* p = &mesh_.xyz[3 * size_t(apex)];
    for (int k = 0; k < 3; ++k) p[k] = mid[k] + eps * into[k];
    const uint32_t v[4] = {a, c, b, apex};
    uint32_t closing[4];
    if (tet_fits(front_, mesh_.xyz, v, closing, fit_)) {
      if (halvings > 0) column_halved_[column_of(f)] = 1;
      commit_tet(v, closing);
      auto& st = out_.stats;
      ++st.face_tets;
      st.face_halvings += size_t(halvings);
      if (halvings > 0) ++st.faces_halved;
      st.max_face_halvings = std::max(st.max_face_halvings, size_t(halvings));
      return Status::success();
    }
    eps *= opt_.shrink;
  }
  return Status(Error::Internal,
                "layers: layer " + std::to_string(layer) + ": front triangle (" + std::to_string(a) +
                    ", " + std::to_string(b) + ", " + std::to_string(c) + ") at " +
                    point_text(mid) + ": no apex fits after " + std::to_string(opt_.max_halvings) +
                    " halvings");
}

Status LayerBuilder::run() {
  const auto start = std::chrono::steady_clock::now();
  for (size_t v = 0; v < s_.num_vertices(); ++v)
    mesh_.add_vertex(s_.point(v), vflag::kOnInputSurface);
  for (size_t t = 0; t < s_.num_triangles(); ++t)
    front_.add(s_.tri[3 * t], s_.tri[3 * t + 1], s_.tri[3 * t + 2], Front::kNone);

  column_halved_.assign(s_.num_triangles(), 0);
  if (Status st = setup_boundary_layer(); !st.ok()) return st;
  const int total_layers = bl_layers_ + opt_.layers;
  for (int layer = 1; layer <= total_layers; ++layer) {
    layer_ = layer;
    bl_index_ = layer <= bl_layers_ ? layer - 1 : -1;
    const auto layer_start = std::chrono::steady_clock::now();
    remaining_layers_ = total_layers - layer + 1;
    LayerStats ls;
    ls.boundary_layer = bl_index_ >= 0;
    ls.front_triangles_before = front_.num_alive();
    const size_t face_tets_before = out_.stats.face_tets, push_tets_before = out_.stats.push_tets;
    const size_t halvings_before = out_.stats.face_halvings + out_.stats.push_halvings;
    // The layer works on the front as it is now: its vertices and (face step) its triangles; a
    // BL layer on the wall vertices only.
    std::vector<uint32_t> vertices;
    for (uint32_t v = 0; v < mesh_.num_vertices(); ++v)
      if (!front_.star(v).empty() && (bl_index_ < 0 || (v < wall_.size() && wall_[v])))
        vertices.push_back(v);
    if (opt_.scheme == LayerScheme::kFacesThenPush && bl_index_ < 0) {
      std::vector<uint32_t> faces;
      for (uint32_t f = 0; f < front_.num_slots(); ++f)
        if (front_.alive(f)) faces.push_back(f);
      for (uint32_t f : faces) {
        Status st = face_tet(f, layer);
        if (!st.ok()) return st;
      }
    }
    const uint32_t first_new_vertex = uint32_t(mesh_.num_vertices());
    Status st = push_step(vertices);
    if (!st.ok()) return st;
    // Every move into the region takes room from the next layer (a cliff usually marks a tight
    // spot), so before the last layer only the really flat tets are worth it.
    if (bl_index_ < 0)
      improve_layer(first_new_vertex,
                    layer == total_layers ? opt_.improve_below : opt_.improve_below_inner);
    ls.face_tets = out_.stats.face_tets - face_tets_before;
    ls.push_tets = out_.stats.push_tets - push_tets_before;
    ls.halvings = out_.stats.face_halvings + out_.stats.push_halvings - halvings_before;
    ls.halved_columns = size_t(std::count(column_halved_.begin(), column_halved_.end(), 1));
    std::fill(column_halved_.begin(), column_halved_.end(), 0);
    out_.stats.halved_columns += ls.halved_columns;
    ls.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - layer_start).count();
    if (ls.boundary_layer) out_.stats.bl_seconds += ls.seconds;
    out_.stats.per_layer.push_back(ls);
  }
  smooth_interior(opt_.interior_smoothing_passes);
  Status st = finish();
  out_.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return st;
}

Status LayerBuilder::finish() {
  auto& st = out_.stats;
  st.tets = mesh_.num_tet_slots();
  st.fit_tests = fit_.tests;
  st.fit_candidates = fit_.candidates;
  st.tri_tests = fit_.tri_tests;
  out_.vertex_origin.resize(mesh_.num_vertices(), TetMesh::kNone);
  st.halving_loops = st.face_halvings + st.push_halvings;
  const size_t column_layers = s_.num_triangles() * st.per_layer.size();
  st.halved_column_share = column_layers ? double(st.halved_columns) / double(column_layers) : 0.0;
  st.bl_layers = bl_layers_;
  st.bl_reduced_vertices =
      size_t(std::count(bl_reduced_root_.begin(), bl_reduced_root_.end(), 1));
  st.bl_reduced_share =
      st.bl_wall_vertices ? double(st.bl_reduced_vertices) / double(st.bl_wall_vertices) : 0.0;
  out_.front_tri.reserve(3 * front_.num_alive());
  for (uint32_t f = 0; f < front_.num_slots(); ++f) {
    if (!front_.alive(f)) continue;
    const uint32_t* t = front_.tri(f);
    const uint32_t owner = front_.owner(f);
    if (owner == Front::kNone)
      return Status(Error::Internal, "layers: input triangle (" + std::to_string(t[0]) + ", " +
                                         std::to_string(t[1]) + ", " + std::to_string(t[2]) +
                                         ") is still on the front");
    int facet = -1;
    for (int i = 0; i < 4 && facet < 0; ++i) {
      const uint32_t q[3] = {mesh_.vertex(owner, kFacetVertex[i][0]),
                             mesh_.vertex(owner, kFacetVertex[i][1]),
                             mesh_.vertex(owner, kFacetVertex[i][2])};
      for (int r = 0; r < 3; ++r)
        if (q[r] == t[0] && q[(r + 1) % 3] == t[1] && q[(r + 2) % 3] == t[2]) facet = i;
    }
    if (facet < 0) return Status(Error::Internal, "layers: a front triangle lost its tet");
    out_.front_tri.insert(out_.front_tri.end(), t, t + 3);
    out_.front_tet.push_back(owner);
    out_.front_facet.push_back(uint8_t(facet));
    for (int k = 0; k < 3; ++k) mesh_.vflags[t[k]] |= vflag::kOnFront;
  }
  return mesh_.build_adjacency();
}

}  // namespace anitet::layers

namespace anitet {

Result<LayersOutput> build_layers(const SurfaceMesh& surface, const SizingField& sizing,
                                  const LayersOptions& options) {
  if (options.layers < 1)
    return Result<LayersOutput>(Error::InvalidArgument, "layers: options.layers must be >= 1");
  if (!(options.face_height > 0.0) || !(options.push_height > 0.0) || options.max_halvings < 0 ||
      options.max_halvings > 200 || !(options.shrink > 0.0 && options.shrink < 1.0) ||
      !(options.keep_margin >= 0.0 && options.keep_margin < 1.0) || options.smoothing_passes < 0)
    return Result<LayersOutput>(Error::InvalidArgument,
                                "layers: heights must be > 0, max_halvings in [0, 200], shrink in "
                                "(0, 1), keep_margin in [0, 1), smoothing_passes >= 0");
  const BoundaryLayerOptions& bl = options.boundary_layer;
  if (bl.enabled() &&
      (!(bl.first_height > 0.0) || !(bl.growth >= 1.0) || bl.layers < 0 || bl.layers > 1000 ||
       (bl.layers == 0 && !(bl.total_thickness > 0.0)) || bl.normal_smoothing < 0 ||
       !(bl.grazing_margin > 0.0 && bl.grazing_margin <= 1.0) || !(bl.gradation >= 1.0) ||
       !(bl.gap_share > 0.0 && bl.gap_share < 0.5)))
    return Result<LayersOutput>(Error::InvalidArgument,
                                "layers: boundary layer: first_height > 0, growth >= 1, layers in "
                                "[1, 1000] or total_thickness > 0, grazing_margin in (0, 1], "
                                "gradation >= 1, gap_share in (0, 0.5)");
  if (!(options.height_gradation > 0.0) || options.improve_passes < 0 ||
      !(options.min_height_fraction > 0.0 && options.min_height_fraction <= 1.0))
    return Result<LayersOutput>(Error::InvalidArgument,
                                "layers: height_gradation > 0, min_height_fraction in (0, 1]");
  Status st = layers::check_input(surface);
  if (!st.ok()) return st;
  LayersOutput out;
  layers::LayerBuilder builder(surface, sizing, options, out);
  st = builder.run();
  if (!st.ok()) return st;
  return out;
}

SurfaceMesh front_surface(const LayersOutput& out, std::vector<uint32_t>* vertex_map) {
  SurfaceMesh s;
  std::vector<uint32_t> local(out.mesh.num_vertices(), TetMesh::kNone);
  for (uint32_t v : out.front_tri) local[v] = 0;
  std::vector<uint32_t> map;
  for (uint32_t v = 0; v < local.size(); ++v) {
    if (local[v] == TetMesh::kNone) continue;
    local[v] = static_cast<uint32_t>(map.size());
    map.push_back(v);
    const double* p = out.mesh.point(v);
    s.add_vertex(p[0], p[1], p[2]);
  }
  for (size_t i = 0; i < out.num_front_triangles(); ++i)
    s.add_triangle(local[out.front_tri[3 * i]], local[out.front_tri[3 * i + 1]],
                   local[out.front_tri[3 * i + 2]]);
  if (vertex_map) *vertex_map = std::move(map);
  return s;
}

}  // namespace anitet
