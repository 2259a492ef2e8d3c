// Small input angles when points may go on segments (--split-segments): the segments at a sharp
// corner (two segments less than 60 degrees apart on the domain's side) are split at the same
// distances from it, powers of two ("concentric shells", after Ruppert and Shewchuk), so the
// triangle in the corner stays isosceles and the mesh beyond it can be good.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mesh2d/metric2.hpp"
#include "mesh2d/triangulation.hpp"

namespace anitet::mesh2d {

// Whether v is a sharp corner; `ends` gets the other ends of its constrained edges and
// `shortest` their shortest length.
bool sharp_corner(const Triangulation& mesh, uint32_t v, std::vector<uint32_t>& ends, double& shortest);

// Splits every constrained edge at v at distance d from v (those shorter than 1.5 d are left);
// the new points are fixed (they keep the shells concentric). Returns the points inserted.
size_t split_corner(Triangulation& mesh, VertexMetrics& metrics, std::vector<uint8_t>& fixed, uint32_t v, double d);

// The first shells: at each sharp corner among the vertices [0, count) and mesh.copies, at the
// power of two below half its shortest segment and the size there.
size_t split_sharp_corners(Triangulation& mesh, VertexMetrics& metrics, std::vector<uint8_t>& fixed, uint32_t count);

// Splits the constrained edge k of t: at a shell when one end is a sharp corner, else at its
// midpoint. Returns the points inserted.
size_t split_segment_piece(Triangulation& mesh, VertexMetrics& metrics, std::vector<uint8_t>& fixed, uint32_t t, int k);

}  // namespace anitet::mesh2d
