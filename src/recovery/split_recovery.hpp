// Recovery by splitting the constraints themselves (internal header; recover_boundary() in
// recovery.hpp is the entry point).
//
// The surface to recover is kept as a list of constraint triangles, at first the input's. When a
// constraint edge is missing from the mesh, a Steiner point is inserted near its middle and the
// edge's two triangles are split there; when a triangle whose edges are present is missing, a
// point is inserted where a mesh edge crosses it (else at its centroid) and the triangle is split
// into three. A constraint triangle is recovered exactly when it is a facet of the mesh, and it is
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
