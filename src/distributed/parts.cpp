#include "distributed/parts.hpp"

#include <algorithm>
#include <climits>
#include <cstring>
#include <string>

#include "core/bvh.hpp"
#include "delaunay/spatial_sort.hpp"
#include "distributed/bytes.hpp"
#include "refine/mesh_ops.hpp"

namespace anitet::distributed {

namespace {

bool live(const TetMesh& m, uint32_t t) { return !m.is_deleted(t) && !m.is_ghost(t); }

std::array<uint32_t, 3> sorted_facet(uint32_t a, uint32_t b, uint32_t c) {
  std::array<uint32_t, 3> f = {a, b, c};
  std::sort(f.begin(), f.end());
  return f;
}

}  // namespace

size_t count_boundary_facets(const TetMesh& m) {
  size_t n = 0;
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t)
    if (live(m, t))
      for (int i = 0; i < 4; ++i) n += m.tet_adj[4 * size_t(t) + i] == TetMesh::kNoNeighbour ? 1 : 0;
  return n;
}

namespace {

void write_mesh(Writer& w, const TetMesh& m) {
  w.array(m.xyz);
  w.array(m.vflags);
  w.array(m.tet_v);
  w.array(m.tet_flags);
  w.array(m.tet_region);
}

// The adjacency is not sent: rebuilt when asked (the mesh holds no deleted or ghost slots), else
// every facet says kNoNeighbour.
Status read_mesh(Reader& r, TetMesh& m, bool with_adjacency) {
  if (!r.array(m.xyz) || !r.array(m.vflags) || !r.array(m.tet_v) || !r.array(m.tet_flags) || !r.array(m.tet_region))
    return Status(Error::Parse, "distributed: a truncated mesh message");
  const size_t nt = m.tet_v.size() / 4;
  if (m.xyz.size() % 3 || m.vflags.size() != m.xyz.size() / 3 || m.tet_v.size() % 4 ||
      m.tet_flags.size() != nt || m.tet_region.size() != nt)
    return Status(Error::Parse, "distributed: a mesh message with arrays that do not agree");
  for (uint32_t v : m.tet_v)
    if (v >= m.num_vertices()) return Status(Error::Parse, "distributed: a mesh message with a vertex out of range");
  m.tet_adj.assign(m.tet_v.size(), TetMesh::kNoNeighbour);
  m.free_tets.clear();
  return with_adjacency ? m.build_adjacency() : Status::success();
}

// A compact copy of the live non-ghost tets (vertex ids kept), for a message.
TetMesh compact(const TetMesh& m) {
  TetMesh c;
  c.xyz = m.xyz;
  c.vflags = m.vflags;
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
    if (!live(m, t)) continue;
    c.tet_v.insert(c.tet_v.end(), &m.tet_v[4 * size_t(t)], &m.tet_v[4 * size_t(t)] + 4);
    c.tet_flags.push_back(m.tet_flags[t] & uint16_t(kKeptFlags));
    c.tet_region.push_back(m.tet_region[t]);
  }
  return c;
}

// The counts a part's message carries (passes and the anisotropic flag besides).
constexpr size_t RefineStats::*kRefineCounts[] = {&RefineStats::splits,           &RefineStats::split_rejected,
                                                  &RefineStats::parallel_splits, &RefineStats::collapses,
                                                  &RefineStats::collapse_rejected, &RefineStats::metric_flips};
constexpr size_t OptimizeStats::*kOptimizeCounts[] = {
    &OptimizeStats::moves,        &OptimizeStats::moves_rejected, &OptimizeStats::flips23,
    &OptimizeStats::edge_removals, &OptimizeStats::perturbations, &OptimizeStats::collapses,
    &OptimizeStats::flat_found,   &OptimizeStats::flat_left};

void write_stats(Writer& w, const RefineStats& r, const OptimizeStats& o) {
  for (auto count : kRefineCounts) w.value<uint64_t>(r.*count);
  for (auto count : kOptimizeCounts) w.value<uint64_t>(o.*count);
  w.value<int32_t>(r.passes);
  w.value<uint8_t>(o.anisotropic ? 1 : 0);
  w.value(r.seconds);
  w.value(o.seconds);
}

