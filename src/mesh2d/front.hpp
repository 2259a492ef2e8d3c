// Stage 1 in 2D: a layer of triangles on the input's front edges (the segments' sides facing the
// domain), so that no input segment is on the new front S1 (the paper's section 3, Lemmas 3.1
// and 3.2 in the plane). Each front edge ab gets a triangle abq: q the neighbouring front
// vertex when the corner there is sharp and the triangle closes it well, else a new point on
// ab's inward normal at the height of an equilateral triangle in the metric, halved until the
// triangle meets no front edge and holds no front vertex (exact tests). In 2D the input's points
// may stay on S1: a point cannot be split, so the conforming recovery of S1 never adds points on
// the input, which is what the 3D method's second step (pushing S's edges off) is for.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/sizing.hpp"
#include "core/status.hpp"

namespace anitet::mesh2d {

struct FrontOptions {
  int layers = 1;                       // layers of triangles (each on the last one's front)
  const SizingField* field = nullptr;   // the apex height is measured in its metric (at z = 0)
  double close_angle_deg = 80.0;        // a corner below this may be closed on the next vertex
};

struct FrontResult {
  std::vector<uint32_t> tri;      // T1: 3 vertices per triangle, counter-clockwise
  std::vector<int32_t> tri_tag;   // 3 per triangle: the input segment on edge k (opposite vertex k), or -1
  std::vector<uint32_t> s1;       // S1: 2 vertices per edge, the unmeshed side on the left
  std::vector<uint32_t> s1_tri;   // per S1 edge: its T1 triangle (on its right)
  size_t halvings = 0;            // apex heights halved (the lemma's epsilon halving)
  size_t closed = 0;              // triangles closed on a neighbouring front vertex
};

// `edges`: the input's front edges (2 vertices each, the domain on their left), with `edge_seg`
// their input segments; xy (2 per vertex) gets the new apexes appended. When no apex can be
// placed on an edge, an error with *failed_segment set to its input segment (kFree past the
// first layer): by the lemma, the domain beside it is thinner than the doubles around it can
// resolve (or the front is corrupt).
Result<FrontResult> build_front(std::vector<double>& xy, const std::vector<uint32_t>& edges,
                                const std::vector<int32_t>& edge_seg, const FrontOptions& options,
                                int32_t* failed_segment = nullptr);

// Whether q lies strictly inside the sector swept counter-clockwise from the ray o->p1 to the
// ray o->p2 (exact). A sector of 360 degrees (p1, p2 on one ray) excludes only that ray.
bool in_sector(const double* o, const double* p1, const double* p2, const double* q);

}  // namespace anitet::mesh2d
