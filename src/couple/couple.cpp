#include "couple/couple.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <sstream>
#include <unordered_map>

#include "predicates/predicates.hpp"

namespace anitet {

namespace {

using Tri = std::array<uint32_t, 3>;

struct TriHash {
  size_t operator()(const Tri& t) const {
    uint64_t h = t[0];
    h = h * 0x9E3779B97F4A7C15ull ^ t[1];
    h = h * 0x9E3779B97F4A7C15ull ^ t[2];
    return static_cast<size_t>(h ^ (h >> 31));
  }
};

Tri sorted(Tri t) {
  std::sort(t.begin(), t.end());
  return t;
}

std::string point_text(const TetMesh& m, uint32_t v) {
  std::ostringstream s;
  s.precision(17);
  const double* p = m.point(v);
  s << "vertex " << v << " (" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return s.str();
}

// A piece of an S1 face in T1: a triangle (oriented like the face) and the T1 tet that has it.
struct Piece {
  Tri tri;
  uint32_t face;  // the S1 face it lies in
  uint32_t tet;
};

class Coupler {
 public:
  Coupler(const SurfaceMesh& surface, LayersOutput& t1, const std::vector<uint32_t>& s1_map,
          const RecoveryOutput& t2)
      : surface_(surface), t1_(t1), mesh_(t1.mesh), s1_map_(s1_map), t2_(t2) {}

  Status run(CoupleStats& stats);

 private:
  Status map_t2_vertices();
  Status split_s1_edges(CoupleStats& stats);
  Status split_edge(uint32_t a, uint32_t b, uint32_t m, CoupleStats& stats);
  Status recone_s1_faces(CoupleStats& stats);
  Status add_t2_tets(CoupleStats& stats);
  Status finish_boundary_and_regions();
  bool positive(uint32_t t) const {
    const uint32_t* v = &mesh_.tet_v[4 * size_t(t)];
    return predicates::orient3d(mesh_.point(v[0]), mesh_.point(v[1]), mesh_.point(v[2]), mesh_.point(v[3])) > 0;
  }
  void add_incidence(uint32_t t) {
    for (int i = 0; i < 4; ++i) vtets_[mesh_.vertex(t, i)].push_back(t);
  }

  const SurfaceMesh& surface_;
  LayersOutput& t1_;
  TetMesh& mesh_;
  const std::vector<uint32_t>& s1_map_;
  const RecoveryOutput& t2_;