bool read_stats(Reader& rd, RefineStats& r, OptimizeStats& o) {
  uint64_t v = 0;
  for (auto count : kRefineCounts) {
    if (!rd.value(v)) return false;
    r.*count = v;
  }
  for (auto count : kOptimizeCounts) {
    if (!rd.value(v)) return false;
    o.*count = v;
  }
  uint8_t anisotropic = 0;
  if (!rd.value(r.passes) || !rd.value(anisotropic)) return false;
  o.anisotropic = anisotropic != 0;
  return rd.value(r.seconds) && rd.value(o.seconds);
}

}  // namespace

std::vector<int32_t> hilbert_parts(const TetMesh& mesh, int parts, double shift) {
  const auto slots = static_cast<uint32_t>(mesh.num_tet_slots());
  std::vector<int32_t> part_of(slots, -1);
  std::vector<uint32_t> tets;
  std::vector<double> centroid;
  for (uint32_t t = 0; t < slots; ++t) {
    if (!live(mesh, t)) continue;
    for (int k = 0; k < 3; ++k) {
      double s = 0.0;
      for (int i = 0; i < 4; ++i) s += mesh.point(mesh.vertex(t, i))[k];
      centroid.push_back(0.25 * s);
    }
    tets.push_back(t);
  }
  if (tets.empty() || parts < 1) return part_of;
  std::vector<uint32_t> order(tets.size());
  for (uint32_t k = 0; k < order.size(); ++k) order[k] = k;
  const Box3 box = bounding_box(centroid.data(), tets.size());
  delaunay_detail::hilbert_sort(centroid.data(), order.data(), order.size(), box.lo, box.hi);
  const auto offset = static_cast<size_t>(shift * double(order.size()) / double(parts));
  for (size_t k = 0; k < order.size(); ++k)
    part_of[tets[order[(k + offset) % order.size()]]] = static_cast<int32_t>(k * size_t(parts) / order.size());
  return part_of;
}

std::vector<int32_t> move_interfaces(const TetMesh& mesh, const std::vector<int32_t>& part_of, int rings,
                                     int zone) {
  const auto slots = static_cast<uint32_t>(part_of.size());
  std::vector<int32_t> tet_part(slots, -1);
  for (uint32_t t = 0; t < slots; ++t)
    if (part_of[t] != -1) tet_part[t] = part_of_label(part_of[t]);
  // The old interfaces: vertices whose tets are in more than one part.
  const size_t nv = mesh.num_vertices();
  std::vector<int32_t> lo(nv, INT32_MAX), hi(nv, -1);
  for (uint32_t t = 0; t < slots; ++t)
    if (tet_part[t] >= 0)
      for (int i = 0; i < 4; ++i) {
        const uint32_t v = mesh.vertex(t, i);
        lo[v] = std::min(lo[v], tet_part[t]);
        hi[v] = std::max(hi[v], tet_part[t]);
      }
  std::vector<int32_t> vertex_part(nv);
  for (int ring = 0; ring < rings; ++ring) {
    std::fill(vertex_part.begin(), vertex_part.end(), INT32_MAX);
    for (uint32_t t = 0; t < slots; ++t)
      if (tet_part[t] >= 0)
        for (int i = 0; i < 4; ++i) {
          int32_t& vp = vertex_part[mesh.vertex(t, i)];
          vp = std::min(vp, tet_part[t]);
        }
    for (uint32_t t = 0; t < slots; ++t)
      if (tet_part[t] >= 0)
        for (int i = 0; i < 4; ++i) tet_part[t] = std::min(tet_part[t], vertex_part[mesh.vertex(t, i)]);
  }
  if (zone <= 0) return tet_part;
  // The zone: `zone` rings of tets around the old interface vertices.
  std::vector<uint8_t> near(nv, 0), in_zone(slots, 0);
  for (size_t v = 0; v < nv; ++v) near[v] = hi[v] >= 0 && lo[v] != hi[v];
  for (int ring = 0; ring < zone; ++ring) {
    for (uint32_t t = 0; t < slots; ++t)
      if (tet_part[t] >= 0 && !in_zone[t])
        for (int i = 0; i < 4 && !in_zone[t]; ++i) in_zone[t] = near[mesh.vertex(t, i)];
    for (uint32_t t = 0; t < slots; ++t)
      if (in_zone[t])
        for (int i = 0; i < 4; ++i) near[mesh.vertex(t, i)] = 1;
  }
  for (uint32_t t = 0; t < slots; ++t)
    if (tet_part[t] >= 0 && !in_zone[t]) tet_part[t] = kept(part_of_label(part_of[t]));
  return tet_part;
}

