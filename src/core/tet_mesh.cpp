#include "core/tet_mesh.hpp"

#include <algorithm>
#include <array>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/buckets.hpp"
#include "predicates/predicates.hpp"

namespace anitet {

uint32_t TetMesh::add_vertex(const double p[3], uint8_t flags) {
  const auto id = static_cast<uint32_t>(num_vertices());
  xyz.insert(xyz.end(), p, p + 3);
  vflags.push_back(flags);
  return id;
}

uint32_t TetMesh::new_tet(uint32_t a, uint32_t b, uint32_t c, uint32_t d, int32_t region) {
  uint32_t t;
  if (!free_tets.empty()) {
    t = free_tets.back();
    free_tets.pop_back();
  } else {
    t = static_cast<uint32_t>(num_tet_slots());
    tet_v.resize(tet_v.size() + 4);
    tet_adj.resize(tet_adj.size() + 4);
    tet_flags.push_back(0);
    tet_region.push_back(0);
  }
  fill_tet(t, a, b, c, d, region);
  return t;
}

void TetMesh::fill_tet(uint32_t t, uint32_t a, uint32_t b, uint32_t c, uint32_t d, int32_t region) {
  uint32_t* v = &tet_v[4 * size_t(t)];
  v[0] = a;
  v[1] = b;
  v[2] = c;
  v[3] = d;
  std::fill_n(&tet_adj[4 * size_t(t)], 4, kNoNeighbour);
  tet_flags[t] = 0;
  tet_region[t] = region;
}

void TetMesh::delete_tet(uint32_t t) {
  tet_flags[t] = tflag::kDeleted;
  free_tets.push_back(t);
}

Status TetMesh::build_adjacency() {
  // Facets grouped by their smallest vertex (a counting sort), then sorted within each group by
  // the other two and paired with their equal neighbour: linear in the tets, and no allocation
  // per facet (a hash map of the facets was most of its time). The adjacency is the same
  // whatever the order of the pairing.
  if (num_tet_slots() > kMaxTetSlots)
    return Status(Error::InvalidArgument, std::to_string(num_tet_slots()) +
                                              " tet slots: more than a mesh holds (2^30, adjacency in 32 bits)");
  const uint32_t slots = num_tet_slots();
  auto sorted_facet = [&](uint32_t t, int i, uint32_t v[3]) {
    for (int k = 0; k < 3; ++k) v[k] = vertex(t, kFacetVertex[i][k]);
    // Three compare-swaps (std::sort's call cost was most of this function's time).
    if (v[0] > v[1]) std::swap(v[0], v[1]);
    if (v[1] > v[2]) std::swap(v[1], v[2]);
    if (v[0] > v[1]) std::swap(v[0], v[1]);
  };
  size_t num_keys = 0;
  for (uint32_t t = 0; t < slots; ++t) {
    if (is_deleted(t)) continue;
    for (int i = 0; i < 4; ++i) {
      tet_adj[4 * size_t(t) + i] = kNoNeighbour;
      uint32_t v[3];
      sorted_facet(t, i, v);
      if (v[0] >= num_vertices())  // (a ghost facet's smallest vertex is a real one)
        return Status(Error::InvalidMesh, "tet " + std::to_string(t) + " refers to vertex " +
                                              std::to_string(v[0]) + ", which does not exist");
      num_keys = std::max(num_keys, size_t(v[0]) + 1);
    }
  }
  std::vector<uint32_t> start, facets, fill;  // facet id: 4 t + i
  parallel_bucket_by_key(
      num_keys, slots,
      [&](size_t first, size_t last, auto&& emit) {
        for (auto t = uint32_t(first); t < last; ++t)
          if (!is_deleted(t))
            for (int i = 0; i < 4; ++i) {
              uint32_t v[3];
              sorted_facet(t, i, v);
              emit(v[0], 4 * t + uint32_t(i));
            }
      },
      start, facets, fill);
  // Each group pairs its own facets only (a facet is in its smallest vertex's group): the groups
  // are paired on every core, in chunks; the error reported is the first in key order, as one
  // loop would report it.
  constexpr size_t kChunk = 4096;
  const size_t chunks = (num_keys + kChunk - 1) / kChunk;
  std::vector<std::string> errors(chunks);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<std::pair<uint64_t, uint32_t>> group;  // (other two vertices, facet id)
    for (size_t c = r.begin(); c != r.end(); ++c) {
      for (size_t key = c * kChunk; key < std::min(num_keys, (c + 1) * kChunk) && errors[c].empty(); ++key) {
        group.clear();
        for (uint32_t k = start[key]; k < start[key + 1]; ++k) {
          uint32_t v[3];
          sorted_facet(facets[k] >> 2, int(facets[k] & 3), v);
          group.emplace_back((uint64_t(v[1]) << 32) | v[2], facets[k]);
        }
        std::sort(group.begin(), group.end());
        for (size_t a = 0; a < group.size();) {
          size_t b = a + 1;
          while (b < group.size() && group[b].first == group[a].first) ++b;
          if (b - a > 2) {
            std::ostringstream msg;
            msg << "facet (" << key << ", " << (group[a].first >> 32) << ", " << (group[a].first & 0xffffffffu)
                << ") is shared by more than two tets (tet " << (group[a + 2].second >> 2) << " among them)";
            errors[c] = msg.str();
            break;
          }
          if (b - a == 2)
            link(group[a].second >> 2, int(group[a].second & 3), group[a + 1].second >> 2,
                 int(group[a + 1].second & 3));
          a = b;
        }
      }
    }
  });
  for (const std::string& e : errors)
    if (!e.empty()) return Status(Error::InvalidMesh, e);
  return Status::success();
}