  std::vector<uint32_t> t2_to_mesh_;               // T2 vertex id -> coupled mesh id
  std::vector<uint32_t> apex_;                     // per S1 face: the apex of its T1 tet
  std::vector<Piece> pieces_;                      // S1 face pieces present in T1
  std::unordered_map<Tri, uint32_t, TriHash> piece_of_;  // sorted triangle -> index in pieces_
  std::vector<std::vector<uint32_t>> vtets_;       // tets around each vertex (edge splits only)
  int32_t bodies_ = 0;
  size_t bl_tets_ = 0;
};

Status Coupler::map_t2_vertices() {
  const size_t n_s1 = s1_map_.size();
  if (t2_.mesh.num_vertices() < n_s1)
    return Status(Error::Internal, "coupling: stage 2's mesh has fewer vertices than S1");
  t2_to_mesh_.resize(t2_.mesh.num_vertices());
  for (size_t i = 0; i < n_s1; ++i) {
    const double* a = t2_.mesh.point(static_cast<uint32_t>(i));
    const double* b = mesh_.point(s1_map_[i]);
    if (a[0] != b[0] || a[1] != b[1] || a[2] != b[2])
      return Status(Error::Internal, "coupling: S1 vertex " + std::to_string(i) + " moved in stage 2");
    t2_to_mesh_[i] = s1_map_[i];
  }
  for (size_t i = n_s1; i < t2_.mesh.num_vertices(); ++i)
    t2_to_mesh_[i] = mesh_.add_vertex(t2_.mesh.point(static_cast<uint32_t>(i)), vflag::kOnFront);
  return Status::success();
}

Status Coupler::split_edge(uint32_t a, uint32_t b, uint32_t m, CoupleStats& stats) {
  // The tets around edge ab (all on the T1 side of S1).
  std::vector<uint32_t> around;
  for (uint32_t t : vtets_[a]) {
    if (mesh_.is_deleted(t)) continue;
    for (int i = 0; i < 4; ++i)
      if (mesh_.vertex(t, i) == b) around.push_back(t);
  }
  if (around.empty())
    return Status(Error::Internal, "coupling: S1 edge (" + std::to_string(a) + ", " + std::to_string(b) +
                                       ") has no T1 tet");
  for (uint32_t t : around) {
    uint32_t v[4];
    std::copy_n(&mesh_.tet_v[4 * size_t(t)], 4, v);
    const int ia = int(std::find(v, v + 4, a) - v), ib = int(std::find(v, v + 4, b) - v);
    // t keeps a (b becomes m); the new tet keeps b (a becomes m).
    uint32_t w[4] = {v[0], v[1], v[2], v[3]};
    w[ia] = m;
    const uint32_t tb = mesh_.new_tet(w[0], w[1], w[2], w[3], mesh_.tet_region[t]);
    mesh_.tet_v[4 * size_t(t) + ib] = m;
    if (!positive(t) || !positive(tb))
      return Status(Error::Internal, "coupling: Steiner " + point_text(mesh_, m) + " on S1 edge (" +
                                         std::to_string(a) + ", " + std::to_string(b) +
                                         ") would make a T1 tet non-positive");
    auto& vb = vtets_[b];
    vb.erase(std::find(vb.begin(), vb.end(), t));
    add_incidence(tb);
    vtets_[m].push_back(t);
    ++stats.edge_split_tets;
    // The S1 pieces of t that contain ab split in two, each kept by the half that has it.
    for (int k = 0; k < 4; ++k) {
      if (k == ia || k == ib) continue;
      auto it = piece_of_.find(sorted({a, b, v[k]}));
      if (it == piece_of_.end()) continue;
      const uint32_t p = it->second;
      piece_of_.erase(it);
      Piece half_a = pieces_[p], half_b = pieces_[p];
      for (uint32_t& x : half_a.tri) x = (x == b) ? m : x;
      for (uint32_t& x : half_b.tri) x = (x == a) ? m : x;
      half_a.tet = t;
      half_b.tet = tb;
      pieces_[p] = half_a;
      piece_of_[sorted(half_a.tri)] = p;
      piece_of_[sorted(half_b.tri)] = static_cast<uint32_t>(pieces_.size());
      pieces_.push_back(half_b);
    }
  }
  return Status::success();
}

Status Coupler::split_s1_edges(CoupleStats& stats) {
  // Steiner points per S1 edge, ordered along it.
  std::unordered_map<uint32_t, std::vector<std::pair<double, uint32_t>>> on_edge;
  for (const SteinerPoint& s : t2_.steiner) {
    if (s.host == SteinerHost::kFace) {
      ++stats.face_steiner_points;
      continue;
    }
    ++stats.edge_steiner_points;
    const uint32_t a = t2_to_mesh_[t2_.input_edges[2 * size_t(s.host_id)]];
    const uint32_t b = t2_to_mesh_[t2_.input_edges[2 * size_t(s.host_id) + 1]];
    const double* pa = mesh_.point(a);
    const double* pb = mesh_.point(b);
    const double* pm = mesh_.point(t2_to_mesh_[s.vertex]);
    double num = 0, den = 0;
    for (int k = 0; k < 3; ++k) {
      num += (pm[k] - pa[k]) * (pb[k] - pa[k]);
      den += (pb[k] - pa[k]) * (pb[k] - pa[k]);
    }
    on_edge[s.host_id].push_back({num / den, t2_to_mesh_[s.vertex]});
  }
  if (on_edge.empty()) return Status::success();

  vtets_.assign(mesh_.num_vertices(), {});
  for (uint32_t t = 0; t < mesh_.num_tet_slots(); ++t)
    if (!mesh_.is_deleted(t)) add_incidence(t);
  // A fixed order (by edge id) keeps the result the same run after run.
  std::vector<uint32_t> edges;
  for (const auto& e : on_edge) edges.push_back(e.first);
  std::sort(edges.begin(), edges.end());
  for (uint32_t e : edges) {
    auto& points = on_edge[e];
    std::sort(points.begin(), points.end());
    uint32_t from = t2_to_mesh_[t2_.input_edges[2 * size_t(e)]];
    const uint32_t to = t2_to_mesh_[t2_.input_edges[2 * size_t(e) + 1]];
    for (const auto& [param, m] : points) {
      (void)param;
      if (Status st = split_edge(from, to, m, stats); !st.ok()) return st;
      from = m;
    }
  }
  vtets_.clear();
  vtets_.shrink_to_fit();
  return Status::success();
}

Status Coupler::recone_s1_faces(CoupleStats& stats) {
  std::vector<std::vector<Tri>> subfaces(t1_.num_front_triangles());
  for (size_t i = 0; i < t2_.s2_face.size(); ++i) {
    const uint32_t f = t2_.s2_face[i];
    if (f >= subfaces.size()) return Status(Error::Internal, "coupling: S2 subface names no S1 face");
    subfaces[f].push_back({t2_to_mesh_[t2_.s2_tri[3 * i]], t2_to_mesh_[t2_.s2_tri[3 * i + 1]],
                           t2_to_mesh_[t2_.s2_tri[3 * i + 2]]});
  }
  std::vector<std::vector<uint32_t>> pieces_of_face(subfaces.size());
  for (uint32_t p = 0; p < pieces_.size(); ++p) pieces_of_face[pieces_[p].face].push_back(p);

  std::vector<char> tet_reconed(mesh_.num_tet_slots(), 0);
  for (uint32_t f = 0; f < subfaces.size(); ++f) {
    auto& subs = subfaces[f];
    if (subs.empty()) return Status(Error::Internal, "coupling: S1 face " + std::to_string(f) + " has no S2 subface");
    // Nothing to do when T1 already has exactly F's S2 subfaces.
    bool same = pieces_of_face[f].size() == subs.size();
    for (size_t i = 0; same && i < subs.size(); ++i) {
      auto it = piece_of_.find(sorted(subs[i]));
      same = it != piece_of_.end() && pieces_[it->second].face == f;
    }
    if (same) continue;
    ++stats.faces_reconed;
    const uint32_t v = apex_[f];
    for (uint32_t p : pieces_of_face[f]) {
      const uint32_t t = pieces_[p].tet;
      if (t >= tet_reconed.size() || tet_reconed[t] || mesh_.is_deleted(t))
        return Status(Error::NotImplemented,
                      "coupling: T1 tet " + std::to_string(t) + " has pieces of two split S1 faces");
      const Tri& tri = pieces_[p].tri;
      bool cone = false;
      for (int i = 0; i < 4 && !cone; ++i)
        cone = mesh_.vertex(t, i) == v;
      for (uint32_t x : tri) cone = cone && std::find(&mesh_.tet_v[4 * size_t(t)], &mesh_.tet_v[4 * size_t(t)] + 4, x) !=
                                                &mesh_.tet_v[4 * size_t(t)] + 4;
      if (!cone)
        return Status(Error::NotImplemented, "coupling: T1 tet " + std::to_string(t) + " on S1 face " +
                                                 std::to_string(f) + " is not the cone from its apex (an edge "
                                                 "of it incident to the apex was split)");
      tet_reconed[t] = 1;
      mesh_.delete_tet(t);
    }
    for (const Tri& s : subs) {
      const uint32_t t = mesh_.new_tet(s[0], s[1], s[2], v, 0);
      if (t >= tet_reconed.size()) tet_reconed.resize(t + 1, 0);
      tet_reconed[t] = 1;
      if (!positive(t))
        return Status(Error::Internal, "coupling: the cone from T1 apex " + point_text(mesh_, v) +
                                           " over a subface of S1 face " + std::to_string(f) +
                                           " is not positive");
    }
  }
  return Status::success();
}

Status Coupler::add_t2_tets(CoupleStats& stats) {
  const TetMesh& m2 = t2_.mesh;
  for (uint32_t t = 0; t < m2.num_tet_slots(); ++t) {
    if (m2.is_deleted(t) || m2.is_ghost(t)) continue;
    mesh_.new_tet(t2_to_mesh_[m2.vertex(t, 0)], t2_to_mesh_[m2.vertex(t, 1)], t2_to_mesh_[m2.vertex(t, 2)],
                  t2_to_mesh_[m2.vertex(t, 3)], 0);
    ++stats.t2_tets;
  }
  return Status::success();
}

Status Coupler::finish_boundary_and_regions() {
  if (Status st = mesh_.build_adjacency(); !st.ok())
    return Status(Error::Internal, "coupling: T1' and T2 do not fit: " + st.message());
  // The facets without neighbour must be exactly S's triangles: anything else is a gap
  // between T1' and T2.
  std::unordered_map<Tri, uint32_t, TriHash> input_tri;
  input_tri.reserve(2 * surface_.num_triangles());
  for (uint32_t i = 0; i < surface_.num_triangles(); ++i)
    input_tri.emplace(sorted({surface_.tri[3 * i], surface_.tri[3 * i + 1], surface_.tri[3 * i + 2]}), i);
  size_t open = 0;
  const size_t nt = mesh_.num_tet_slots();
  std::vector<uint32_t> region_key(nt, TetMesh::kNone);  // smallest input triangle of each tet
  for (uint32_t t = 0; t < nt; ++t) {
    if (mesh_.is_deleted(t)) continue;
    for (int i = 0; i < 4; ++i) {
      if (mesh_.tet_adj[4 * size_t(t) + i] != TetMesh::kNoNeighbour) continue;
      ++open;
      const Tri f = {mesh_.vertex(t, kFacetVertex[i][0]), mesh_.vertex(t, kFacetVertex[i][1]),
                     mesh_.vertex(t, kFacetVertex[i][2])};
      auto it = input_tri.find(sorted(f));
      if (it == input_tri.end())
        return Status(Error::Internal, "coupling: facet (" + std::to_string(f[0]) + ", " + std::to_string(f[1]) +
                                           ", " + std::to_string(f[2]) +
                                           ") of the coupled mesh has one tet but is not on S");
      mesh_.set_facet_protected(t, i, true);
      region_key[t] = std::min(region_key[t], it->second);
    }
  }
  if (open != surface_.num_triangles())
    return Status(Error::Internal, "coupling: " + std::to_string(open) + " boundary facets for " +
                                       std::to_string(surface_.num_triangles()) + " input triangles");
  // Regions: connected bodies (through facets not on S), numbered by their smallest input triangle.
  std::vector<uint32_t> component(nt, TetMesh::kNone), stack;
  std::vector<uint32_t> component_key;
  for (uint32_t seed = 0; seed < nt; ++seed) {
    if (mesh_.is_deleted(seed) || component[seed] != TetMesh::kNone) continue;
    const auto c = static_cast<uint32_t>(component_key.size());
    component_key.push_back(TetMesh::kNone);
    component[seed] = c;
    stack.push_back(seed);
    while (!stack.empty()) {
      const uint32_t t = stack.back();
      stack.pop_back();
      component_key[c] = std::min(component_key[c], region_key[t]);
      for (int i = 0; i < 4; ++i) {
        if (mesh_.tet_adj[4 * size_t(t) + i] == TetMesh::kNoNeighbour) continue;
        const uint32_t n = mesh_.neighbour(t, i);
        if (component[n] == TetMesh::kNone) {
          component[n] = c;
          stack.push_back(n);
        }
      }
    }
  }
  std::vector<uint32_t> order(component_key.size());
  for (uint32_t c = 0; c < order.size(); ++c) order[c] = c;
  std::sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) { return component_key[x] < component_key[y]; });
  std::vector<int32_t> region_of(order.size());
  for (size_t r = 0; r < order.size(); ++r) region_of[order[r]] = static_cast<int32_t>(r);
  // Boundary-layer tets: the T1 tets with a nonzero region (stage 1 tags them; the other T1
  // tets, the T2 tets and the cones are 0) go to region bodies + their body's region, and
  // their vertices are flagged vflag::kBoundaryLayer.
  const auto bodies = static_cast<int32_t>(order.size());
  bodies_ = bodies;
  for (uint32_t t = 0; t < nt; ++t) {
    if (mesh_.is_deleted(t)) continue;
    const bool bl = mesh_.tet_region[t] != 0;
    mesh_.tet_region[t] = region_of[component[t]] + (bl ? bodies : 0);
    if (!bl) continue;
    ++bl_tets_;
    for (int i = 0; i < 4; ++i) mesh_.vflags[mesh_.vertex(t, i)] |= vflag::kBoundaryLayer;
  }
  return Status::success();
}

