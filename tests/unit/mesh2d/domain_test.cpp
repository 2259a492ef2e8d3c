// The input's faces: holes and regions (Triangle's rules), interfaces between regions, the
// bad inputs refused with their element named, points on no segment, regional area bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mesh2d/domain.hpp"
#include "mesh2d/mesher2.hpp"

namespace anitet::mesh2d {
namespace {

// The square [0, 2]^2 split by the segment x = 1 into two regions (points 4, 5 on the sides).
Pslg two_regions() {
  Pslg p;
  p.name = "two.poly";
  p.xy = {0, 0, 1, 0, 2, 0, 2, 2, 1, 2, 0, 2};
  p.seg = {0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 0, 1, 4};
  p.label = {1, 1, 1, 1, 1, 1, 9};
  p.regions = {Region{0.5, 1, 10, -1}, Region{1.5, 1, 20, 0.01}};
  return p;
}

TEST(Mesh2dDomain, RegionsAndTheirInterface) {
  const Pslg p = two_regions();
  Result<Domain> d = analyse_domain(p);
  ASSERT_TRUE(d.ok()) << d.status().message();
  EXPECT_EQ(d->sides[6], 3);  // the interface: inside on both sides
  EXPECT_EQ(d->sides[0], 1);  // the outer loop runs counter-clockwise: inside on its left
  Mesh2dOptions o;
  o.sizing.hsize = 0.25;
  o.split_segments = true;  // the unit-long segments would bound the triangles along them
  Result<TriMesh2> m = mesh_pslg(p, o);
  ASSERT_TRUE(m.ok()) << m.status().message();
  // The right region's triangles are small (area bound 0.01), and both regions are covered.
  double left = 0, right = 0, largest_right = 0;
  for (size_t t = 0; t < m->num_triangles(); ++t) {
    const double* a = &m->xy[2 * size_t(m->tri[3 * t])];
    const double* b = &m->xy[2 * size_t(m->tri[3 * t + 1])];
    const double* c = &m->xy[2 * size_t(m->tri[3 * t + 2])];
    const double ar = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    if (m->attribute[t] == 20.0) right += ar, largest_right = std::max(largest_right, ar);
    else left += ar;
  }
  EXPECT_NEAR(left, 2.0, 1e-12);
  EXPECT_NEAR(right, 2.0, 1e-12);
  EXPECT_LT(largest_right, 0.011);  // the bound, to the edges' tolerance
  // The interface is kept as edges with its label.
  size_t nines = 0;
  for (int32_t l : m->edge_label) nines += l == 9;
  EXPECT_GE(nines, 1u);
}

TEST(Mesh2dDomain, BadInputsNameTheirElement) {
  auto refused = [](Pslg p, Error code, const std::string& named) {
    Result<Domain> d = analyse_domain(p);
    ASSERT_FALSE(d.ok()) << named;
    EXPECT_EQ(d.status().code(), code) << d.status().message();
    EXPECT_NE(d.status().message().find(named), std::string::npos) << d.status().message();
  };
  // A bridge from the outer square to an island: the same face on both sides.
  Pslg bridge;
  bridge.xy = {0, 0, 4, 0, 4, 4, 0, 4, 1, 1, 2, 1, 2, 2, 1, 2};
  bridge.seg = {0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4, 0, 4};
  bridge.label.assign(9, 0);
  refused(bridge, Error::OpenBoundary, "segment 9 has the same face on both sides");
  // A hole point on a segment, a region outside, a point outside.
  Pslg p = two_regions();
  p.holes = {1, 1};
  refused(p, Error::InvalidArgument, "hole 1 lies on a segment");
  p = two_regions();
  p.regions.push_back(Region{5, 5, 1, -1});
  refused(p, Error::InvalidArgument, "region 3 lies outside the domain");
  p = two_regions();
  p.xy.insert(p.xy.end(), {3, 3});
  refused(p, Error::InvalidArgument, "point 7 is on no segment and lies outside the domain");
  // Two points at one place; a segment from a point to itself; a zero-length input.
  p = two_regions();
  p.xy[2] = 0, p.xy[3] = 0;
  refused(p, Error::DuplicatePoint, "point 1 and point 2 are at the same place");
  // Every face a hole.
  p = two_regions();
  p.regions.clear();
  p.holes = {0.5, 1, 1.5, 1};
  refused(p, Error::EmptyInput, "no domain is left");
}

TEST(Mesh2dDomain, PointsOnNoSegmentAreMeshVertices) {
  Pslg p = two_regions();
  p.xy.insert(p.xy.end(), {0.3, 0.7, 1.6, 1.2});
  Mesh2dOptions o;
  o.sizing.hsize = 0.5;
  Result<TriMesh2> m = mesh_pslg(p, o);
  ASSERT_TRUE(m.ok()) << m.status().message();
  EXPECT_EQ(m->xy[12], 0.3);  // kept as given, in the input's order
  EXPECT_EQ(m->xy[15], 1.2);
  size_t uses = 0;
  for (uint32_t v : m->tri) uses += v == 6 || v == 7;
  EXPECT_GE(uses, 6u);
}

}  // namespace
}  // namespace anitet::mesh2d
