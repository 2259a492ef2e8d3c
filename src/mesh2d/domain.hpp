// Which faces of an input PSLG are meshed: the input's conforming Delaunay triangulation (Steiner
// points on its segments allowed: it is only used to classify) split into faces by the segments;
// the unbounded face and the faces holding a hole point are outside, the others inside with the
// attribute of their region point (Triangle's rule), or, for GeoJSON, the faces inside the
// polygons. Refuses holes or regions outside the domain, segments with no inside face on either
// side, and points (on no segment) outside, naming them.
#pragma once

#include <cstdint>
#include <vector>

#include "core/status.hpp"
#include "mesh2d/pslg.hpp"
#include "mesh2d/triangulation.hpp"

namespace anitet::mesh2d {

struct Domain {
  Triangulation mesh;                  // the classification triangulation (tags: segment index)
  std::vector<uint32_t> face;          // per triangle slot
  std::vector<uint8_t> face_inside;    // per face
  std::vector<double> face_attribute;  // per face
  std::vector<double> face_max_area;   // per face (<= 0: none)
  // Per segment: bit 0 when the face on its left (from seg[2i] to seg[2i+1]) is inside, bit 1
  // when the face on its right is.
  std::vector<uint8_t> sides;
  std::vector<uint32_t> free_points;   // input points on no segment (all inside)
  uint32_t outer_face = kNone;         // the unbounded face

  // The face holding p (outer_face beyond the triangulation's box), kNone when p lies on a
  // segment or a point; `hint`: a triangle to start the walk from (updated).
  uint32_t face_at(const double p[2], uint32_t& hint) const;
};

// Checks the PSLG (check_pslg) and classifies its faces.
Result<Domain> analyse_domain(const Pslg& pslg);

}  // namespace anitet::mesh2d
