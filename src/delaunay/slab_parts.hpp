// What the slab tasks of the parallel bulk build (delaunay.cpp) and of BatchInserter
// (batch_inserter.cpp) share (internal header): each task's slot pool, each tet's part, the
// pools' leftovers given back, and, with PointInserter, the box of the vertices for the static
// filters and where a walk starts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/bvh.hpp"
#include "core/tet_mesh.hpp"
#include "delaunay/tet_storage.hpp"

namespace anitet::delaunay_detail {

// Pools of want[k] slots: the mesh's free slots dealt out in turn, then fresh slots appended to
// the mesh (marked deleted) for the rest, through `store` (a storage of the mesh without pool,
// which sees the arrays move). The arrays are not resized while the tasks run.
void fill_slot_pools(TetMesh& mesh, TetStorage& store, const std::vector<SlotPool*>& pools,
                     const std::vector<size_t>& want);

// The pools' unused slots back to the mesh's free list, in a fixed order.
void return_slot_pools(TetMesh& mesh, const std::vector<SlotPool*>& pools);

// Each tet slot's part: that of its (real) vertices when they agree, else kNoPart (deleted
// slots too); on every core.
void tet_parts_from_vertices(const TetMesh& mesh, const std::vector<uint8_t>& vertex_part, uint8_t no_part,
                             std::vector<uint8_t>& tet_part);

// Where a walk starts: `hint` when it is a live tet, else `last` when it is, else the first live
// tet (kNone: the mesh has none).
uint32_t walk_start(const TetMesh& mesh, uint32_t hint, uint32_t last);

// The box of a mesh's vertices, grown as vertices are appended (removed ones may leave it larger:
// a superset serves the static filters), and its largest side.
class VertexBox {
 public:
  // Takes in the vertices added since the last call; returns the box's largest side.
  double update(const TetMesh& mesh);
  // Vertices from n on were removed: the next update() takes in whatever is there then.
  void forget_from(size_t n) { seen_ = seen_ < n ? seen_ : n; }

 private:
  size_t seen_ = 0;  // vertices 0..seen_-1 are in box_
  Box3 box_ = {};
};

}  // namespace anitet::delaunay_detail
