// AdaptMesh: the working mesh of anisotropic adaptation (adapt.hpp), made for local operations
// on a mesh that changes everywhere: flat arrays of points (coordinates, metric, surface
// geometry) and tets (vertices, neighbours across faces, boundary faces with their patch labels).
//
// Tet t has vertices tv[4t..4t+3], positively oriented (orient3d > 0, as TetMesh); face i is the
// triangle opposite vertex i; adj[4t+i] = 4n+j when face i of t is face j of tet n, kNone on the
// mesh's hull. A boundary face (bit i of bnd[t]) is a face of the input's surface (a hull face, or
// an interface face between two tets, flagged on both sides) with its label in fref[4t+i].
// Every hull face is a boundary face.
//
// Points carry a tag (ptag) saying how they may move, a metric (6 doubles xx xy yy xz yz zz), one
// live tet holding them (ptet), a hint for the background metric's point location, and, on the
// surface, the geometry of the smooth surface through them: a unit normal (a ridge point: one
// per side, nrm and nrm2, and the unit tangent of the ridge, tng).
// Feature edges (ridges: sharp dihedral angles, patch borders, non-manifold edges) are kept in a
// hash of vertex pairs.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/flat_key_map.hpp"

namespace anitet::adapt {

constexpr uint32_t kNone = 0xffffffffu;

namespace ptag {
constexpr uint8_t kBoundary = 1u << 0;  // on a boundary face
constexpr uint8_t kRidge = 1u << 1;     // on a feature edge: moves along the ridge curve only
constexpr uint8_t kCorner = 1u << 2;    // a feature vertex: never moves, never removed
constexpr uint8_t kRequired = 1u << 3;  // never moves, never removed (the kept surface)
constexpr uint8_t kRemoved = 1u << 4;   // collapsed away: in no tet
constexpr uint8_t kFrozen = kCorner | kRequired;
}  // namespace ptag

constexpr uint8_t kTetDeleted = 1u << 7;  // bnd[t]: the slot is on the free list

constexpr int kFaceVertex[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};  // as TetMesh
constexpr int kEdgeVertex[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

inline uint64_t edge_key(uint32_t a, uint32_t b) {
  return a < b ? (uint64_t(a) << 32) | b : (uint64_t(b) << 32) | a;
}

// The tets around edge ab in turn: tets[k] = (a b ring[k] ring[k+1]) positively oriented. A
// closed shell (an inner edge) has ring.size() == tets.size() (ring[k+1] read modulo its size);
// an open one (a hull edge) one ring vertex more, its first and last faces (a b ring[0]) and
// (a b ring.back()) on the hull.
struct Shell {
  std::vector<uint32_t> tets;
  std::vector<uint32_t> ring;
  bool open = false;
  // Boundary faces containing ab: the ring index of the face's third vertex and its label.
  int num_boundary = 0;
  std::array<uint32_t, 4> bnd_ring{};
  std::array<int32_t, 4> bnd_label{};
  uint32_t ring_at(size_t k) const { return ring[k % ring.size()]; }
};

class AdaptMesh {
 public:
  // Points.
  std::vector<double> xyz;   // 3 per point
  std::vector<double> met;   // 6 per point
  std::vector<double> mdet;  // 1 per point: det of its metric
  std::vector<double> nrm;   // 3 per point: surface normal (a ridge point's first side)
  std::vector<double> nrm2;  // 3 per point: a ridge point's second side
  std::vector<double> tng;   // 3 per point: a ridge point's tangent
  std::vector<uint8_t> tag;
  std::vector<uint32_t> ptet;  // a live tet holding the point (kNone: removed)
  std::vector<uint32_t> hint;  // where the background metric last found it
  // The cycle in which an operation last changed the point's tets (its edges, its ball); sweeps
  // of cycle `epoch` look at the points changed in it or the cycle before (active()).
  std::vector<uint32_t> touched;
  uint32_t epoch = 1;
  // Tets.
  std::vector<uint32_t> tv;     // 4 per tet
  std::vector<uint32_t> adj;    // 4 per tet
  std::vector<int32_t> fref;    // 4 per tet: label of a boundary face
  std::vector<uint8_t> bnd;     // bits 0-3: boundary faces; kTetDeleted
  std::vector<int32_t> region;  // 1 per tet
  std::vector<double> qual;     // 1 per tet: quality in the metric (kept by the operations)
  std::vector<uint32_t> free_tets;
  FlatKeyMap ridge;  // edge_key -> 1 for a feature edge (0: was one)

  size_t num_points() const { return tag.size(); }
  size_t num_slots() const { return tv.size() / 4; }
  size_t num_tets() const { return num_slots() - free_tets.size(); }
  const double* p(uint32_t v) const { return &xyz[3 * size_t(v)]; }
  const double* m(uint32_t v) const { return &met[6 * size_t(v)]; }
  void set_metric(uint32_t v, const double mm[6]);
  bool dead(uint32_t t) const { return (bnd[t] & kTetDeleted) != 0; }
  bool is_bnd_face(uint32_t t, int i) const { return (bnd[t] >> i) & 1u; }
  const uint32_t* verts(uint32_t t) const { return &tv[4 * size_t(t)]; }
  int local(uint32_t t, uint32_t v) const {
    const uint32_t* w = verts(t);
    return w[0] == v ? 0 : w[1] == v ? 1 : w[2] == v ? 2 : w[3] == v ? 3 : -1;
  }

  void touch(uint32_t v) { touched[v] = epoch; }
  void touch_tet(uint32_t t) {
    for (int i = 0; i < 4; ++i) touched[tv[4 * size_t(t) + size_t(i)]] = epoch;
  }
  bool active(uint32_t v) const { return touched[v] + 1 >= epoch; }

  bool is_ridge(uint32_t a, uint32_t b) const {
    const uint32_t r = ridge.find(edge_key(a, b));
    return r != FlatKeyMap::kAbsent && r != 0;
  }
  void set_ridge(uint32_t a, uint32_t b, bool on) {
    if (on) ridge.find_or_insert(edge_key(a, b), 1) = 1;
    else if (ridge.find(edge_key(a, b)) != FlatKeyMap::kAbsent) ridge.find_or_insert(edge_key(a, b), 0) = 0;
  }

  // A new point (its geometry zeroed) and a new tet slot (free list first; no neighbours, no
  // boundary faces).
  uint32_t add_point(const double x[3], const double mm[6], uint8_t t, uint32_t h);
  uint32_t new_tet(uint32_t a, uint32_t b, uint32_t c, uint32_t d, int32_t reg);
  void delete_tet(uint32_t t);

  // Marks: a stamp per tet and per point, raised by next_stamp(); marked(x) is x's stamp equal
  // to the current one.
  uint32_t next_stamp();
  void mark_tet(uint32_t t) { tmark_[t] = stamp_; }
  bool tet_marked(uint32_t t) const { return tmark_[t] == stamp_; }
  void mark_point(uint32_t v) { pmark_[v] = stamp_; }
  bool point_marked(uint32_t v) const { return pmark_[v] == stamp_; }

  // The tets holding v (from ptet[v]). False when ptet[v] is stale (then repaired by a scan).
  void ball(uint32_t v, std::vector<uint32_t>& out);
  // The shell of edge ab from tet t0 holding both. False when a step finds no tet (a corrupt
  // mesh) or the shell has more than max_tets tets.
  bool shell(uint32_t a, uint32_t b, uint32_t t0, Shell& s, size_t max_tets = 64) const;
  // A tet holding edge ab (kNone: ab is no edge).
  uint32_t edge_tet(uint32_t a, uint32_t b, std::vector<uint32_t>& scratch);

  // ptet[v] checked and repaired (a scan) when stale.
  uint32_t tet_of(uint32_t v);

  // Structural audit: adjacency symmetric and matching, boundary flags agreeing on both sides of
  // a face, hull faces flagged, ptet of every live point live and holding it, no tet with a
  // removed point, every tet positive (exact). Empty when sound, else the first problem.
  std::string check() const;

  // Sizes the marks to the points and tets (after building the arrays directly).
  void sync_marks();

 private:
  std::vector<uint32_t> tmark_, pmark_;
  uint32_t stamp_ = 0;
};

// Face j of tet n across face i of t (adj[4t+i] == 4n+j).
inline uint32_t adj_tet(uint32_t a) { return a >> 2; }
inline int adj_face(uint32_t a) { return int(a & 3u); }

// Local indices (i, j) completing (ia, ib) to an even permutation of (0 1 2 3): the tet
// (v[ia] v[ib] v[i] v[j]) is then positively oriented as t is.
void other_two(int ia, int ib, int& i, int& j);

}  // namespace anitet::adapt