Status Coupler::run(CoupleStats& stats) {
  stats.t1_tets = mesh_.num_live_tets();
  apex_.resize(t1_.num_front_triangles());
  pieces_.reserve(t1_.num_front_triangles());
  piece_of_.reserve(2 * t1_.num_front_triangles());
  for (uint32_t f = 0; f < t1_.num_front_triangles(); ++f) {
    const uint32_t t = t1_.front_tet[f];
    apex_[f] = mesh_.vertex(t, t1_.front_facet[f]);
    const Tri tri = {t1_.front_tri[3 * f], t1_.front_tri[3 * f + 1], t1_.front_tri[3 * f + 2]};
    piece_of_[sorted(tri)] = f;
    pieces_.push_back({tri, f, t});
  }
  if (Status st = map_t2_vertices(); !st.ok()) return st;
  if (Status st = split_s1_edges(stats); !st.ok()) return st;
  if (Status st = recone_s1_faces(stats); !st.ok()) return st;
  if (Status st = add_t2_tets(stats); !st.ok()) return st;
  if (Status st = finish_boundary_and_regions(); !st.ok()) return st;
  stats.tets = mesh_.num_live_tets();
  stats.bodies = static_cast<size_t>(bodies_);
  stats.bl_tets = bl_tets_;
  return Status::success();
}

}  // namespace

Result<CoupledMesh> couple_meshes(const SurfaceMesh& surface, LayersOutput t1,
                                  const std::vector<uint32_t>& s1_vertex_map, const RecoveryOutput& t2) {
  const auto start = std::chrono::steady_clock::now();
  CoupleStats stats;
  Coupler coupler(surface, t1, s1_vertex_map, t2);
  if (Status st = coupler.run(stats); !st.ok()) return st;
  CoupledMesh out;
  out.mesh = std::move(t1.mesh);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.stats = stats;
  return out;
}

}  // namespace anitet
