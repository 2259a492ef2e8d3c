// The exact test that keeps stage 1 valid: does a new tet fit into the region bounded by the
// front, touching the front only where it should?
//
// A tet K fits when
//   1. it is positive (exact orient3d);
//   2. each facet of K that is already a front triangle ("closing" facet: the base, or a facet
//      shared with a tet built just before) is oriented so that K lies on the region's side of it;
//   3. no other front triangle T meets K beyond the corners and edges they share: T does not meet
//      a new (non-closing) facet of K beyond their common corners (exact triangle-triangle test,
//      validate/tri_intersect.hpp), and no corner of T that is not a corner of K lies in the
//      closed K.
// Why that suffices: if a front triangle met K elsewhere, either it crosses K's boundary (caught
// by 3, the closing facets being front triangles that the valid front keeps apart from T) or it
// lies inside K without touching the boundary (then its corners are inside K: caught by 3). So the
// front meets K only in its closing facets and shared lower faces; K's interior is connected,
// touches the region next to a closing facet (by 2), hence lies in the region, and the new front
// (closing facets removed, new facets added) bounds the region minus K.
#pragma once

#include <cstdint>
#include <vector>

#include "layers/front.hpp"

namespace anitet::layers {

struct FitCounters {
  uint64_t tests = 0;        // tet_fits calls
  uint64_t candidates = 0;   // front triangles whose box overlapped the tet's box
  uint64_t tri_tests = 0;    // exact triangle-triangle tests run
};

// v: the tet's vertex ids (coordinates in xyz). On success closing[i] is the front triangle equal
// to facet i of v (kFacetVertex order), or Front::kNone for a new facet.
bool tet_fits(const Front& front, const std::vector<double>& xyz, const uint32_t v[4],
              uint32_t closing[4], FitCounters& counters);

// The same test with the front triangles to look at given: `near` holds every alive front
// triangle whose box overlaps the tet's (it may hold others, and dead slots, which are skipped;
// a triangle listed twice is tested twice). A cone of tets over one apex asks the octree once for
// all of them (LayerBuilder::join_to_front).
bool tet_fits(const Front& front, const std::vector<double>& xyz, const uint32_t v[4],
              uint32_t closing[4], FitCounters& counters, const std::vector<uint32_t>& near);

}  // namespace anitet::layers
