#include "distributed/rank_mesh.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <string>
#include <unordered_map>

#include "distributed/bytes.hpp"
#include "distributed/memory_trace.hpp"
#include "refine/edges.hpp"
#include "refine/mesh_ops.hpp"
#include "refine/refine.hpp"

namespace anitet::distributed {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

bool live(const TetMesh& m, uint32_t t) { return !m.is_deleted(t) && !m.is_ghost(t); }

// The rank a gid's directory entry lives on.
int home_of(uint64_t gid, int ranks) {
  return static_cast<int>(((gid * 0x9E3779B97F4A7C15ull) >> 20) % uint64_t(ranks));
}

Status truncated(const char* what) { return Status(Error::Internal, std::string("distributed: a truncated ") + what + " message"); }

std::unordered_map<uint64_t, uint32_t> gid_index(const std::vector<uint64_t>& gid) {
  std::unordered_map<uint64_t, uint32_t> at;
  at.reserve(gid.size());
  for (uint32_t v = 0; v < gid.size(); ++v) at.emplace(gid[v], v);
  return at;
}

// Tets (4 gids, region, flags) and the vertices they use (gid, xyz, vflags), as bytes.
std::vector<uint8_t> pack_tets(const TetMesh& m, const std::vector<uint64_t>& gid, const std::vector<uint32_t>& tets) {
  std::vector<uint32_t> verts;
  for (uint32_t t : tets)
    for (int i = 0; i < 4; ++i) verts.push_back(m.vertex(t, i));
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  std::vector<uint64_t> vgid(verts.size()), tgid(4 * tets.size());
  std::vector<double> xyz(3 * verts.size());
  std::vector<uint8_t> vflags(verts.size());
  for (size_t k = 0; k < verts.size(); ++k) {
    vgid[k] = gid[verts[k]];
    std::copy_n(m.point(verts[k]), 3, &xyz[3 * k]);
    vflags[k] = m.vflags[verts[k]];
  }
  std::vector<int32_t> region(tets.size());
  std::vector<uint16_t> flags(tets.size());
  for (size_t k = 0; k < tets.size(); ++k) {
    for (int i = 0; i < 4; ++i) tgid[4 * k + size_t(i)] = gid[m.vertex(tets[k], i)];
    region[k] = m.tet_region[tets[k]];
    flags[k] = m.tet_flags[tets[k]] & kKeptFlags;
  }
  Writer w;
  w.array(vgid);
  w.array(xyz);
  w.array(vflags);
  w.array(tgid);
  w.array(region);
  w.array(flags);
  return std::move(w.bytes);
}

// Appends a pack_tets message to `m` (vertices it has, by gid, are not added again); the new
// tets' ids in *added.
Status unpack_tets(const std::vector<uint8_t>& bytes, TetMesh& m, std::vector<uint64_t>& gid,
                   std::unordered_map<uint64_t, uint32_t>& at, std::vector<uint32_t>* added) {
  Reader r(bytes);
  std::vector<uint64_t> vgid, tgid;
  std::vector<double> xyz;
  std::vector<uint8_t> vflags;
  std::vector<int32_t> region;
  std::vector<uint16_t> flags;
  if (!r.array(vgid) || !r.array(xyz) || !r.array(vflags) || !r.array(tgid) || !r.array(region) || !r.array(flags) ||
      !r.done() || xyz.size() != 3 * vgid.size() || vflags.size() != vgid.size() || tgid.size() != 4 * region.size() ||
      flags.size() != region.size())
    return truncated("tets");
  for (size_t k = 0; k < vgid.size(); ++k)
    if (at.emplace(vgid[k], uint32_t(m.num_vertices())).second) {
      m.add_vertex(&xyz[3 * k], vflags[k]);
      gid.push_back(vgid[k]);
    }
  for (size_t k = 0; k < region.size(); ++k) {
    uint32_t v[4];
    for (int i = 0; i < 4; ++i) {
      const auto it = at.find(tgid[4 * k + size_t(i)]);
      if (it == at.end()) return Status(Error::Internal, "distributed: a tet message with a vertex it does not carry");
      v[i] = it->second;
    }
    const uint32_t n = m.new_tet(v[0], v[1], v[2], v[3], region[k]);
    m.tet_flags[n] = flags[k];
    if (added) added->push_back(n);
  }
  return Status::success();
}

// `m` without the vertices no tet uses (ids kept in order), and the gids with them.
void drop_unused_vertices(TetMesh& m, std::vector<uint64_t>& gid) {
  std::vector<uint32_t> to(m.num_vertices(), TetMesh::kNone);
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t)
    if (live(m, t))
      for (int i = 0; i < 4; ++i) to[m.vertex(t, i)] = 0;
  uint32_t n = 0;
  for (uint32_t v = 0; v < to.size(); ++v) {
    if (to[v] == TetMesh::kNone) continue;
    to[v] = n;
    std::copy_n(m.point(v), 3, &m.xyz[3 * size_t(n)]);
    m.vflags[n] = m.vflags[v];
    gid[n] = gid[v];
    ++n;
  }
  m.xyz.resize(3 * size_t(n));
  m.vflags.resize(n);
  gid.resize(n);
  m.xyz.shrink_to_fit();
  m.vflags.shrink_to_fit();
  gid.shrink_to_fit();
  for (uint32_t& v : m.tet_v) v = to[v];
}

