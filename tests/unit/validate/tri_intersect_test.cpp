#include <gtest/gtest.h>

#include <array>
#include <random>

#include "validate/shells.hpp"
#include "validate/tri_intersect.hpp"

namespace anitet {
namespace {

using P = std::array<double, 3>;
using Tri = std::array<P, 3>;

// The answer must not depend on the order of the triangles or the rotation of their corners.
bool intersect(const Tri& a, const Tri& b) {
  const auto test = [](const Tri& x, const Tri& y, int rx, int ry) {
    const double* t1[3] = {x[rx % 3].data(), x[(rx + 1) % 3].data(), x[(rx + 2) % 3].data()};
    const double* t2[3] = {y[ry % 3].data(), y[(ry + 1) % 3].data(), y[(ry + 2) % 3].data()};
    return tri_intersect::triangles_intersect(t1, t2);
  };
  const bool first = test(a, b, 0, 0);
  for (int rx = 0; rx < 3; ++rx) {
    for (int ry = 0; ry < 3; ++ry) {
      EXPECT_EQ(test(a, b, rx, ry), first);
      EXPECT_EQ(test(b, a, ry, rx), first);
    }
  }
  return first;
}

const Tri kBase = {P{0, 0, 0}, P{4, 0, 0}, P{0, 4, 0}};

TEST(TriIntersect, DisjointTriangles) {
  EXPECT_FALSE(intersect(kBase, Tri{P{0, 0, 1}, P{4, 0, 1}, P{0, 4, 1}}));  // parallel
  EXPECT_FALSE(intersect(kBase, Tri{P{3, 3, -1}, P{3, 3, 1}, P{5, 5, 0}}));  // beyond hypotenuse
  EXPECT_FALSE(intersect(kBase, Tri{P{5, 0, 0}, P{6, 0, 0}, P{5, 1, 0}}));  // coplanar, apart
}

TEST(TriIntersect, PiercingAndTouchingWithoutSharedCorners) {
  EXPECT_TRUE(intersect(kBase, Tri{P{1, 1, -1}, P{1, 1, 1}, P{2, 1, 1}}));   // edge pierces
  EXPECT_TRUE(intersect(kBase, Tri{P{1, 1, 0}, P{1, 2, 1}, P{2, 1, 1}}));    // vertex on face
  EXPECT_TRUE(intersect(kBase, Tri{P{1, 1, 0}, P{2, 1, 0}, P{1, 1, 1}}));    // edge on face
  EXPECT_TRUE(intersect(kBase, Tri{P{2, 2, 0}, P{5, 5, 1}, P{5, 5, -1}}));   // vertex on edge
  EXPECT_FALSE(intersect(kBase, Tri{P{4, 0, 0}, P{5, 0, 1}, P{5, 1, 1}}));  // a corner only
  EXPECT_FALSE(intersect(kBase, Tri{P{2.5, 2.5, 0}, P{5, 5, 1}, P{5, 5, -1}}));  // just beyond
}

TEST(TriIntersect, CoplanarWithoutSharedCorners) {
  EXPECT_TRUE(intersect(kBase, Tri{P{1, 1, 0}, P{5, 1, 0}, P{1, 5, 0}}));    // overlap
  EXPECT_TRUE(intersect(kBase, Tri{P{1, 1, 0}, P{1.5, 1, 0}, P{1, 1.5, 0}}));  // inside
  EXPECT_TRUE(intersect(kBase, Tri{P{2, 2, 0}, P{5, 2, 0}, P{2, 5, 0}}));    // corner on edge
  EXPECT_FALSE(intersect(kBase, Tri{P{4, 0, 0}, P{8, 0, 0}, P{4, -1, 0}}));  // a corner only
  // Collinear edges overlapping.
  EXPECT_TRUE(intersect(kBase, Tri{P{2, 0, 0}, P{6, 0, 0}, P{4, -1, 0}}));
  EXPECT_FALSE(intersect(kBase, Tri{P{3, 3, 0}, P{6, 3, 0}, P{3, 6, 0}}));
}

TEST(TriIntersect, SharedCorner) {
  // Non-coplanar, meeting at the corner only.
  EXPECT_FALSE(intersect(kBase, Tri{P{0, 0, 0}, P{-1, 0, 1}, P{0, -1, 1}}));
  EXPECT_FALSE(intersect(kBase, Tri{P{0, 0, 0}, P{1, 1, 1}, P{2, 0, 1}}));
  // The opposite edge of the second triangle pierces the first.
  EXPECT_TRUE(intersect(kBase, Tri{P{0, 0, 0}, P{1, 1, -1}, P{1, 1, 1}}));
  // An edge from the shared corner runs inside the first triangle.
  EXPECT_TRUE(intersect(kBase, Tri{P{0, 0, 0}, P{1, 1, 0}, P{0, 0, 1}}));
  // An edge from the shared corner runs along the first triangle's edge.
  EXPECT_TRUE(intersect(kBase, Tri{P{0, 0, 0}, P{2, 0, 0}, P{0, 0, 1}}));
  // ... or away from it (opposite direction): only the corner.
  EXPECT_FALSE(intersect(kBase, Tri{P{0, 0, 0}, P{-2, 0, 0}, P{0, 0, 1}}));
  // Coplanar wedges: overlapping, disjoint, and sharing a ray.
  EXPECT_TRUE(intersect(kBase, Tri{P{0, 0, 0}, P{2, 1, 0}, P{-1, 3, 0}}));
  EXPECT_FALSE(intersect(kBase, Tri{P{0, 0, 0}, P{-1, 0, 0}, P{-1, -1, 0}}));
  EXPECT_FALSE(intersect(kBase, Tri{P{0, 0, 0}, P{0, -3, 0}, P{-3, 0, 0}}));
  EXPECT_TRUE(intersect(kBase, Tri{P{0, 0, 0}, P{0, -3, 0}, P{1, 0, 0}}));  // shares ray +x
  EXPECT_FALSE(intersect(kBase, Tri{P{0, 0, 0}, P{-1, 5, 0}, P{-4, 0, 0}}));
}

TEST(TriIntersect, SharedEdge) {
  EXPECT_FALSE(intersect(kBase, Tri{P{4, 0, 0}, P{0, 4, 0}, P{3, 3, 1}}));   // folded
  EXPECT_FALSE(intersect(kBase, Tri{P{4, 0, 0}, P{0, 4, 0}, P{3, 3, 0}}));   // flat, other side
  EXPECT_TRUE(intersect(kBase, Tri{P{4, 0, 0}, P{0, 4, 0}, P{1, 1, 0}}));    // flat, same side
  EXPECT_TRUE(intersect(kBase, Tri{P{4, 0, 0}, P{0, 4, 0}, P{-5, -5, 0}}));  // covers it
  // Duplicates are not intersections (they are reported as duplicates).
  EXPECT_FALSE(intersect(kBase, Tri{P{0, 4, 0}, P{4, 0, 0}, P{0, 0, 0}}));
}

TEST(TriIntersect, SegmentHitsTriangle) {
  const double a[3] = {0, 0, 0}, b[3] = {4, 0, 0}, c[3] = {0, 4, 0};
  const double p[3] = {1, 1, -1}, q[3] = {1, 1, 1}, r[3] = {1, 1, 0.5}, e[3] = {0, 0, 5};
  const double in1[3] = {1, 1, 0}, out1[3] = {5, 5, 0}, out2[3] = {6, 5, 0};
  EXPECT_TRUE(tri_intersect::segment_hits_triangle(p, q, a, b, c));
  EXPECT_FALSE(tri_intersect::segment_hits_triangle(r, q, a, b, c));
  EXPECT_TRUE(tri_intersect::segment_hits_triangle(a, e, a, b, c));  // touches a corner
  EXPECT_TRUE(tri_intersect::segment_hits_triangle(in1, out1, a, b, c));  // coplanar, crossing
  EXPECT_FALSE(tri_intersect::segment_hits_triangle(out1, out2, a, b, c));
}

// Points exactly in line with the edges, diagonals and corners of a cube must still be classified
// correctly by ray parity (the symbolic perturbation decides the degenerate crossings).
TEST(RayParity, CubeWithDegenerateRays) {
  // Cube [0, 2]^3 split as in test_surfaces.hpp.
  std::vector<P> v;
  for (int i = 0; i < 8; ++i) {
    v.push_back(P{(i & 1) ? 2.0 : 0.0, (i & 2) ? 2.0 : 0.0, (i & 4) ? 2.0 : 0.0});
  }
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<std::array<int, 3>> tris;
  for (const auto& q : quads) {
    tris.push_back({q[0], q[1], q[2]});
    tris.push_back({q[0], q[2], q[3]});
  }
  const double coords[] = {-1, 0, 0.5, 1, 2, 3};
  int tested = 0, inside = 0;
  for (double x : coords) {
    for (double y : coords) {
      for (double z : coords) {
        const P p{x, y, z};
        const auto in_open = [](double c) { return c > 0 && c < 2; };
        const auto in_closed = [](double c) { return c >= 0 && c <= 2; };
        const bool on_surface = in_closed(x) && in_closed(y) && in_closed(z) &&
                                !(in_open(x) && in_open(y) && in_open(z));
        if (on_surface) continue;
        int crossings = 0;
        for (const auto& t : tris) {
          crossings += shells::ray_crosses(p.data(), v[t[0]].data(), v[t[1]].data(),
                                           v[t[2]].data());
        }
        const bool want = in_open(x) && in_open(y) && in_open(z);
        EXPECT_EQ(crossings % 2 == 1, want) << x << " " << y << " " << z;
        ++tested;
        inside += want;
      }
    }
  }
  EXPECT_EQ(inside, 8);
  EXPECT_GT(tested, 100);
}

}  // namespace
}  // namespace anitet
