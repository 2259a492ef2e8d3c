#include "delaunay/slab_parts.hpp"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace anitet::delaunay_detail {

void fill_slot_pools(TetMesh& mesh, TetStorage& store, const std::vector<SlotPool*>& pools,
                     const std::vector<size_t>& want) {
  const size_t np = pools.size();
  for (SlotPool* p : pools) p->free.clear();
  size_t kept = 0;
  for (size_t i = 0; i < mesh.free_tets.size(); ++i) {
    SlotPool& p = *pools[i % np];
    if (p.free.size() < want[i % np]) p.free.push_back(mesh.free_tets[i]);
    else mesh.free_tets[kept++] = mesh.free_tets[i];  // kept for the sequential inserts
  }
  mesh.free_tets.resize(kept);
  size_t total = 0;
  for (size_t k = 0; k < np; ++k) total += want[k] - std::min(want[k], pools[k]->free.size());
  uint32_t next = store.append(total);
  for (size_t t = next; t < size_t(next) + total; ++t) mesh.tet_flags[t] = tflag::kDeleted;
  for (size_t k = 0; k < np; ++k) {
    SlotPool& p = *pools[k];
    p.next = next;
    p.end = next + static_cast<uint32_t>(want[k] - std::min(want[k], p.free.size()));
    next = p.end;
  }
}

void return_slot_pools(TetMesh& mesh, const std::vector<SlotPool*>& pools) {
  for (SlotPool* p : pools) {
    mesh.free_tets.insert(mesh.free_tets.end(), p->free.begin(), p->free.end());
    for (uint32_t t = p->end; t > p->next; --t) mesh.free_tets.push_back(t - 1);
  }
}

void tet_parts_from_vertices(const TetMesh& mesh, const std::vector<uint8_t>& vertex_part, uint8_t no_part,
                             std::vector<uint8_t>& tet_part) {
  const size_t slots = mesh.num_tet_slots();
  tet_part.resize(slots);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, slots, 1 << 14), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t t = range.begin(); t < range.end(); ++t) {
      const uint32_t* v = &mesh.tet_v[4 * t];
      uint8_t o = no_part;
      if (!(mesh.tet_flags[t] & tflag::kDeleted)) {
        o = vertex_part[v[0]];
        if (vertex_part[v[1]] != o || vertex_part[v[2]] != o || (v[3] != TetMesh::kGhost && vertex_part[v[3]] != o))
          o = no_part;
      }
      tet_part[t] = o;
    }
  });
}

uint32_t walk_start(const TetMesh& mesh, uint32_t hint, uint32_t last) {
  auto live = [&mesh](uint32_t t) { return t < mesh.num_tet_slots() && !mesh.is_deleted(t); };
  if (live(hint)) return hint;
  if (live(last)) return last;
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t)
    if (!mesh.is_deleted(t)) return t;
  return TetMesh::kNone;
}

double VertexBox::update(const TetMesh& mesh) {
  const size_t nv = mesh.num_vertices();
  seen_ = std::min(seen_, nv);
  if (seen_ < nv) {
    const Box3 fresh = bounding_box(&mesh.xyz[3 * seen_], nv - seen_);
    for (int k = 0; k < 3; ++k) {
      box_.lo[k] = seen_ == 0 ? fresh.lo[k] : std::min(box_.lo[k], fresh.lo[k]);
      box_.hi[k] = seen_ == 0 ? fresh.hi[k] : std::max(box_.hi[k], fresh.hi[k]);
    }
    seen_ = nv;
  }
  return seen_ == 0 ? 0.0 : std::max({box_.hi[0] - box_.lo[0], box_.hi[1] - box_.lo[1], box_.hi[2] - box_.lo[2]});
}

}  // namespace anitet::delaunay_detail