Status check_meshable_in_parts(const TetMesh& mesh) {
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t)
    if (!mesh.is_deleted(t) && mesh.is_ghost(t))
      return Status(Error::InvalidArgument, "distributed: the mesh has ghost tets");
  return Status::success();
}

std::vector<double> vertex_metrics(const TetMesh& mesh, const SizingField& field, double scale) {
  const ScaledSizing scaled(field, scale);
  std::vector<double> metrics(6 * mesh.num_vertices());
  for (uint32_t v = 0; v < mesh.num_vertices(); ++v) scaled.metric(mesh.point(v), &metrics[6 * size_t(v)]);
  return metrics;
}

Status run_steps_and_cycles(const PartsOptions& options, bool anisotropic, const double& refined_in_range,
                            const OptimizeStats& optimize, const std::function<Status(Step)>& steps) {
  for (Step step : {Step::kRefine, Step::kOptimize})
    if (Status st = steps(step); !st.ok()) return st;
  if (options.cycles_run) *options.cycles_run = 0;
  for (int c = 0; anisotropic && c < options.anisotropic_cycles; ++c) {
    if (options.cycle_optimizer_gain > 0.0 &&
        optimize.length_in_range_after < optimize.length_in_range_before + options.cycle_optimizer_gain)
      break;
    const double before = refined_in_range;
    for (Step step : {Step::kRefine, Step::kOptimize})
      if (Status st = steps(step); !st.ok()) return st;
    if (options.cycles_run) ++*options.cycles_run;
    if (refined_in_range < before + options.cycle_gain) break;
  }
  return Status::success();
}

Result<MeshPart> extract_part(const TetMesh& whole, const std::vector<int32_t>& part_of, int32_t p) {
  const size_t nv = whole.num_vertices();
  const auto slots = static_cast<uint32_t>(whole.num_tet_slots());
  // Vertices of own tets; then the halo: the other tets with one of them.
  std::vector<uint8_t> mark(nv, 0);  // 1: own tets have it, 2: also a halo tet
  for (uint32_t t = 0; t < slots; ++t)
    if (part_of[t] == p)
      for (int i = 0; i < 4; ++i) mark[whole.vertex(t, i)] = 1;
  std::vector<uint32_t> own, halo;
  for (uint32_t t = 0; t < slots; ++t) {
    if (part_of[t] == -1) continue;
    if (part_of[t] == p) {
      own.push_back(t);
      continue;
    }
    bool touches = false;
    for (int i = 0; i < 4; ++i) touches |= mark[whole.vertex(t, i)] != 0;
    if (touches) halo.push_back(t);
  }
  for (uint32_t t : halo)
    for (int i = 0; i < 4; ++i) mark[whole.vertex(t, i)] = 2;

  MeshPart part;
  std::vector<uint32_t> local(nv, TetMesh::kNone);
  TetMesh& m = part.mesh;
  for (uint32_t v = 0; v < nv; ++v) {
    if (!mark[v]) continue;
    local[v] = static_cast<uint32_t>(part.global_of.size());
    part.global_of.push_back(v);
    part.frozen.push_back(mark[v] == 2);
    m.add_vertex(whole.point(v), uint8_t(whole.vflags[v] | (mark[v] == 2 ? vflag::kLocked : 0)));
  }
  auto add = [&](uint32_t t, bool is_halo) {
    const uint32_t n = m.new_tet(local[whole.vertex(t, 0)], local[whole.vertex(t, 1)], local[whole.vertex(t, 2)],
                                 local[whole.vertex(t, 3)], is_halo ? -1 - whole.tet_region[t] : whole.tet_region[t]);
    m.tet_flags[n] = uint16_t(whole.tet_flags[t] & kKeptFlags) | (is_halo ? tflag::kFacetProtectedMask : 0);
  };
  for (uint32_t t : own) add(t, false);
  for (uint32_t t : halo) add(t, true);
  if (Status st = m.build_adjacency(); !st.ok())
    return Status(Error::Internal, "distributed: part " + std::to_string(p) + ": " + st.message());
  // Own facets against the halo: protected on the own side too (the flags agree on both sides).
  for (uint32_t t = 0; t < own.size(); ++t)
    for (int i = 0; i < 4; ++i) {
      if (m.tet_adj[4 * size_t(t) + i] == TetMesh::kNoNeighbour || m.neighbour(t, i) < own.size() ||
          m.facet_protected(t, i))
        continue;
      m.set_facet_protected(t, i, true);
      const int* f = kFacetVertex[i];
      part.interface_facets.push_back(sorted_facet(part.global_of[m.vertex(t, f[0])], part.global_of[m.vertex(t, f[1])],
                                                   part.global_of[m.vertex(t, f[2])]));
    }
  return part;
}

