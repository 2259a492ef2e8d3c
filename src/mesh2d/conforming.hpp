// Delaunay triangulation of a point set and conforming recovery of segments in it (the 2D form
// of stage 2): missing segments are split at their midpoints, each point inserted through the
// kernel's cavities, which recovered pieces stop, until every piece is an edge (the modified
// Delaunay kernel of the paper's reference [12]). Also the faces the recovered segments cut the
// triangulation into.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/status.hpp"
#include "mesh2d/triangulation.hpp"

namespace anitet::mesh2d {

// The Delaunay triangulation of the points `which` of xy (2 per point; the others stay in the
// triangulation's vertex list, unused), inside a box 4 corners (appended after xy's points,
// from index *first_corner) make convex: no point is on the hull. Points inserted in a BRIO +
// Hilbert order. Error::DuplicatePoint naming two points at one place (their indices in xy).
Result<Triangulation> delaunay_in_box(const std::vector<double>& xy, const std::vector<uint32_t>& which,
                                      uint32_t* first_corner);

struct ConformingStats {
  size_t steiner = 0;  // midpoints inserted
};

// Recovers each segment i (seg[2i], seg[2i+1]) as a chain of edges tagged tags[i], splitting a
// missing one at its midpoint (appended to the vertices), recursively. Segments must not cross
// or touch but at shared ends. Error::RecoveryFailed when more than max_steiner points would be
// needed or a midpoint cannot be inserted (crossing segments).
Status recover_segments(Triangulation& mesh, const std::vector<uint32_t>& seg, const std::vector<int32_t>& tags,
                        ConformingStats* stats = nullptr, size_t max_steiner = 0);

// Connected components of the live triangles across untagged edges: face[t] (kNone for free
// slots); returns the number of faces.
uint32_t label_faces(const Triangulation& mesh, std::vector<uint32_t>& face);

// The pieces of each tagged chain in order: for tag g, the vertices from the segment's start
// `from[g]` to its end, following the edges tagged g. Error::RecoveryFailed when a chain is
// broken.
Status chain_vertices(const Triangulation& mesh, uint32_t from, uint32_t to, int32_t tag, std::vector<uint32_t>& out);

}  // namespace anitet::mesh2d
