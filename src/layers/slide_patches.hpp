// Boundary layers on walls that meet other patches (BoundaryLayerOptions::slide_patches): a pipe's
// wall meets its inlet, a half-model's body the symmetry plane, a floor the channel's sides.
//
// Where a wall meets a slide patch P, the columns of the wall's vertices on that junction slide
// along P: in P's plane, or along the edge where two planar faces of slide patches meet (a box's
// corner). Their points (A_1 .. A_n above each junction vertex A_0, heights h0 r^i) are placed
// before stage 1, and P is triangulated again around them: the band the layers cover is made of
// the prisms' side faces (per junction edge AB and layer i, the quad A_i B_i B_(i+1) A_(i+1) split
// by the diagonal from the top of the column pushed first, the one with the smaller vertex id,
// to the foot of the other: the faces stage 1's push order makes), and the rest of P's triangles
// that the band overlaps, or whose vertices it covers or nearly touches, are replaced by a
// constrained triangulation (planar_cdt.hpp) of what is left of them, keeping their other
// vertices and their outline. Everything else of the surface stays as given: same vertices
// (first, same ids), same triangles.
//
// Stage 1 then pushes each junction vertex A_i to A_(i+1) (LayerBuilder, bl_step.cpp): the cone
// over A_i's wall triangles closes the band triangles of that layer.
//
// Limits (Error::NotImplemented, naming the place): a slide patch must be planar where the
// layers slide on it (a plane, or planar faces meeting at edges); a column cannot slide along
// more than one such edge; a vertex of a wall and of a patch that is neither a wall nor a slide
// patch is refused (InvalidArgument) with the label to add to the slide patches.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "layers/layers.hpp"

namespace anitet {

struct SlidePatchChange {
  int32_t label = 0;
  size_t triangles_before = 0;   // the patch's triangles in the input
  size_t triangles_after = 0;    // in the surface meshed
  size_t band_triangles = 0;     // of those, the prisms' side faces
  size_t dropped_vertices = 0;   // the patch's vertices inside or next to the band, left out
};

struct SlideSurface {
  SurfaceMesh surface;                // the input, its slide patches re-triangulated; the new
                                      // column points after the input's vertices
  std::vector<uint32_t> column_next;  // per vertex of `surface`: the next point of its junction
                                      // column (TetMesh::kNone: none)
  std::vector<SlidePatchChange> changes;  // per slide patch a wall meets, by label
  size_t junction_vertices = 0;       // wall vertices on a slide patch (columns that slide)
  size_t reduced_columns = 0;         // of those, columns lowered below 90% of h0 r^i (fronts
                                      // across, the patch's own edge, gradation)
};

// What a run reports of them: SlideSurface without the columns.
struct SlideReport {
  SurfaceMesh surface;  // the surface meshed: the input, its slide patches re-triangulated
  std::vector<SlidePatchChange> changes;
  size_t junction_vertices = 0;  // wall vertices on a slide patch
  size_t reduced_columns = 0;    // of those, columns lowered below 90% of h0 r^i before stage 1
};
SlideReport slide_report(SlideSurface&& slid);

// The surface with the slide patches re-triangulated and the junction columns (see above).
// `surface` must be valid (closed, oriented, no self-intersection). Errors: InvalidArgument for
// a label both a wall and a slide patch, or a wall meeting a patch that is neither;
// NotImplemented for the limits above.
Result<SlideSurface> slide_boundary_layer(const SurfaceMesh& surface, const BoundaryLayerOptions& bl);

}  // namespace anitet
