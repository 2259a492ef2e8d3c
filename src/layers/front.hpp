// The advancing front: the closed triangulated surface that bounds the region still to mesh.
//
// Orientation convention (the same as the input surface's): every front triangle (a, b, c) is
// counter-clockwise seen from OUTSIDE the region still to mesh, i.e. its right-hand normal points
// away from that region (into the input's outside, or into tets already built). So a point p lies
// on the region's side of the triangle iff orient3d(a, b, c, p) < 0, and the tet (a, c, b, p) is
// then positive.
//
// Triangles live in slots (ids stay valid while alive); each slot remembers the tet that has the
// triangle as a facet (kNone for input triangles). A vertex -> alive triangles table and a loose
// octree over the triangles' boxes answer the star and proximity queries.
//
// Transactions: between begin() and commit()/rollback() every add and remove is logged, and
// rollback() restores the front exactly as it was at begin() (same slot ids), so that a tentative
// sequence of tets (a vertex push) can be undone when a later tet of the sequence does not fit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/bvh.hpp"
#include "layers/loose_octree.hpp"

namespace anitet::layers {

class Front {
 public:
  static constexpr uint32_t kNone = 0xffffffffu;

  // xyz: the vertex coordinates (3 per vertex), owned by the caller; it may grow (new vertices)
  // but a vertex's coordinates must not change while it is on the front. `bounds` must contain
  // every vertex that will ever be on the front.
  Front(const std::vector<double>& xyz, const Box3& bounds);

  // The triangles of `from` whose box reaches below `cut` along `axis` (low side) or above it
  // (high side), in the same slots, over the coordinates `xyz` (a copy of from's, which may grow).
  // For a push task that stays strictly on that side of the cut (LayerBuilder::push_sides): it
  // sees every triangle a query strictly on its side can meet. Its own triangles get slots past
  // from's (dead slots are never reused), so that the copied slots keep their ids.
  Front(const Front& from, const std::vector<double>& xyz, int axis, double cut, bool low_side);

  uint32_t add(uint32_t a, uint32_t b, uint32_t c, uint32_t owner_tet);
  void remove(uint32_t f);

  void begin();
  void commit();
  void rollback();

  bool alive(uint32_t f) const { return alive_[f] != 0; }
  const uint32_t* tri(uint32_t f) const { return &tri_[3 * size_t(f)]; }
  uint32_t owner(uint32_t f) const { return owner_[f]; }
  size_t num_slots() const { return alive_.size(); }
  size_t num_alive() const { return num_alive_; }

  // Alive triangles that have v as a corner (empty for a vertex not on the front).
  const std::vector<uint32_t>& star(uint32_t v) const {
    return v < star_.size() ? star_[v] : empty_;
  }
  // The alive triangle with corners {a, b, c} in any order, or kNone.
  uint32_t find(uint32_t a, uint32_t b, uint32_t c) const;

  // The triangle's bounding box, computed when it went on the front (its corners do not move
  // while it is there).
  const Box3& box(uint32_t f) const { return box_[f]; }

  // Calls visit(f) for every alive triangle whose box overlaps `query` (closed boxes); visit
  // returns false to stop.
  template <class Visit>
  void near(const Box3& query, Visit&& visit) const {
    index_.query(query, visit);
  }

 private:
  void link(uint32_t f);    // into the star table and the index
  void unlink(uint32_t f);

  const std::vector<double>& xyz_;
  std::vector<uint32_t> tri_;     // 3 per slot
  std::vector<uint32_t> owner_;   // 1 per slot
  std::vector<Box3> box_;         // 1 per slot, set by link()
  std::vector<uint8_t> alive_;    // 1 per slot
  std::vector<uint32_t> free_;    // dead slots that may be reused
  std::vector<std::vector<uint32_t>> star_;
  std::vector<uint32_t> empty_;
  LooseOctree index_;
  size_t num_alive_ = 0;

  // Transaction log: +(f+1) added, -(f+1) removed. Slots removed inside a transaction are not
  // reused before it ends, so rollback can revive them in place.
  bool in_transaction_ = false;
  std::vector<int64_t> log_;
  std::vector<uint32_t> pending_free_;
  Box3 bounds_;
  bool reuse_slots_ = true;
};

}  // namespace anitet::layers