// A compact copy of the live tets of `m` for which keep(t) holds (no adjacency).
template <class Keep>
TetMesh compact_tets(const TetMesh& m, Keep keep) {
  TetMesh c;
  c.xyz = m.xyz;
  c.vflags = m.vflags;
  size_t kept_count = 0;
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t) kept_count += live(m, t) && keep(t) ? 1 : 0;
  c.reserve_tets(kept_count);
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
    if (!live(m, t) || !keep(t)) continue;
    const uint32_t n = c.new_tet(m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2), m.vertex(t, 3), m.tet_region[t]);
    c.tet_flags[n] = m.tet_flags[t];
  }
  return c;
}

// Keeps, in place and in order, the live tets t of `m` for which keep(t) holds (keep reads slot t
// before any later slot is written): no second copy of the rank's mesh, as compact_tets makes.
// The adjacency is left unset (kNoNeighbour); the vertices stay.
template <class Keep>
void keep_tets_in_place(TetMesh& m, Keep keep) {
  const auto slots = static_cast<uint32_t>(m.num_tet_slots());
  uint32_t n = 0;
  for (uint32_t t = 0; t < slots; ++t) {
    if (!live(m, t) || !keep(t)) continue;
    std::copy_n(&m.tet_v[4 * size_t(t)], 4, &m.tet_v[4 * size_t(n)]);
    m.tet_flags[n] = m.tet_flags[t];
    m.tet_region[n] = m.tet_region[t];
    ++n;
  }
  m.tet_v.resize(4 * size_t(n));
  m.tet_adj.assign(4 * size_t(n), TetMesh::kNoNeighbour);
  m.tet_flags.resize(n);
  m.tet_region.resize(n);
  m.free_tets.clear();
  m.tet_v.shrink_to_fit();
  m.tet_adj.shrink_to_fit();
  m.tet_flags.shrink_to_fit();
  m.tet_region.shrink_to_fit();
}

// Per (vertex, sharer) pair one value to the sharer; each value of `values` combined (min or max)
// with what the sharers sent for the vertex.
Status combine_with_sharers(const RankMesh& rm, const Sharing& sharing, std::vector<int32_t>& values, bool max,
                            Comm& comm) {
  std::vector<Writer> out(static_cast<size_t>(comm.ranks()));
  for (const auto& [v, q] : sharing.pairs) {
    out[size_t(q)].value(rm.gid[v]);
    out[size_t(q)].value(values[v]);
  }
  std::vector<std::vector<uint8_t>> to(out.size());
  for (size_t q = 0; q < out.size(); ++q) to[q] = std::move(out[q].bytes);
  Result<std::vector<std::vector<uint8_t>>> from = comm.exchange(to);
  if (!from.ok()) return from.status();
  std::unordered_map<uint64_t, uint32_t> at;
  for (const auto& pair : sharing.pairs) at.emplace(rm.gid[pair.first], pair.first);
  for (const std::vector<uint8_t>& bytes : from.value()) {
    if (bytes.size() % 12) return truncated("label");
    Reader r(bytes);
    uint64_t g = 0;
    int32_t value = 0;
    while (r.value(g) && r.value(value)) {
      const auto it = at.find(g);
      if (it == at.end()) return Status(Error::Internal, "distributed: a label for a vertex this rank does not share");
      int32_t& mine = values[it->second];
      mine = max ? std::max(mine, value) : std::min(mine, value);
    }
  }
  return Status::success();
}

}  // namespace

Result<RankMesh> own_coarse_part(const TetMesh& coarse, const std::vector<int32_t>& part_of, int rank) {
  if (part_of.size() != coarse.num_tet_slots()) return Status(Error::Internal, "distributed: a partition of another mesh");
  RankMesh rm;
  std::vector<uint32_t> local(coarse.num_vertices(), TetMesh::kNone);
  for (uint32_t t = 0; t < coarse.num_tet_slots(); ++t) {
    if (part_of[t] != rank || !live(coarse, t)) continue;
    uint32_t v[4];
    for (int i = 0; i < 4; ++i) {
      const uint32_t g = coarse.vertex(t, i);
      if (local[g] == TetMesh::kNone) {
        local[g] = static_cast<uint32_t>(rm.gid.size());
        rm.gid.push_back(g);
        rm.mesh.add_vertex(coarse.point(g), coarse.vflags[g]);
      }
      v[i] = local[g];
    }
    const uint32_t n = rm.mesh.new_tet(v[0], v[1], v[2], v[3], coarse.tet_region[t]);
    rm.mesh.tet_flags[n] = coarse.tet_flags[t] & kKeptFlags;
  }
  rm.meshable.assign(rm.mesh.num_tet_slots(), 1);
  if (Status st = rm.mesh.build_adjacency(); !st.ok()) return st;
  return rm;
}

