// The input of the 2D mesher: a planar straight-line graph (PSLG) with holes and regions, as
// Triangle's .poly files hold it, and its checks.
//
// Segments bound the domain (unless `polygons` gives it): every face of the planar graph that holds a hole point, and the
// unbounded face, is outside; every other face is inside, with the attribute of the region point
// in it (0 without one). A segment between two inside faces is an interface: the mesh keeps it
// too. Points on no segment are mesh vertices too (when inside).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.hpp"

namespace anitet::mesh2d {

struct Region {
  double x = 0, y = 0;
  double attribute = 0;
  double max_area = -1;  // Triangle's regional area bound; <= 0: none
};

// Where an element came from, for messages: the file's line, or a GeoJSON ring's place.
struct Origin {
  uint32_t line = 0;     // 1-based line of a text file (0: none)
  uint32_t feature = 0;  // GeoJSON: 1-based feature, polygon, ring, vertex (0: none)
  uint32_t polygon = 0, ring = 0, vertex = 0;
};

// A polygon of a GeoJSON input: its rings (outer first), as closed lists of point indices.
struct PolygonRings {
  std::vector<std::vector<uint32_t>> rings;
  double attribute = 0;
};

struct Pslg {
  std::string name;             // the file's name, for messages
  std::vector<double> xy;       // 2 per point
  std::vector<uint32_t> seg;    // 2 per segment (0-based point indices)
  std::vector<int32_t> label;   // per segment: its boundary marker / reference / label
  std::vector<double> holes;    // 2 per hole point
  std::vector<Region> regions;
  // When not empty (GeoJSON), the domain is the union of these polygons (each by the even-odd
  // rule over its rings), a face taking the attribute of the first polygon holding it; holes
  // and regions are then unused.
  std::vector<PolygonRings> polygons;
  // Optional (empty, or one per element): where each came from.
  std::vector<Origin> point_origin, seg_origin, hole_origin, region_origin;
  // The number the file gave the first element (Triangle's .poly may count from 0 or 1): the
  // messages name elements the way the file does.
  int first_index = 1;

  size_t num_points() const { return xy.size() / 2; }
  size_t num_segments() const { return seg.size() / 2; }
  size_t num_holes() const { return holes.size() / 2; }
  const double* point(size_t i) const { return &xy[2 * i]; }
};

// "point 12 (line 30)", "segment 4 (feature 1, polygon 1, ring 2, vertex 3)", "hole 1 (line 9)".
std::string describe_point(const Pslg& pslg, size_t i);
std::string describe_segment(const Pslg& pslg, size_t i);
std::string describe_hole(const Pslg& pslg, size_t i);
std::string describe_region(const Pslg& pslg, size_t i);

// The checks that need no triangulation, each naming the first offending elements (prefixed
// with the file's name): finite coordinates (NonFiniteCoordinate), segment ends (BadIndex), a
// segment from a point to itself (InvalidArgument), two points at one place (DuplicatePoint),
// two segments on the same two points (InvalidArgument), an open loop: a point ending one
// segment only (OpenBoundary; analyse_domain finds the other dangling segments), two segments
// crossing or touching anywhere but at a shared
// end, or a point on a segment (SelfIntersection; exact tests). EmptyInput without 3 segments.
Status check_pslg(const Pslg& pslg);

}  // namespace anitet::mesh2d
