// Recovery by splitting the constraints themselves (internal header; recover_boundary() in
// recovery.hpp is the entry point).
//
// The surface to recover is kept as a list of constraint triangles, at first the input's. When a
// subsegment of an input edge is missing from the mesh, one flip makes it when one can (no
// point), else a Steiner point is inserted on the input segment (at a point a walk from one end
// shows joined to it, the walk's chain of tets forced into the cavity; else near the middle, or at
// a power-of-two distance from an input vertex) and the edge's two triangles are split there.
// Present subsegments are defended (constrained in the kernel) so later points do not destroy
// them. An edge inside an input face is free: a missing one is flipped within the face (to the
// mesh's edge, or the face's 2D Delaunay one, sweeping until no flip is left), else made by flips
// of the mesh along it, or split like an input edge. When a triangle whose input-edge subsegments are
// missing, a point is inserted where a mesh edge crosses it (kept away from its edges), else at
// its centroid, and the triangle is split into three. With RecoveryOptions::face_apex, no split
// or flip may leave a piece that does not see its face's apex (the coupling's cones). Before all
// this, the long edge of every cap (an angle above RecoveryOptions::split_cap_degrees) is split at
// its apex's projection. A constraint triangle is recovered exactly when it is a facet of the mesh, and it is
// then protected, so every decision is combinatorial: no orientation test decides which facets
// lie on a face (the fuzzy part of the other strategy, which fails on nearly flat stacks of
// tets). The Steiner points are computed in floating point, so each split triangle lies within
// rounding of its input face (Claim 5.1: every constraint triangle keeps its input face's id).
// The outside is carved combinatorially too: a protected facet seen from a tet with the same
// cyclic order as its (outward) constraint triangle has the outside on that tet's side.
#pragma once

#include "core/status.hpp"
#include "recovery/recovery.hpp"

namespace anitet::recovery_detail {

// Fills out (mesh, S2, Steiner points, stats) or fails with RecoveryFailed naming the triangle
// or edge left. S as for recover_boundary().
Status recover_by_splitting(const SurfaceMesh& S, const RecoveryOptions& options, RecoveryOutput& out);

}  // namespace anitet::recovery_detail