Result<Sharing> find_sharing(const RankMesh& rm, Comm& comm) {
  const TetMesh& m = rm.mesh;
  const int ranks = comm.ranks();
  std::vector<uint8_t> open(m.num_vertices(), 0);
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t)
    if (live(m, t))
      for (int i = 0; i < 4; ++i)
        if (m.tet_adj[4 * size_t(t) + i] == TetMesh::kNoNeighbour)
          for (int k = 0; k < 3; ++k) open[m.vertex(t, kFacetVertex[i][k])] = 1;
  std::vector<Writer> out(static_cast<size_t>(ranks));
  for (uint32_t v = 0; v < open.size(); ++v)
    if (open[v]) out[size_t(home_of(rm.gid[v], ranks))].value(rm.gid[v]);
  std::vector<std::vector<uint8_t>> to(static_cast<size_t>(ranks));
  for (size_t q = 0; q < to.size(); ++q) to[q] = std::move(out[q].bytes);
  Result<std::vector<std::vector<uint8_t>>> asked = comm.exchange(to);
  if (!asked.ok()) return asked.status();
  // The directory: every (gid, rank holding it) this rank is home of; a gid of several ranks
  // goes back to each of them with the others.
  std::vector<std::pair<uint64_t, int32_t>> entries;
  for (int q = 0; q < ranks; ++q) {
    Reader r(asked.value()[size_t(q)]);
    uint64_t g = 0;
    while (r.value(g)) entries.emplace_back(g, q);
  }
  std::sort(entries.begin(), entries.end());
  std::vector<Writer> back(static_cast<size_t>(ranks));
  for (size_t a = 0; a < entries.size();) {
    size_t b = a;
    while (b < entries.size() && entries[b].first == entries[a].first) ++b;
    for (size_t i = a; i < b && b - a > 1; ++i)
      for (size_t j = a; j < b; ++j)
        if (i != j) {
          back[size_t(entries[i].second)].value(entries[i].first);
          back[size_t(entries[i].second)].value(entries[j].second);
        }
    a = b;
  }
  for (size_t q = 0; q < to.size(); ++q) to[q] = std::move(back[q].bytes);
  Result<std::vector<std::vector<uint8_t>>> told = comm.exchange(to);
  if (!told.ok()) return told.status();
  std::unordered_map<uint64_t, uint32_t> at;
  for (uint32_t v = 0; v < open.size(); ++v)
    if (open[v]) at.emplace(rm.gid[v], v);
  Sharing s;
  for (const std::vector<uint8_t>& bytes : told.value()) {
    Reader r(bytes);
    uint64_t g = 0;
    int32_t q = 0;
    while (r.value(g) && r.value(q)) {
      const auto it = at.find(g);
      if (it == at.end() || q < 0 || q >= ranks) return Status(Error::Internal, "distributed: a bad directory answer");
      s.pairs.emplace_back(it->second, q);
    }
  }
  std::sort(s.pairs.begin(), s.pairs.end());
  return s;
}

namespace {

// Drops, in place, the kept tets of `m` (all slots live; meshable per slot) that share no vertex
// with a meshable one: they are in neither this rank's part nor its halo, and mesh_round holds
// them aside already (in the optimization's zone rounds, most of the rank's tets). Returns the
// label of each tet left (0 meshable, kept(0) kept); the adjacency is left unset. The vertices
// stay.
std::vector<int32_t> drop_far_kept_tets(TetMesh& m, const std::vector<uint8_t>& meshable) {
  std::vector<uint8_t> near(m.num_vertices(), 0);
  const auto slots = static_cast<uint32_t>(m.num_tet_slots());
  for (uint32_t t = 0; t < slots; ++t)
    if (meshable[t])
      for (int i = 0; i < 4; ++i) near[m.vertex(t, i)] = 1;
  std::vector<int32_t> label;
  keep_tets_in_place(m, [&](uint32_t t) {
    bool keep = meshable[t] != 0;
    for (int i = 0; i < 4 && !keep; ++i) keep = near[m.vertex(t, i)] != 0;
    if (keep) label.push_back(meshable[t] ? 0 : kept(0));
    return keep;
  });
  return label;
}

}  // namespace

Result<LocalMesh> with_halo(RankMesh rm, const Sharing& sharing, Comm& comm) {
  const TetMesh& m = rm.mesh;
  const int ranks = comm.ranks();
  // The ranks sharing each vertex (CSR over the sorted pairs).
  std::vector<uint32_t> first(m.num_vertices() + 1, 0);
  for (const auto& pair : sharing.pairs) ++first[pair.first + 1];
  for (size_t v = 0; v < m.num_vertices(); ++v) first[v + 1] += first[v];
  std::vector<std::vector<uint32_t>> tets_for(static_cast<size_t>(ranks));
  std::vector<int32_t> targets;
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
    if (!live(m, t)) continue;
    targets.clear();
    for (int i = 0; i < 4; ++i) {
      const uint32_t v = m.vertex(t, i);
      for (uint32_t k = first[v]; k < first[v + 1]; ++k) targets.push_back(sharing.pairs[k].second);
    }
    std::sort(targets.begin(), targets.end());
    targets.erase(std::unique(targets.begin(), targets.end()), targets.end());
    for (int32_t q : targets) tets_for[size_t(q)].push_back(t);
  }
  std::vector<std::vector<uint8_t>> to(static_cast<size_t>(ranks));
  for (size_t q = 0; q < to.size(); ++q)
    if (!tets_for[q].empty()) to[q] = pack_tets(m, rm.gid, tets_for[q]);
  tets_for.clear();
  Result<std::vector<std::vector<uint8_t>>> from = comm.exchange(to);
  if (!from.ok()) return from.status();
  to.clear();
  LocalMesh local;
  // The own tets become the local mesh's first ones: moved when every slot is live (as a round
  // and a migration leave them), so that the rank does not hold its part twice.
  if (m.num_live_tets() != m.num_tet_slots()) rm.mesh = compact_tets(m, [](uint32_t) { return true; });
  local.label = drop_far_kept_tets(rm.mesh, rm.meshable);
  local.mesh = std::move(rm.mesh);
  local.gid = std::move(rm.gid);
  auto at = gid_index(local.gid);
  for (const std::vector<uint8_t>& bytes : from.value()) {
    if (bytes.empty()) continue;
    if (Status st = unpack_tets(bytes, local.mesh, local.gid, at, nullptr); !st.ok()) return st;
  }
  local.label.resize(local.mesh.num_tet_slots(), 1);
  return local;
}

