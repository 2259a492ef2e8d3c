#include "layers/tet_fit.hpp"

#include <algorithm>

#include "core/tet_mesh.hpp"
#include "predicates/predicates.hpp"
#include "validate/tri_intersect.hpp"

namespace anitet::layers {

namespace {

Box3 box_of(const double* const* p, int n) {
  Box3 b;
  for (int k = 0; k < 3; ++k) {
    b.lo[k] = b.hi[k] = p[0][k];
    for (int i = 1; i < n; ++i) {
      b.lo[k] = std::min(b.lo[k], p[i][k]);
      b.hi[k] = std::max(b.hi[k], p[i][k]);
    }
  }
  return b;
}

// (t0 t1 t2) is a cyclic rotation of (f0 f2 f1): the same triangle, opposite orientation.
bool reversed(const uint32_t* t, const uint32_t f[3]) {
  for (int r = 0; r < 3; ++r)
    if (t[r] == f[0] && t[(r + 1) % 3] == f[2] && t[(r + 2) % 3] == f[1]) return true;
  return false;
}

// Whether one facet's plane keeps the front triangle t (corners q) off the closed tet except where
// they share corners: every corner of t that is a corner of the tet is a corner of that facet,
// and every other corner lies strictly on the far side of its plane (exact). Then t meets the tet
// only in shared corners or a shared edge, and no triangle-triangle test below could find more.
bool separated(const uint32_t v[4], const double* const facet[4][3], const uint32_t* t,
               const double* const q[3]) {
  int corner[3];  // the tet corner each corner of t is, or -1
  for (int k = 0; k < 3; ++k) {
    corner[k] = -1;
    for (int j = 0; j < 4; ++j)
      if (t[k] == v[j]) corner[k] = j;
  }
  for (int i = 0; i < 4; ++i) {
    // Facet i holds every tet corner but v[i] (kFacetVertex).
    if (corner[0] == i || corner[1] == i || corner[2] == i) continue;
    bool apart = true;
    for (int k = 0; k < 3 && apart; ++k)
      if (corner[k] < 0)
        apart = predicates::orient3d(facet[i][0], facet[i][1], facet[i][2], q[k]) < 0;
    if (apart) return true;
  }
  return false;
}

}  // namespace

namespace {

// The test, with for_near(box, visit) calling visit(f) for (at least) every alive front triangle
// whose box overlaps `box`, until visit returns false.
template <class ForNear>
bool fits(const Front& front, const std::vector<double>& xyz, const uint32_t v[4], uint32_t closing[4],
          FitCounters& counters, ForNear&& for_near) {
  ++counters.tests;
  const double* p[4];
  for (int i = 0; i < 4; ++i) p[i] = &xyz[3 * size_t(v[i])];
  if (predicates::orient3d(p[0], p[1], p[2], p[3]) <= 0) return false;

  const double* facet[4][3];
  Box3 facet_box[4];
  for (int i = 0; i < 4; ++i) {
    uint32_t f[3];
    for (int k = 0; k < 3; ++k) {
      f[k] = v[kFacetVertex[i][k]];
      facet[i][k] = p[kFacetVertex[i][k]];
    }
    closing[i] = front.find(f[0], f[1], f[2]);
    // A closing facet must face the region: the front triangle is K's facet reversed.
    if (closing[i] != Front::kNone && !reversed(front.tri(closing[i]), f)) return false;
    facet_box[i] = box_of(facet[i], 3);
  }

  const Box3 tet_box = box_of(p, 4);
  bool fits = true;
  for_near(tet_box, [&](uint32_t f) {
    if (f == closing[0] || f == closing[1] || f == closing[2] || f == closing[3]) return true;
    ++counters.candidates;
    const uint32_t* t = front.tri(f);
    const double* q[3];
    for (int k = 0; k < 3; ++k) {
      q[k] = &xyz[3 * size_t(t[k])];
      if (t[k] == v[0] || t[k] == v[1] || t[k] == v[2] || t[k] == v[3]) continue;
      // Outside the tet's box, outside the closed tet: the exact tests below would say so too.
      if (q[k][0] < tet_box.lo[0] || q[k][0] > tet_box.hi[0] || q[k][1] < tet_box.lo[1] ||
          q[k][1] > tet_box.hi[1] || q[k][2] < tet_box.lo[2] || q[k][2] > tet_box.hi[2])
        continue;
      // A front vertex in the closed tet: the tet would swallow or touch front that it must not.
      bool inside = true;
      for (int i = 0; i < 4 && inside; ++i)
        inside = predicates::orient3d(facet[i][0], facet[i][1], facet[i][2], q[k]) >= 0;
      if (inside) {
        fits = false;
        return false;
      }
    }
    const Box3& tb = front.box(f);
    if (separated(v, facet, t, q)) return true;
    for (int i = 0; i < 4; ++i) {
      if (closing[i] != Front::kNone || !boxes_overlap(facet_box[i], tb)) continue;
      ++counters.tri_tests;
      if (tri_intersect::triangles_intersect(facet[i], q)) {
        fits = false;
        return false;
      }
    }
    return true;
  });
  return fits;
}

}  // namespace

bool tet_fits(const Front& front, const std::vector<double>& xyz, const uint32_t v[4], uint32_t closing[4],
              FitCounters& counters) {
  return fits(front, xyz, v, closing, counters,
              [&](const Box3& box, auto&& visit) { front.near(box, visit); });
}

bool tet_fits(const Front& front, const std::vector<double>& xyz, const uint32_t v[4], uint32_t closing[4],
              FitCounters& counters, const std::vector<uint32_t>& near) {
  return fits(front, xyz, v, closing, counters, [&](const Box3& box, auto&& visit) {
    for (uint32_t f : near)
      if (front.alive(f) && boxes_overlap(front.box(f), box) && !visit(f)) return;
  });
}

}  // namespace anitet::layers