Status mesh_part(MeshPart& part, Step step, const SizingField& field, const RefineOptions& refine,
                 const OptimizeOptions& optimize) {
  if (step == Step::kRefine) {
    RefineOptions options = refine;
    options.defer_at_frozen = true;
    Result<RefineStats> r = refine_mesh(part.mesh, field, options);
    if (!r.ok()) return Status(r.status().code(), "stage 3b (refinement of a part): " + r.status().message());
    order_for_locality(part.mesh, static_cast<uint32_t>(part.global_of.size()));
    part.refine = r.value();
    return Status::success();
  }
  const ScaledSizing scaled(field, refine.size_scale > 0.0 ? refine.size_scale : 1.0);
  Result<OptimizeStats> o = optimize_mesh(part.mesh, scaled, optimize);
  if (!o.ok()) return Status(o.status().code(), "stage 3c (optimization of a part): " + o.status().message());
  part.optimize = o.value();
  return Status::success();
}

Result<TetMesh> merge_parts(const TetMesh& whole, const std::vector<int32_t>& part_of,
                            const std::vector<MeshPart>& parts, size_t boundary_facets,
                            std::vector<int32_t>* tet_part) {
  TetMesh merged;
  merged.xyz = whole.xyz;
  merged.vflags = whole.vflags;
  if (tet_part) tet_part->clear();
  for (uint32_t t = 0; t < whole.num_tet_slots() && t < part_of.size(); ++t) {
    if (part_of[t] > -2 || !live(whole, t)) continue;
    const uint32_t* v = &whole.tet_v[4 * size_t(t)];
    const uint32_t n = merged.new_tet(v[0], v[1], v[2], v[3], whole.tet_region[t]);
    merged.tet_flags[n] = whole.tet_flags[t] & uint16_t(kKeptFlags);
    if (tet_part) tet_part->push_back(part_of_label(part_of[t]));
  }
  std::vector<std::array<uint32_t, 3>> interface;
  for (size_t p = 0; p < parts.size(); ++p) {
    const MeshPart& part = parts[p];
    const TetMesh& m = part.mesh;
    const size_t first = part.global_of.size();
    if (m.num_vertices() < first || part.frozen.size() != first)
      return Status(Error::Internal, "distributed: part " + std::to_string(p) + " lost vertices");
    const auto offset = static_cast<uint32_t>(merged.num_vertices());
    for (size_t l = 0; l < first; ++l)
      if (!part.frozen[l]) std::copy_n(m.point(uint32_t(l)), 3, &merged.xyz[3 * size_t(part.global_of[l])]);
    for (size_t l = first; l < m.num_vertices(); ++l) merged.add_vertex(m.point(uint32_t(l)), m.vflags[l]);
    auto global = [&](uint32_t l) { return l < first ? part.global_of[l] : offset + (l - uint32_t(first)); };
    for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
      if (!live(m, t) || m.tet_region[t] < 0) continue;
      const uint32_t n = merged.new_tet(global(m.vertex(t, 0)), global(m.vertex(t, 1)), global(m.vertex(t, 2)),
                                        global(m.vertex(t, 3)), m.tet_region[t]);
      merged.tet_flags[n] = m.tet_flags[t] & uint16_t(kKeptFlags);
      if (tet_part) tet_part->push_back(static_cast<int32_t>(p));
    }
    interface.insert(interface.end(), part.interface_facets.begin(), part.interface_facets.end());
  }
  if (Status st = merged.build_adjacency(); !st.ok())
    return Status(Error::Internal, "distributed: the parts overlap: " + st.message());
  // A gap or an overlap between parts leaves facets without a partner that the whole had not.
  if (const size_t b = count_boundary_facets(merged); b != boundary_facets)
    return Status(Error::Internal, "distributed: the merged parts have " + std::to_string(b) +
                                       " boundary facets, the mesh they came from " + std::to_string(boundary_facets));
  std::sort(interface.begin(), interface.end());
  for (uint32_t t = 0; t < merged.num_tet_slots(); ++t)
    for (int i = 0; i < 4; ++i) {
      if (!merged.facet_protected(t, i)) continue;
      const int* f = kFacetVertex[i];
      if (std::binary_search(interface.begin(), interface.end(),
                             sorted_facet(merged.vertex(t, f[0]), merged.vertex(t, f[1]), merged.vertex(t, f[2]))))
        merged.set_facet_protected(t, i, false);
    }
  return merged;
}