namespace {

// The round's result as the rank's own tets: the part's own tets (its halo dropped, the facets
// protected for the cut unprotected, gids for its new vertices) and the kept tets.
Result<RankMesh> own_after_round(const MeshPart& part, const std::vector<uint64_t>& whole_gid,
                                 const std::vector<uint8_t>& whole_vflags, TetMesh kept_tets,
                                 std::vector<uint64_t> kept_gid, int rank, uint64_t created) {
  const TetMesh& m = part.mesh;
  const size_t first = part.global_of.size();
  RankMesh rm;
  rm.created = created;
  rm.gid.resize(m.num_vertices());
  rm.mesh.xyz = m.xyz;
  rm.mesh.vflags = m.vflags;
  for (size_t l = 0; l < m.num_vertices(); ++l) {
    if (l < first) {
      rm.gid[l] = whole_gid[part.global_of[l]];
      rm.mesh.vflags[l] = whole_vflags[part.global_of[l]];
    } else {
      rm.gid[l] = created_gid(rank, rm.created++);
    }
  }
  std::vector<std::array<uint32_t, 3>> interface = part.interface_facets;
  std::sort(interface.begin(), interface.end());
  size_t own_tets = 0;
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t) own_tets += live(m, t) && m.tet_region[t] >= 0 ? 1 : 0;
  rm.mesh.reserve_tets(own_tets + kept_tets.num_live_tets());
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
    if (!live(m, t) || m.tet_region[t] < 0) continue;
    const uint32_t n = rm.mesh.new_tet(m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2), m.vertex(t, 3), m.tet_region[t]);
    rm.mesh.tet_flags[n] = m.tet_flags[t] & kKeptFlags;
    for (int i = 0; i < 4; ++i) {
      if (!m.facet_protected(t, i)) continue;
      std::array<uint32_t, 3> f;
      bool old = true;
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = m.vertex(t, kFacetVertex[i][k]);
        old = old && v < first;
        f[size_t(k)] = old ? part.global_of[v] : 0;
      }
      if (!old) continue;
      std::sort(f.begin(), f.end());
      if (std::binary_search(interface.begin(), interface.end(), f)) rm.mesh.set_facet_protected(n, i, false);
    }
  }
  const size_t meshed = rm.mesh.num_tet_slots();
  auto at = gid_index(rm.gid);
  for (uint32_t t = 0; t < kept_tets.num_tet_slots(); ++t) {
    uint32_t v[4];
    for (int i = 0; i < 4; ++i) {
      const uint32_t k = kept_tets.vertex(t, i);
      auto [it, added] = at.emplace(kept_gid[k], uint32_t(rm.mesh.num_vertices()));
      if (added) {
        rm.mesh.add_vertex(kept_tets.point(k), kept_tets.vflags[k]);
        rm.gid.push_back(kept_gid[k]);
      }
      v[i] = it->second;
    }
    const uint32_t n = rm.mesh.new_tet(v[0], v[1], v[2], v[3], kept_tets.tet_region[t]);
    rm.mesh.tet_flags[n] = kept_tets.tet_flags[t];
  }
  rm.meshable.assign(rm.mesh.num_tet_slots(), 0);
  std::fill(rm.meshable.begin(), rm.meshable.begin() + std::ptrdiff_t(meshed), 1);
  drop_unused_vertices(rm.mesh, rm.gid);
  if (Status st = rm.mesh.build_adjacency(); !st.ok())
    return Status(Error::Internal, "distributed: rank " + std::to_string(rank) + " after a round: " + st.message());
  return rm;
}

}  // namespace