VolumeMesh TetMesh::to_volume_mesh(bool drop_unused_vertices, std::vector<uint32_t>* vertex_map) const {
  return to_volume_mesh(drop_unused_vertices, {}, {}, vertex_map);
}

void TetMesh::number_output_vertices(bool drop_unused_vertices, const std::vector<uint32_t>& bnd_tri,
                                     std::vector<uint32_t>& remap) const {
  const size_t nv = num_vertices();
  remap.assign(nv, kNone);
  if (!drop_unused_vertices)
    for (size_t v = 0; v < nv; ++v) remap[v] = static_cast<uint32_t>(v);
  for (uint32_t t = 0; t < num_tet_slots(); ++t) {
    if (is_deleted(t) || is_ghost(t)) continue;
    for (int i = 0; i < 4; ++i) {
      uint32_t v = vertex(t, i);
      if (remap[v] == kNone) remap[v] = 0;  // mark used; numbered below in vertex order
    }
  }
  for (uint32_t v : bnd_tri)
    if (v < nv && remap[v] == kNone) remap[v] = 0;
  if (drop_unused_vertices) {
    uint32_t next = 0;
    for (size_t v = 0; v < nv; ++v)
      if (remap[v] != kNone) remap[v] = next++;
  }
}

VolumeMesh TetMesh::to_volume_mesh(bool drop_unused_vertices, const std::vector<uint32_t>& bnd_tri,
                                   const std::vector<int32_t>& bnd_patch, std::vector<uint32_t>* vertex_map) const {
  VolumeMesh out;
  const size_t nv = num_vertices();
  std::vector<uint32_t> local;
  std::vector<uint32_t>& remap = vertex_map ? *vertex_map : local;
  number_output_vertices(drop_unused_vertices, bnd_tri, remap);
  out.xyz.reserve(3 * nv);
  for (size_t v = 0; v < nv; ++v)
    if (remap[v] != kNone) out.xyz.insert(out.xyz.end(), &xyz[3 * v], &xyz[3 * v] + 3);
  size_t tets = 0;
  for (uint32_t t = 0; t < num_tet_slots(); ++t) tets += !is_deleted(t) && !is_ghost(t);
  out.tet.reserve(4 * tets);
  out.region.reserve(tets);
  for (uint32_t t = 0; t < num_tet_slots(); ++t) {
    if (is_deleted(t) || is_ghost(t)) continue;
    for (int i = 0; i < 4; ++i) out.tet.push_back(remap[vertex(t, i)]);
    out.region.push_back(tet_region[t]);
  }
  out.bnd_tri.reserve(bnd_tri.size());
  for (uint32_t v : bnd_tri) out.bnd_tri.push_back(v < nv ? remap[v] : kNone);
  out.bnd_patch = bnd_patch;
  return out;
}