std::vector<uint8_t> serialize_part(const MeshPart& part) {
  Writer w;
  write_mesh(w, compact(part.mesh));
  w.array(part.global_of);
  w.array(part.frozen);
  w.array(part.interface_facets);
  write_stats(w, part.refine, part.optimize);
  return std::move(w.bytes);
}

Result<MeshPart> deserialize_part(const std::vector<uint8_t>& bytes) {
  Reader r(bytes);
  MeshPart part;
  if (Status st = read_mesh(r, part.mesh, false); !st.ok()) return st;
  if (!r.array(part.global_of) || !r.array(part.frozen) || !r.array(part.interface_facets) ||
      !read_stats(r, part.refine, part.optimize) || !r.done())
    return Status(Error::Parse, "distributed: a truncated part message");
  return part;
}

std::vector<uint8_t> serialize_mesh(const TetMesh& mesh, const std::vector<int32_t>& tet_part) {
  Writer w;
  write_mesh(w, compact(mesh));
  w.array(tet_part);
  return std::move(w.bytes);
}

Result<TetMesh> deserialize_mesh(const std::vector<uint8_t>& bytes, std::vector<int32_t>& tet_part,
                                 bool with_adjacency) {
  Reader r(bytes);
  TetMesh mesh;
  if (Status st = read_mesh(r, mesh, with_adjacency); !st.ok()) return st;
  if (!r.array(tet_part) || !r.done() || (!tet_part.empty() && tet_part.size() != mesh.num_tet_slots()))
    return Status(Error::Parse, "distributed: a truncated mesh message");
  return mesh;
}

void add_counts(const MeshPart& part, RefineStats& refine, OptimizeStats& optimize) {
  for (auto count : kRefineCounts) refine.*count += part.refine.*count;
  for (auto count : kOptimizeCounts) optimize.*count += part.optimize.*count;
  refine.passes = std::max(refine.passes, part.refine.passes);
  refine.seconds = std::max(refine.seconds, part.refine.seconds);
  optimize.anisotropic |= part.optimize.anisotropic;
  optimize.seconds = std::max(optimize.seconds, part.optimize.seconds);
}

}  // namespace anitet::distributed
