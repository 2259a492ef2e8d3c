// Exact intersection tests between closed triangles, built on the orient2d/orient3d predicates.
// Triangles are given by their corner coordinates and must not be degenerate (callers drop
// degenerate triangles first). Corners with exactly equal coordinates count as shared.
#pragma once

namespace anitet::tri_intersect {

// True when the closed segment pq meets the closed triangle abc.
bool segment_hits_triangle(const double* p, const double* q, const double* a, const double* b,
                           const double* c);

// True when the two triangles meet anywhere beyond their shared part: for triangles with no
// common corner, any contact; with one common corner v, any point other than v; with a common
// edge, any point off that edge (which happens only when they are coplanar and on the same side
// of it). Triangles with three common corners (duplicates) return false: they are reported
// as duplicates instead.
bool triangles_intersect(const double* const t1[3], const double* const t2[3]);

}  // namespace anitet::tri_intersect