VolumeMesh TetMesh::take_volume_mesh(bool drop_unused_vertices, const std::vector<uint32_t>& bnd_tri,
                                     const std::vector<int32_t>& bnd_patch, std::vector<uint32_t>* vertex_map) {
  VolumeMesh out;
  const size_t nv = num_vertices();
  std::vector<uint32_t> local;
  std::vector<uint32_t>& remap = vertex_map ? *vertex_map : local;
  number_output_vertices(drop_unused_vertices, bnd_tri, remap);
  // Compacted in place, front to back: a vertex's or tet's new place is never after its old one.
  size_t kept = 0;
  for (size_t v = 0; v < nv; ++v)
    if (remap[v] != kNone) std::copy_n(&xyz[3 * v], 3, &xyz[3 * kept++]);
  xyz.resize(3 * kept);
  size_t tets = 0;
  for (uint32_t t = 0; t < num_tet_slots(); ++t) {
    if (is_deleted(t) || is_ghost(t)) continue;
    for (int i = 0; i < 4; ++i) tet_v[4 * tets + i] = remap[tet_v[4 * size_t(t) + i]];
    tet_region[tets++] = tet_region[t];
  }
  tet_v.resize(4 * tets);
  tet_region.resize(tets);
  out.xyz = std::move(xyz);
  out.tet = std::move(tet_v);
  out.region = std::move(tet_region);
  out.bnd_tri.reserve(bnd_tri.size());
  for (uint32_t v : bnd_tri) out.bnd_tri.push_back(v < nv ? remap[v] : kNone);
  out.bnd_patch = bnd_patch;
  *this = TetMesh();
  return out;
}

TetMesh TetMesh::from_volume_mesh(const VolumeMesh& m) {
  TetMesh out;
  out.xyz = m.xyz;
  out.vflags.assign(m.num_vertices(), 0);
  for (size_t t = 0; t < m.num_tets(); ++t) {
    const uint32_t* v = &m.tet[4 * t];
    out.new_tet(v[0], v[1], v[2], v[3], m.region.empty() ? 0 : m.region[t]);
  }
  return out;
}

namespace {

// Collects the first few problems and counts them all.
class ProblemLog {
 public:
  void add(const std::string& what) {
    if (++count_ <= 8) text_ << (count_ > 1 ? "; " : "") << what;
  }
  Status status() const {
    if (count_ == 0) return Status::success();
    std::ostringstream msg;
    msg << count_ << " mesh problem(s): " << text_.str() << (count_ > 8 ? "; ..." : "");
    return Status(Error::InvalidMesh, msg.str());
  }

 private:
  size_t count_ = 0;
  std::ostringstream text_;
};

}  // namespace