Status mesh_round(RankMesh& rm, Step step, const SizingField& field, const RefineOptions& refine,
                  const OptimizeOptions& optimize, Comm& comm, RefineStats& refine_counts,
                  OptimizeStats& optimize_counts) {
  const size_t open_before = count_boundary_facets(rm.mesh);
  Result<Sharing> sharing = find_sharing(rm, comm);
  if (!sharing.ok()) return sharing.status();
  // The kept tets wait aside; the rank's mesh goes into the local mesh (moved, not copied), the
  // local mesh into the part: at most two copies of the part at once.
  TetMesh kept_tets = compact_tets(rm.mesh, [&](uint32_t t) { return !rm.meshable[t]; });
  std::vector<uint64_t> kept_gid = rm.gid;
  drop_unused_vertices(kept_tets, kept_gid);
  trace_memory(comm.rank(), "round: kept tets aside");
  const uint64_t created = rm.created;
  Result<LocalMesh> local = with_halo(std::move(rm), sharing.value(), comm);
  rm = RankMesh();
  if (!local.ok()) return local.status();
  trace_memory(comm.rank(), "round: local mesh with halo");
  Result<MeshPart> part = extract_part(local->mesh, local->label, 0);
  if (!part.ok()) return part.status();
  trace_memory(comm.rank(), "round: part extracted");
  const std::vector<uint64_t> whole_gid = std::move(local->gid);
  const std::vector<uint8_t> whole_vflags = std::move(local->mesh.vflags);
  local = LocalMesh();
  if (Status st = mesh_part(part.value(), step, field, refine, optimize); !st.ok()) return st;
  trace_memory(comm.rank(), step == Step::kRefine ? "round: part refined" : "round: part optimized");
  // own_after_round reads the part's tets and flags, not its adjacency (16 bytes per tet slot).
  std::vector<uint32_t>().swap(part->mesh.tet_adj);
  Result<RankMesh> next = own_after_round(part.value(), whole_gid, whole_vflags, std::move(kept_tets),
                                          std::move(kept_gid), comm.rank(), created);
  if (!next.ok()) return next.status();
  rm = std::move(next).value();
  trace_memory(comm.rank(), "round: own tets rebuilt");
  if (const size_t open_after = count_boundary_facets(rm.mesh); open_after != open_before)
    return Status(Error::Internal, "distributed: rank " + std::to_string(comm.rank()) + "'s part has " +
                                       std::to_string(open_after) + " facets without a neighbour after the round, " +
                                       std::to_string(open_before) + " before");
  add_counts(part.value(), refine_counts, optimize_counts);
  return Status::success();
}

}  // namespace anitet::distributed

