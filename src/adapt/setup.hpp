// Adaptation's setup and output: the working mesh from a VolumeMesh (checks, adjacency, boundary
// faces and labels), the surface's features and normals, and the VolumeMesh written back.
#pragma once

#include <cstddef>
#include <cstdint>

#include "adapt/adapt_mesh.hpp"
#include "core/status.hpp"
#include "core/volume_mesh.hpp"

namespace anitet::adapt {

// A boundary face between two regions that no input triangle lists: kept as a surface, not
// written out.
constexpr int32_t kUnlisted = INT32_MIN;

// Points (coordinates only: metrics, tags and geometry are the caller's) and tets of `in`, with
// the adjacency and the boundary faces: every input boundary triangle (its label), every hull face
// (label 0 when no triangle lists it) and every face between tets of different regions (kUnlisted
// when none does). Error::InvalidArgument naming (1-based) a tet that is inverted or flat (exact
// orient3d), a boundary triangle that is no face of the tets; Error::InvalidMesh for a face of
// three tets; Error::EmptyInput without tets.
Status build_adapt_mesh(const VolumeMesh& in, AdaptMesh& out);

struct SurfaceFeatures {
  size_t ridge_edges = 0, corners = 0, boundary_points = 0;
};

// Tags the boundary points (kBoundary; kRequired for all with keep_surface), finds the ridges
// (dihedral angle between the normals of two boundary faces over ridge_angle_deg, two labels, or
// an edge of other than two boundary faces) and corners (ends and crossings of ridges, a ridge
// turning by more than ridge_angle_deg, a point where the surface is not one fan), and sets the
// normals (angle-weighted means of the faces' on each side of a ridge) and ridge tangents.
SurfaceFeatures analyse_surface(AdaptMesh& mesh, double ridge_angle_deg, bool keep_surface);

// The live tets, compacted with their points (in the order of their first use), regions, the
// boundary faces as triangles (hull faces oriented out of the mesh, an interface once, kUnlisted
// ones left out) and the metric at the points.
VolumeMesh export_mesh(const AdaptMesh& mesh);

}  // namespace anitet::adapt