Status check_mesh(const TetMesh& m, const MeshCheckOptions& options) {
  ProblemLog log;
  const size_t nv = m.num_vertices();
  const size_t nt = m.num_tet_slots();
  if (m.tet_adj.size() != 4 * nt || m.tet_flags.size() != nt || m.tet_region.size() != nt ||
      m.vflags.size() != nv)
    return Status(Error::InvalidMesh, "array sizes disagree");

  const bool check_hull = options.check_convex_hull || options.check_delaunay;
  std::vector<char> on_free_list(nt, 0);
  for (uint32_t t : m.free_tets) {
    if (t >= nt || on_free_list[t]) log.add("bad free-list entry " + std::to_string(t));
    else on_free_list[t] = 1;
  }
  for (uint32_t t = 0; t < nt; ++t) {
    const bool deleted = m.is_deleted(t);
    if (deleted != bool(on_free_list[t]))
      log.add("tet " + std::to_string(t) + (deleted ? " deleted but not on the free list"
                                                     : " on the free list but not deleted"));
    if (deleted) continue;
    if (m.tet_flags[t] & tflag::kScratchMask)
      log.add("tet " + std::to_string(t) + " has scratch flag bits left set");

    for (int i = 0; i < 4; ++i) {
      const uint32_t v = m.vertex(t, i);
      const bool ghost_slot_ok = (v == TetMesh::kGhost && i == 3);
      if (v >= nv && !ghost_slot_ok)
        log.add("tet " + std::to_string(t) + " has bad vertex " + std::to_string(v));
    }
    if (!m.is_ghost(t)) {
      bool in_range = true;
      for (int i = 0; i < 4; ++i) in_range = in_range && m.vertex(t, i) < nv;
      if (in_range && predicates::orient3d(m.point(m.vertex(t, 0)), m.point(m.vertex(t, 1)),
                                           m.point(m.vertex(t, 2)), m.point(m.vertex(t, 3))) <= 0)
        log.add("tet " + std::to_string(t) + " is not positively oriented");
    }

    for (int i = 0; i < 4; ++i) {
      const uint32_t adj = m.tet_adj[4 * size_t(t) + i];
      if (adj == TetMesh::kNoNeighbour) {
        if (options.require_closed || m.is_ghost(t))
          log.add("facet " + std::to_string(i) + " of tet " + std::to_string(t) + " has no neighbour");
        continue;
      }
      const uint32_t n = m.neighbour(t, i);
      const int j = m.neighbour_facet(t, i);
      if (n >= nt || m.is_deleted(n)) {
        log.add("tet " + std::to_string(t) + " points to missing neighbour " + std::to_string(n));
        continue;
      }
      if (m.tet_adj[4 * size_t(n) + j] != 4 * uint32_t(t) + uint32_t(i)) {
        log.add("adjacency of tets " + std::to_string(t) + " and " + std::to_string(n) + " is not symmetric");
        continue;
      }
      // The shared facet must have the same three vertices, in opposite orientation.
      std::array<uint32_t, 3> a{}, b{};
      for (int k = 0; k < 3; ++k) {
        a[k] = m.vertex(t, kFacetVertex[i][k]);
        b[k] = m.vertex(n, kFacetVertex[j][k]);
      }
      std::array<uint32_t, 3> sa = a, sb = b;
      std::sort(sa.begin(), sa.end());
      std::sort(sb.begin(), sb.end());
      if (sa != sb) {
        log.add("tets " + std::to_string(t) + " and " + std::to_string(n) + " are linked by different facets");
        continue;
      }
      // Opposite orientation: b is a reversed rotation of a.
      bool reversed = false;
      for (int r = 0; r < 3; ++r)
        reversed = reversed || (b[0] == a[r] && b[1] == a[(r + 2) % 3] && b[2] == a[(r + 1) % 3]);
      if (!reversed)
        log.add("tets " + std::to_string(t) + " and " + std::to_string(n) + " share a facet with the same orientation");
      if (m.facet_protected(t, i) != m.facet_protected(n, j))
        log.add("facet " + std::to_string(i) + " of tet " + std::to_string(t) + " is protected on one side only");

      if (check_hull && m.is_ghost(t) && (i == 3) == m.is_ghost(n)) {
        log.add("ghost tet " + std::to_string(t) + (i == 3 ? " has a ghost behind its hull facet"
                                                           : " has a real tet beside it"));
      } else if (check_hull && m.is_ghost(t) && i != 3 && t < n) {
        // Hull edge shared by the hull facets of t and n: n's third vertex must not lie beyond
        // t's hull facet (whose normal, facet 3 of a ghost, points out of the hull).
        uint32_t d = TetMesh::kNone;
        for (int k = 0; k < 3; ++k)
          if (m.vertex(n, k) != m.vertex(t, 0) && m.vertex(n, k) != m.vertex(t, 1) &&
              m.vertex(n, k) != m.vertex(t, 2))
            d = m.vertex(n, k);
        if (d < nv && predicates::orient3d(m.point(m.vertex(t, 0)), m.point(m.vertex(t, 1)),
                                           m.point(m.vertex(t, 2)), m.point(d)) > 0)
          log.add("hull is not convex at the edge shared by ghost tets " + std::to_string(t) +
                  " and " + std::to_string(n));
      }
      if (options.check_delaunay && t < n && !m.is_ghost(t) && !m.is_ghost(n) && !m.facet_protected(t, i)) {
        const uint32_t apex = m.vertex(n, j);
        if (predicates::insphere(m.point(m.vertex(t, 0)), m.point(m.vertex(t, 1)),
                                 m.point(m.vertex(t, 2)), m.point(m.vertex(t, 3)), m.point(apex)) > 0)
          log.add("facet " + std::to_string(i) + " of tet " + std::to_string(t) + " is not locally Delaunay");
      }
    }
  }
  return log.status();
}

}  // namespace anitet