namespace anitet::distributed {

Result<size_t> move_and_migrate(RankMesh& rm, int rings, int zone, const std::vector<int32_t>& priority, Comm& comm) {
  const int rank = comm.rank(), ranks = comm.ranks();
  Result<Sharing> sharing = find_sharing(rm, comm);
  if (!sharing.ok()) return sharing.status();
  TetMesh& m = rm.mesh;
  const auto slots = static_cast<uint32_t>(m.num_tet_slots());
  const size_t nv = m.num_vertices();
  if (priority.size() != size_t(ranks)) return Status(Error::Internal, "distributed: a priority list of another size");
  // move_interfaces' rule in the order `priority` gives the ranks: `rings` times, a vertex takes
  // the first label of its tets (over all ranks), a tet the first of its vertices. The labels
  // are the priorities; rank_of maps them back.
  std::vector<int32_t> rank_of(size_t(ranks), -1);
  for (int q = 0; q < ranks; ++q) {
    const int32_t p = priority[size_t(q)];
    if (p < 0 || p >= ranks || rank_of[size_t(p)] >= 0) return Status(Error::Internal, "distributed: priorities that are no order");
    rank_of[size_t(p)] = q;
  }
  std::vector<int32_t> label(slots, priority[size_t(rank)]), vertex_label(nv);
  for (int ring = 0; ring < rings; ++ring) {
    std::fill(vertex_label.begin(), vertex_label.end(), INT32_MAX);
    for (uint32_t t = 0; t < slots; ++t)
      if (live(m, t))
        for (int i = 0; i < 4; ++i) vertex_label[m.vertex(t, i)] = std::min(vertex_label[m.vertex(t, i)], label[t]);
    if (Status st = combine_with_sharers(rm, sharing.value(), vertex_label, false, comm); !st.ok()) return st;
    for (uint32_t t = 0; t < slots; ++t)
      if (live(m, t))
        for (int i = 0; i < 4; ++i) label[t] = std::min(label[t], vertex_label[m.vertex(t, i)]);
  }
  for (uint32_t t = 0; t < slots; ++t) label[t] = rank_of[size_t(label[t])];
  // The zone: `zone` rings of tets around the old interfaces (the shared vertices), the ring
  // distance crossing ranks.
  std::vector<uint8_t> in_zone(slots, zone <= 0 ? 1 : 0);
  if (zone > 0) {
    std::vector<int32_t> near(nv, 0);
    for (const auto& pair : sharing->pairs) near[pair.first] = 1;
    for (int ring = 0; ring < zone; ++ring) {
      for (uint32_t t = 0; t < slots; ++t)
        if (live(m, t) && !in_zone[t])
          for (int i = 0; i < 4 && !in_zone[t]; ++i) in_zone[t] = near[m.vertex(t, i)] != 0;
      for (uint32_t t = 0; t < slots; ++t)
        if (in_zone[t])
          for (int i = 0; i < 4; ++i) near[m.vertex(t, i)] = 1;
      if (Status st = combine_with_sharers(rm, sharing.value(), near, true, comm); !st.ok()) return st;
    }
  }
  // Migration: the zone's tets labelled with another rank go there.
  std::vector<std::vector<uint32_t>> tets_for(static_cast<size_t>(ranks));
  size_t sent = 0;
  for (uint32_t t = 0; t < slots; ++t)
    if (live(m, t) && in_zone[t] && label[t] != rank) {
      tets_for[size_t(label[t])].push_back(t);
      ++sent;
    }
  std::vector<std::vector<uint8_t>> to(static_cast<size_t>(ranks));
  for (size_t q = 0; q < to.size(); ++q)
    if (!tets_for[q].empty()) to[q] = pack_tets(m, rm.gid, tets_for[q]);
  Result<std::vector<std::vector<uint8_t>>> from = comm.exchange(to);
  if (!from.ok()) return from.status();
  to.clear();
  std::vector<uint8_t> meshable;  // of the tets that stay, kept in place
  keep_tets_in_place(m, [&](uint32_t t) {
    const bool stays = !in_zone[t] || label[t] == rank;
    if (stays) meshable.push_back(in_zone[t]);
    return stays;
  });
  auto at = gid_index(rm.gid);
  for (const std::vector<uint8_t>& bytes : from.value()) {
    if (bytes.empty()) continue;
    if (Status st = unpack_tets(bytes, rm.mesh, rm.gid, at, nullptr); !st.ok()) return st;
  }
  meshable.resize(rm.mesh.num_tet_slots(), 1);
  rm.meshable = std::move(meshable);
  drop_unused_vertices(rm.mesh, rm.gid);
  if (Status st = rm.mesh.build_adjacency(); !st.ok())
    return Status(Error::Internal, "distributed: rank " + std::to_string(rank) + " after migration: " + st.message());
  trace_memory(rank, "move: migrated");
  return sent;
}

Result<GlobalIds> number_globally(const RankMesh& rm, Comm& comm) {
  const int rank = comm.rank();
  Result<Sharing> sharing = find_sharing(rm, comm);
  if (!sharing.ok()) return sharing.status();
  const size_t nv = rm.mesh.num_vertices();
  GlobalIds ids;
  ids.vertex_owner.assign(nv, rank);
  for (const auto& [v, q] : sharing->pairs) ids.vertex_owner[v] = std::min(ids.vertex_owner[v], q);
  uint64_t owned = 0;
  for (int32_t o : ids.vertex_owner) owned += o == rank ? 1 : 0;
  const uint64_t tets = rm.mesh.num_live_tets();
  Result<uint64_t> vfirst = comm.exscan(owned);
  if (!vfirst.ok()) return vfirst.status();
  Result<uint64_t> tfirst = comm.exscan(tets);
  if (!tfirst.ok()) return tfirst.status();
  Result<std::vector<double>> totals = comm.allreduce({double(owned), double(tets)}, false);
  if (!totals.ok()) return totals.status();
  ids.first_tet = tfirst.value();
  ids.total_vertices = uint64_t(totals.value()[0]);
  ids.total_tets = uint64_t(totals.value()[1]);
  ids.vertex.assign(nv, UINT64_MAX);
  uint64_t next = vfirst.value();
  for (size_t v = 0; v < nv; ++v)
    if (ids.vertex_owner[v] == rank) ids.vertex[v] = next++;
  // The owners send the ids of their shared vertices to the other holders.
  std::vector<Writer> out(static_cast<size_t>(comm.ranks()));
  for (const auto& [v, q] : sharing->pairs)
    if (ids.vertex_owner[v] == rank) {
      out[size_t(q)].value(rm.gid[v]);
      out[size_t(q)].value(ids.vertex[v]);
    }
  std::vector<std::vector<uint8_t>> to(out.size());
  for (size_t q = 0; q < out.size(); ++q) to[q] = std::move(out[q].bytes);
  Result<std::vector<std::vector<uint8_t>>> from = comm.exchange(to);
  if (!from.ok()) return from.status();
  std::unordered_map<uint64_t, uint32_t> at;
  for (const auto& pair : sharing->pairs) at.emplace(rm.gid[pair.first], pair.first);
  for (const std::vector<uint8_t>& bytes : from.value()) {
    Reader r(bytes);
    uint64_t g = 0, id = 0;
    while (r.value(g) && r.value(id)) {
      const auto it = at.find(g);
      if (it == at.end()) return Status(Error::Internal, "distributed: an id for a vertex this rank does not hold");
      ids.vertex[it->second] = id;
    }
  }
  for (uint64_t id : ids.vertex)
    if (id == UINT64_MAX) return Status(Error::Internal, "distributed: a shared vertex got no id from its owner");
  return ids;
}

namespace {

// The ranks in the order of the tets their parts are heading for (the predicted final tets of
// their own tets; ties by rank): the zones around the interfaces go to the lighter side.
Result<std::vector<int32_t>> least_loaded_first(const RankMesh& rm, const SizingField& field, double scale, Comm& comm) {
  std::vector<double> load(static_cast<size_t>(comm.ranks()), 0.0);
  load[size_t(comm.rank())] = estimate_refined_tets(rm.mesh, field, scale);
  Result<std::vector<double>> all = comm.allreduce(load, false);
  if (!all.ok()) return all.status();
  std::vector<int32_t> order(load.size());
  for (size_t q = 0; q < order.size(); ++q) order[q] = int32_t(q);
  std::stable_sort(order.begin(), order.end(),
                   [&](int32_t a, int32_t b) { return all.value()[size_t(a)] < all.value()[size_t(b)]; });
  std::vector<int32_t> priority(order.size());
  for (size_t k = 0; k < order.size(); ++k) priority[size_t(order[k])] = int32_t(k);
  return priority;
}

// Sums the counts over the ranks.
Status sum_counts(RefineStats& refine, OptimizeStats& optimize, Comm& comm) {
  std::vector<double> v = {double(refine.splits),    double(refine.split_rejected), double(refine.parallel_splits),
                           double(refine.collapses), double(refine.collapse_rejected), double(refine.metric_flips),
                           double(optimize.moves),   double(optimize.moves_rejected), double(optimize.flips23),
                           double(optimize.edge_removals), double(optimize.perturbations), double(optimize.collapses),
                           double(optimize.flat_found), double(optimize.flat_left)};
  Result<std::vector<double>> s = comm.allreduce(v, false);
  if (!s.ok()) return s.status();
  size_t k = 0;
  for (size_t* c : {&refine.splits, &refine.split_rejected, &refine.parallel_splits, &refine.collapses,
                    &refine.collapse_rejected, &refine.metric_flips, &optimize.moves, &optimize.moves_rejected,
                    &optimize.flips23, &optimize.edge_removals, &optimize.perturbations, &optimize.collapses,
                    &optimize.flat_found, &optimize.flat_left})
    *c = size_t(s.value()[k++]);
  return Status::success();
}

// The quality of the union of the parts from each part's.
Result<QualitySummary> whole_quality(const TetMesh& mesh, Comm& comm) {
  const QualitySummary q = summarize_quality(mesh);
  Result<std::vector<double>> sum =
      comm.allreduce({double(q.tets), q.mean * double(q.tets), double(q.below_01), double(q.below_04)}, false);
  if (!sum.ok()) return sum.status();
  Result<std::vector<double>> lowest = comm.allreduce({q.tets ? -q.min : -1.0}, true);
  if (!lowest.ok()) return lowest.status();
  QualitySummary w;
  w.tets = size_t(sum.value()[0]);
  w.mean = w.tets ? sum.value()[1] / double(w.tets) : 0.0;
  w.below_01 = size_t(sum.value()[2]);
  w.below_04 = size_t(sum.value()[3]);
  w.min = -lowest.value()[0];
  return w;
}

// Whether the anisotropic cycles may run: some are asked for and the field is anisotropic at a
// vertex of some rank (the optimizer's rule). Collective.
Result<bool> anisotropic_cycles_wanted(const TetMesh& mesh, const SizingField& field, double scale,
                                       const PartsOptions& options, Comm& comm) {
  if (options.anisotropic_cycles <= 0) return false;
  const ScaledSizing scaled(field, scale);
  double m[6], found = 0.0;
  for (uint32_t v = 0; v < mesh.num_vertices() && found == 0.0; ++v) {
    scaled.metric(mesh.point(v), m);
    found = meshops::MetricMap::of(m).identity ? 0.0 : 1.0;
  }
  Result<std::vector<double>> any = comm.allreduce({found}, true);
  if (!any.ok()) return any.status();
  return any.value()[0] > 0.0;
}

// The share of the edges not on a protected facet whose normalized length in `metrics`
// (vertex_metrics) is in [lo, hi], over the ranks: each rank's share of its own edges weighted by
// its tets (edges on an interface are measured on each rank that has them; the cycles' gates need
// no more). Collective.
Result<double> share_in_range(const TetMesh& mesh, const std::vector<double>& metrics, double lo, double hi,
                              Comm& comm) {
  double mean = 0.0, share = 0.0;
  refine_detail::summarize_edge_lengths(mesh, metrics, lo, hi, mean, share);
  const auto tets = double(mesh.num_live_tets());
  Result<std::vector<double>> sum = comm.allreduce({share * tets, tets}, false);
  if (!sum.ok()) return sum.status();
  return sum.value()[1] > 0.0 ? sum.value()[0] / sum.value()[1] : 1.0;
}

}  // namespace

Result<size_t> split_coarse_for_parts(TetMesh& coarse, const SizingField& field, const RefineOptions& refine_options,
                                      int parts, double tets_per_part) {
  const double scale = refine_options.size_scale > 0.0 ? refine_options.size_scale : 1.0;
  const std::vector<double> weights = estimate_refined_tets_per_tet(coarse, field, scale);
  double total = 0.0, largest = 0.0;
  for (double w : weights) {
    total += w;
    largest = std::max(largest, w);
  }
  const double cap = total / (double(parts) * std::max(1.0, tets_per_part));
  if (largest <= cap) return size_t(0);
  // Refined to s times the final lengths, a tet predicts about s^3 final tets.
  RefineOptions options = refine_options;
  options.size_scale = scale * std::cbrt(std::max(1.0, cap));
  options.collapse = false;  // only split: the small tets near the surface stay as they are
  options.defer_at_frozen = false;
  // Few edges are long here: the default stop share ended after one pass of 257 splits on
  // armadillo. The spacing is the default's 0.7 in final lengths: 0.1 in the scaled ones (points
  // 0.3 final lengths apart on fandisk) left 5% more tets than one process and a lower mean.
  options.stop_fraction = 0.0;
  options.max_passes = 8;
  options.spacing = 0.7 / std::cbrt(std::max(1.0, cap));
  options.progress = nullptr;
  options.expected_tets = 0;
  Result<RefineStats> r = refine_mesh(coarse, field, options);
  if (!r.ok()) return Status(r.status().code(), "distributed: splitting the coarse mesh: " + r.status().message());
  return r->splits;
}

Status run_rank_parts(TetMesh& coarse, const SizingField& field, const RefineOptions& refine_options,
                      const OptimizeOptions& optimize_options, const PartsOptions& options, Comm& comm,
                      CoarsePartitioner& partitioner, RankMesh& rm, RefineStats& refine, OptimizeStats& optimize,
                      RankRunStats* stats) {
  RankRunStats local_stats;
  RankRunStats& rs = stats ? *stats : local_stats;
  if (Status s = check_meshable_in_parts(coarse); !s.ok()) return s;
  refine = RefineStats();
  optimize = OptimizeStats();
  auto t0 = Clock::now();
  optimize.before = summarize_quality(coarse);
  refine.vertices_before = refine_detail::live_vertex_count(coarse);
  refine.tets_before = coarse.num_live_tets();
  {
    const double scale = refine_options.size_scale > 0.0 ? refine_options.size_scale : 1.0;
    if (comm.ranks() > 1 && options.coarse_tets_per_part > 0) {
      Result<size_t> splits =
          split_coarse_for_parts(coarse, field, refine_options, comm.ranks(), options.coarse_tets_per_part);
      if (!splits.ok()) return splits.status();
      rs.coarse_splits = splits.value();
    }
    const std::vector<double> weights = estimate_refined_tets_per_tet(coarse, field, scale);
    trace_memory(comm.rank(), "coarse mesh split");
    Result<std::vector<int32_t>> part_of = partitioner.partition(coarse, weights, comm.ranks());
    if (!part_of.ok()) return part_of.status();
    trace_memory(comm.rank(), "coarse mesh partitioned");
    Result<RankMesh> mine = own_coarse_part(coarse, part_of.value(), comm.rank());
    if (!mine.ok()) return mine.status();
    rm = std::move(mine).value();
  }
  coarse = TetMesh();  // from here on, this rank holds its part only
  trace_memory(comm.rank(), "coarse mesh freed");
  rs.partition_seconds = since(t0);
  rs.own_tets_after_partition = rm.mesh.num_live_tets();
  t0 = Clock::now();
  auto round = [&](Step step) { return mesh_round(rm, step, field, refine_options, optimize_options, comm, refine, optimize); };
  // Refinement's first round leaves the coarse tets beside its frozen interfaces unrefined (the
  // points whose cavities reached them were put off); split_coarse_for_parts keeps that band one
  // small coarse tet deep, which the move's rings take inside a part. Each move gives the zones
  // to the side with fewer predicted tets.
  const double scale = refine_options.size_scale > 0.0 ? refine_options.size_scale : 1.0;
  auto move = [&](Step step) -> Status {
    Result<std::vector<int32_t>> priority = least_loaded_first(rm, field, scale, comm);
    if (!priority.ok()) return priority.status();
    const bool refining = step == Step::kRefine;
    Result<size_t> sent =
        move_and_migrate(rm, refining ? options.refine_rings : options.optimize_rings,
                         refining ? options.refine_zone : options.optimize_zone, priority.value(), comm);
    if (!sent.ok()) return sent.status();
    rs.migrated_tets += sent.value();
    return Status::success();
  };
  // The shares of edges in [1/sqrt2, sqrt2] that the anisotropic cycles' gates read (refinement's
  // range, then the unit range), over the ranks.
  Result<bool> wanted = anisotropic_cycles_wanted(rm.mesh, field, scale, options, comm);
  if (!wanted.ok()) return wanted.status();
  const bool anisotropic = wanted.value();
  double refined_in_range = 0.0;
  auto steps = [&](Step step) -> Status {
    std::fill(rm.meshable.begin(), rm.meshable.end(), 1);
    if (Status st = round(step); !st.ok()) return st;
    const int moves = step == Step::kRefine ? 1 : std::max(1, options.optimize_moves);
    for (int k = 0; k < moves; ++k) {
      if (Status st = move(step); !st.ok()) return st;
      if (Status st = round(step); !st.ok()) return st;
    }
    if (!anisotropic) return Status::success();
    const std::vector<double> metrics = vertex_metrics(rm.mesh, field, scale);
    Result<double> share =
        share_in_range(rm.mesh, metrics, refine_options.collapse_length, refine_options.split_length, comm);
    if (!share.ok()) return share.status();
    if (step == Step::kRefine) refined_in_range = share.value();
    Result<double> unit = share_in_range(rm.mesh, metrics, kUnitRangeMin, kUnitRangeMax, comm);
    if (!unit.ok()) return unit.status();
    (step == Step::kRefine ? optimize.length_in_range_before : optimize.length_in_range_after) = unit.value();
    return Status::success();
  };
  if (Status st = run_steps_and_cycles(options, anisotropic, refined_in_range, optimize, steps); !st.ok()) return st;
  rs.rounds_seconds = since(t0);
  if (Status st = sum_counts(refine, optimize, comm); !st.ok()) return st;
  Result<QualitySummary> after = whole_quality(rm.mesh, comm);
  if (!after.ok()) return after.status();
  optimize.after = after.value();
  Result<std::vector<double>> counts =
      comm.allreduce({double(refine_detail::live_vertex_count(rm.mesh)), double(rm.mesh.num_live_tets())}, false);
  if (!counts.ok()) return counts.status();
  refine.vertices_after = size_t(counts.value()[0]);  // shared vertices counted on each of their ranks
  refine.tets_after = size_t(counts.value()[1]);
  return Status::success();
}

}  // namespace anitet::distributed
