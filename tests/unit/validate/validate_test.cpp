#include "validate/validate.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "test_surfaces.hpp"

namespace anitet {
namespace {

using test::add_cube;

size_t errors(const ValidationReport& r) {
  size_t n = 0;
  for (const Problem& p : r.problems) n += p.severity == Severity::Error ? 1 : 0;
  return n;
}

const Repair* find_repair(const ValidationReport& r, const std::string& kind) {
  for (const Repair& x : r.repairs) {
    if (x.kind == kind) return &x;
  }
  return nullptr;
}

TEST(Validate, CleanCube) {
  SurfaceMesh s = test::cube();
  const SurfaceMesh before = s;
  const ValidationReport r = validate_surface(s);
  EXPECT_TRUE(r.ok()) << r.summary();
  EXPECT_TRUE(r.status().ok());
  EXPECT_TRUE(r.problems.empty());
  EXPECT_TRUE(r.repairs.empty());
  ASSERT_EQ(r.shells.size(), 1u);
  EXPECT_TRUE(r.shells[0].closed);
  EXPECT_EQ(r.shells[0].depth, 0);
  EXPECT_EQ(r.shells[0].parent, -1);
  EXPECT_EQ(r.shells[0].region, 0);
  EXPECT_NEAR(r.shells[0].signed_volume, 1.0, 1e-12);
  EXPECT_EQ(r.num_regions, 1u);
  EXPECT_EQ(s.tri, before.tri);
  EXPECT_EQ(s.xyz, before.xyz);
}

TEST(Validate, CleanSphere) {
  SurfaceMesh s = test::sphere(4);  // 2048 triangles
  const ValidationReport r = validate_surface(s);
  EXPECT_TRUE(r.ok()) << r.summary();
  EXPECT_EQ(r.shells.size(), 1u);
  EXPECT_NEAR(r.shells[0].signed_volume, 4.0 / 3.0 * M_PI, 0.05);
}

TEST(Validate, EmptyAndBadIndex) {
  SurfaceMesh empty;
  EXPECT_EQ(validate_surface(empty).status().code(), Error::EmptyInput);

  SurfaceMesh s = test::cube();
  s.add_triangle(0, 1, 99);
  const ValidationReport r = validate_surface(s);
  EXPECT_EQ(r.status().code(), Error::BadIndex);
  EXPECT_EQ(r.count(Error::BadIndex), 1u);
  ASSERT_EQ(r.problems[0].examples.size(), 1u);
  EXPECT_EQ(r.problems[0].examples[0].triangles[0], 12u);
  EXPECT_EQ(errors(r), 1u);  // nothing else was checked
}

TEST(Validate, NonFiniteCoordinate) {
  SurfaceMesh s = test::cube();
  s.xyz[3 * 5 + 1] = std::numeric_limits<double>::quiet_NaN();
  s.xyz[3 * 6 + 2] = std::numeric_limits<double>::infinity();
  const ValidationReport r = validate_surface(s);
  EXPECT_EQ(r.status().code(), Error::NonFiniteCoordinate);
  EXPECT_EQ(r.count(Error::NonFiniteCoordinate), 2u);
  EXPECT_EQ(r.problems[0].examples[0].vertices[0], 5u);
  EXPECT_TRUE(r.intersecting_pairs.empty());
  const nlohmann::json j = nlohmann::json::parse(report_to_json(r));  // NaN written as null
  EXPECT_TRUE(j["problems"][0]["examples"][0]["points"][0][1].is_null());
}

TEST(Validate, OpenBoundary) {
  SurfaceMesh s = test::cube();
  s.tri.resize(s.tri.size() - 3);  // drop the last triangle
  s.patch.pop_back();
  const ValidationReport r = validate_surface(s);
  EXPECT_EQ(r.status().code(), Error::OpenBoundary);
  EXPECT_EQ(r.count(Error::OpenBoundary), 3u);
  EXPECT_EQ(errors(r), 1u) << r.summary();
  ASSERT_EQ(r.shells.size(), 1u);
  EXPECT_FALSE(r.shells[0].closed);
  const Problem* p = r.find("open_boundary");
  ASSERT_NE(p, nullptr);
  ASSERT_EQ(p->examples[0].vertices.size(), 2u);
  ASSERT_EQ(p->examples[0].points.size(), 2u);
  EXPECT_EQ(p->examples[0].triangles.size(), 1u);
}

TEST(Validate, NonManifoldEdge) {
  SurfaceMesh s = test::cube();
  // A fin on the cube's edge (0, 1): the edge now has three triangles.
  s.add_vertex(0.5, -1.0, -1.0);
  s.add_triangle(0, 1, 8);
  const ValidationReport r = validate_surface(s);
  EXPECT_EQ(r.count(Error::NonManifoldEdge), 1u) << r.summary();
  EXPECT_EQ(r.count(Error::OpenBoundary), 2u);
  EXPECT_EQ(r.find("non_manifold_edge")->examples[0].triangles.size(), 3u);
}

TEST(Validate, NonManifoldVertexTwoCubesAtACorner) {
  SurfaceMesh s;
  add_cube(s, 0, 0, 0, 1);
  add_cube(s, 1, 1, 1, 1);  // its corner (1,1,1) is a copy of the first cube's corner
  const ValidationReport r = validate_surface(s);
  // The copy is merged (repair), which makes (1,1,1) a vertex with two fans.
  const Repair* merged = find_repair(r, "merged_duplicate_vertices");
  ASSERT_NE(merged, nullptr);
  EXPECT_EQ(merged->count, 1u);
  EXPECT_EQ(s.num_vertices(), 15u);
  ASSERT_EQ(r.vertex_map.size(), 16u);
  EXPECT_EQ(r.vertex_map[8], 7u);  // the second cube's corner (1,1,1) is the first's 7
  EXPECT_EQ(r.vertex_map[9], 8u);
  EXPECT_EQ(r.count(Error::NonManifoldVertex), 1u) << r.summary();
  EXPECT_EQ(errors(r), 1u) << r.summary();  // touching at a corner is not an intersection
  const Problem* p = r.find("non_manifold_vertex");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->examples[0].points[0], (std::array<double, 3>{1, 1, 1}));
  EXPECT_EQ(r.shells.size(), 2u);
  EXPECT_EQ(r.num_regions, 2u);
}

TEST(Validate, InconsistentOrientation) {
  SurfaceMesh s = test::cube();
  std::swap(s.tri[1], s.tri[2]);  // flip triangle 0
  ValidationOptions no_repair;
  no_repair.orient_triangles = false;
  SurfaceMesh kept = s;
  const ValidationReport r = validate_surface(kept, no_repair);
  EXPECT_EQ(r.status().code(), Error::InconsistentOrientation);
  EXPECT_EQ(r.count(Error::InconsistentOrientation), 3u);
  EXPECT_EQ(errors(r), 1u) << r.summary();
  EXPECT_FALSE(r.shells[0].closed);
  // The repair: the one triangle that disagrees with its neighbours is flipped back.
  const ValidationReport repaired = validate_surface(s);
  EXPECT_TRUE(repaired.ok()) << repaired.summary();
  ASSERT_NE(find_repair(repaired, "reoriented_triangles"), nullptr);
  EXPECT_EQ(find_repair(repaired, "reoriented_triangles")->count, 1u);
  EXPECT_EQ(s.tri, test::cube().tri);
  EXPECT_TRUE(repaired.shells[0].closed);
}

// A polygon soup of a closed surface (every triangle with its own corners, a random half of them
// facing the other way), as STL files of other tools often are: merged, reoriented consistently
// (the fewer triangles flipped), then outward; every triangle ends as in the original.
TEST(Validate, PolygonSoupFacingEitherWayIsReoriented) {
  const SurfaceMesh sphere = test::sphere(3);
  SurfaceMesh soup;
  std::mt19937 rng(7);
  size_t flipped = 0;
  for (size_t t = 0; t < sphere.num_triangles(); ++t) {
    const bool flip = rng() % 2 == 0;
    flipped += flip;
    for (int k : {0, flip ? 2 : 1, flip ? 1 : 2}) {
      const double* p = sphere.point(sphere.tri[3 * t + size_t(k)]);
      soup.add_vertex(p[0], p[1], p[2]);
    }
    soup.add_triangle(uint32_t(3 * t), uint32_t(3 * t + 1), uint32_t(3 * t + 2));
  }
  // Facing inward on the whole (more flipped than not): the shell repair turns it outward after.
  SurfaceMesh inward = soup;
  for (size_t t = 0; t < inward.num_triangles(); ++t) std::swap(inward.tri[3 * t + 1], inward.tri[3 * t + 2]);
  for (SurfaceMesh* s : {&soup, &inward}) {
    const ValidationReport r = validate_surface(*s);
    ASSERT_TRUE(r.ok()) << r.summary();
    const Repair* re = find_repair(r, "reoriented_triangles");
    ASSERT_NE(re, nullptr);
    EXPECT_EQ(re->count, std::min(flipped, sphere.num_triangles() - flipped));
    EXPECT_NE(re->message.find("to match their neighbours"), std::string::npos) << re->message;
    EXPECT_GT(r.shells[0].signed_volume, 0.0);
    // Each triangle faces as in the original sphere (outward): its normal points away from the centre.
    for (size_t t = 0; t < s->num_triangles(); ++t) {
      const double *a = s->point(s->tri[3 * t]), *b = s->point(s->tri[3 * t + 1]), *c = s->point(s->tri[3 * t + 2]);
      const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
      ASSERT_GT(n[0] * a[0] + n[1] * a[1] + n[2] * a[2], 0.0) << "triangle " << t;
    }
  }
}

// The real projective plane (6 vertices, 10 triangles, every edge on two): closed but no
// orientation agrees across all its edges. Refused, naming an edge; nothing flipped.
TEST(Validate, NonOrientableShellIsRefused) {
  SurfaceMesh s;
  const double p[6][3] = {{0, 0, 1}, {1, 0, 0}, {0.3, 0.95, 0}, {-0.8, 0.6, 0.1}, {-0.8, -0.6, 0.2}, {0.3, -0.95, 0.3}};
  for (const auto& q : p) s.add_vertex(q[0], q[1], q[2]);
  const uint32_t t[10][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 1},
                             {1, 2, 4}, {2, 3, 5}, {3, 4, 1}, {4, 5, 2}, {5, 1, 3}};
  for (const auto& c : t) s.add_triangle(c[0], c[1], c[2]);
  const SurfaceMesh before = s;
  const ValidationReport r = validate_surface(s);
  EXPECT_FALSE(r.ok());
  const Problem* p_no = r.find("non_orientable_shell");
  ASSERT_NE(p_no, nullptr) << r.summary();
  EXPECT_EQ(p_no->code, Error::InconsistentOrientation);
  EXPECT_NE(p_no->message.find("at edge ("), std::string::npos) << p_no->message;
  ASSERT_EQ(p_no->examples.size(), 1u);
  EXPECT_EQ(p_no->examples[0].vertices.size(), 2u);
  EXPECT_EQ(find_repair(r, "reoriented_triangles"), nullptr);
  EXPECT_EQ(s.tri, before.tri);
}

TEST(Validate, DegenerateTriangles) {
  SurfaceMesh s = test::cube();
  // Three exactly collinear points, and a triangle with a repeated vertex.
  s.add_vertex(3, 0, 0);
  s.add_vertex(4, 1, 0.5);
  s.add_vertex(5, 2, 1);
  s.add_triangle(8, 9, 10);
  s.add_triangle(9, 9, 10);
  const ValidationReport r = validate_surface(s);
  EXPECT_EQ(r.count(Error::DegenerateTriangle), 2u) << r.summary();
  const Problem* p = r.find("degenerate_triangle");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->examples[0].triangles[0], 12u);
  EXPECT_EQ(p->examples[1].triangles[0], 13u);
  EXPECT_EQ(r.count(Error::SelfIntersection), 0u);
}

TEST(Validate, AlmostCollinearIsNotDegenerate) {
  SurfaceMesh s;
  s.add_vertex(0, 0, 0);
  s.add_vertex(1, 1, 1);
  s.add_vertex(2, 2, std::nextafter(2.0, 3.0));
  s.add_triangle(0, 1, 2);
  const ValidationReport r = validate_surface(s);
  EXPECT_EQ(r.count(Error::DegenerateTriangle), 0u) << r.summary();
  EXPECT_EQ(r.count(Error::OpenBoundary), 3u);
}

TEST(Validate, DuplicateTriangle) {
  SurfaceMesh s = test::cube();
  s.add_triangle(s.tri[4], s.tri[5], s.tri[3]);  // triangle 1, rotated
  const ValidationReport r = validate_surface(s);
  EXPECT_EQ(r.count(Error::DuplicateTriangle), 1u) << r.summary();
  const Problem* p = r.find("duplicate_triangle");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->examples[0].triangles, (std::vector<uint32_t>{12, 1}));
  EXPECT_EQ(r.count(Error::NonManifoldEdge), 3u);
  EXPECT_EQ(r.count(Error::SelfIntersection), 0u);  // duplicates are not double-reported
}

// A bipyramid whose bottom apex is pulled up and out through a top face: the edge from e0 to
// the bottom apex pierces the top face (e1 e2 top).
TEST(Validate, SelfIntersectionPierced) {
  const double top[3] = {1, 1, 3}, bottom[3] = {3, 3, 1};
  SurfaceMesh s = test::bipyramid(top, bottom);
  const ValidationReport r = validate_surface(s);
  EXPECT_EQ(r.status().code(), Error::SelfIntersection) << r.summary();
  EXPECT_GT(r.count(Error::SelfIntersection), 0u);
  EXPECT_EQ(r.count(Error::IntersectingShells), 0u);
  EXPECT_EQ(r.count(Error::SelfIntersection), r.intersecting_pairs.size());
  const Problem* p = r.find("self_intersection");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->examples[0].triangles.size(), 2u);
  EXPECT_EQ(p->examples[0].points.size(), 6u);
  // The same apex below the equator is a valid bipyramid.
  const double below[3] = {1, 1, -3};
  SurfaceMesh ok = test::bipyramid(top, below);
  EXPECT_TRUE(validate_surface(ok).ok());
}

// The bottom apex lies inside a top face: two neighbours across edge e0-e1 overlap in a plane.
TEST(Validate, SelfIntersectionCoplanarNeighbours) {
  const double top[3] = {1, 1, 3};
  // A point of the face (e0 = (0,0,0), e1 = (4,0,0), top): e0 + 0.5 (e1 - e0) + 0.25 (top - e0).
  const double bottom[3] = {2.25, 0.25, 0.75};
  SurfaceMesh s = test::bipyramid(top, bottom);
  const ValidationReport r = validate_surface(s);
  ASSERT_GT(r.count(Error::SelfIntersection), 0u) << r.summary();
  // The coplanar neighbours are triangles 0 (e0 e1 top) and 1 (e1 e0 bottom).
  EXPECT_NE(std::find(r.intersecting_pairs.begin(), r.intersecting_pairs.end(),
                      std::make_pair(0u, 1u)),
            r.intersecting_pairs.end());
}

// A box whose top is dented down until one of its edges lies on the bottom face.
TEST(Validate, SelfIntersectionEdgeTouchingFace) {
  const std::vector<double> xs = {0, 1, 3, 4}, ys = {0, 2, 4};
  std::vector<double> z(12, 2.0);
  const double centre[2] = {2.5, 3.5};
  SurfaceMesh dent = test::heightfield_box(xs, ys, z, 0.0, centre);
  {
    SurfaceMesh copy = dent;
    const ValidationReport r = validate_surface(copy);
    EXPECT_TRUE(r.ok()) << r.summary();
  }
  z[4 + 1] = z[4 + 2] = 1.0;  // the two inner top vertices half way down: still valid
  SurfaceMesh half = test::heightfield_box(xs, ys, z, 0.0, centre);
  EXPECT_TRUE(validate_surface(half).ok());
  z[4 + 1] = z[4 + 2] = 0.0;  // down to the bottom: the edge between them lies on the bottom
  SurfaceMesh touching = test::heightfield_box(xs, ys, z, 0.0, centre);
  const ValidationReport r = validate_surface(touching);
  EXPECT_GT(r.count(Error::SelfIntersection), 0u) << r.summary();
  EXPECT_EQ(r.count(Error::IntersectingShells), 0u);
  for (const auto& pr : r.intersecting_pairs) {
    // Every pair is a top triangle against a bottom triangle (ids: 12 top, then walls/bottom).
    EXPECT_LT(pr.first, 12u);
    EXPECT_GE(pr.second, 12u);
  }
}

TEST(Validate, InwardCubeIsFlipped) {
  SurfaceMesh s;
  add_cube(s, 0, 0, 0, 2, /*inward=*/true);
  const ValidationReport r = validate_surface(s);
  EXPECT_TRUE(r.ok()) << r.summary();
  const Repair* flip = find_repair(r, "flipped_shell");
  ASSERT_NE(flip, nullptr);
  EXPECT_EQ(flip->count, 12u);
  EXPECT_TRUE(r.shells[0].flipped);
  EXPECT_NEAR(r.shells[0].signed_volume, 8.0, 1e-12);
  // The surface now matches an outward cube.
  EXPECT_EQ(s.tri, [] {
    SurfaceMesh c;
    add_cube(c, 0, 0, 0, 2);
    return c.tri;
  }());
  // With the repair off, the wrong orientation is an error.
  SurfaceMesh t;
  add_cube(t, 0, 0, 0, 2, true);
  ValidationOptions no_repair;
  no_repair.orient_shells = false;
  EXPECT_EQ(validate_surface(t, no_repair).status().code(), Error::InconsistentOrientation);
}

TEST(Validate, NestedCubesBoundACavity) {
  SurfaceMesh s;
  add_cube(s, 0, 0, 0, 3);
  add_cube(s, 1, 1, 1, 1);  // given facing outward: must face into the cavity
  const ValidationReport r = validate_surface(s);
  EXPECT_TRUE(r.ok()) << r.summary();
  ASSERT_EQ(r.shells.size(), 2u);
  EXPECT_EQ(r.shells[0].depth, 0);
  EXPECT_EQ(r.shells[1].depth, 1);
  EXPECT_EQ(r.shells[1].parent, 0);
  EXPECT_EQ(r.shells[1].region, r.shells[0].region);
  EXPECT_EQ(r.num_regions, 1u);
  EXPECT_FALSE(r.shells[0].flipped);
  EXPECT_TRUE(r.shells[1].flipped);
  EXPECT_LT(r.shells[1].signed_volume, 0.0);
  // Given correctly (inner facing the cavity), nothing changes.
  SurfaceMesh t;
  add_cube(t, 0, 0, 0, 3);
  add_cube(t, 1, 1, 1, 1, /*inward=*/true);
  const ValidationReport r2 = validate_surface(t);
  EXPECT_TRUE(r2.ok());
  EXPECT_TRUE(r2.repairs.empty());
}

TEST(Validate, ThreeLevelsOfNesting) {
  SurfaceMesh s;
  add_cube(s, 2, 2, 2, 1, true);  // the island, given inward: flipped outward
  add_cube(s, 0, 0, 0, 5);        // outer body
  add_cube(s, 1, 1, 1, 3, true);  // cavity, correct
  add_cube(s, 10, 0, 0, 1);       // a separate body
  const ValidationReport r = validate_surface(s);
  EXPECT_TRUE(r.ok()) << r.summary();
  ASSERT_EQ(r.shells.size(), 4u);
  EXPECT_EQ(r.shells[0].depth, 2);
  EXPECT_EQ(r.shells[0].parent, 2);
  EXPECT_TRUE(r.shells[0].flipped);
  EXPECT_EQ(r.shells[1].depth, 0);
  EXPECT_EQ(r.shells[2].depth, 1);
  EXPECT_EQ(r.shells[2].parent, 1);
  EXPECT_EQ(r.shells[3].depth, 0);
  EXPECT_EQ(r.num_regions, 3u);  // outer body (with its cavity), island, separate body
  EXPECT_EQ(r.shells[2].region, r.shells[1].region);
  EXPECT_NE(r.shells[0].region, r.shells[1].region);
  EXPECT_NE(r.shells[3].region, r.shells[1].region);
}

TEST(Validate, DisjointCubesAreTwoRegions) {
  SurfaceMesh s;
  add_cube(s, 0, 0, 0, 1);
  add_cube(s, 2, 0, 0, 1);
  const ValidationReport r = validate_surface(s);
  EXPECT_TRUE(r.ok()) << r.summary();
  EXPECT_EQ(r.num_regions, 2u);
  EXPECT_NE(r.shells[0].region, r.shells[1].region);
}

TEST(Validate, OverlappingCubesAreIntersectingShells) {
  SurfaceMesh s;
  add_cube(s, 0, 0, 0, 2);
  add_cube(s, 1, 1, 1, 2);
  const ValidationReport r = validate_surface(s);
  EXPECT_EQ(r.status().code(), Error::IntersectingShells) << r.summary();
  EXPECT_GT(r.count(Error::IntersectingShells), 0u);
  EXPECT_EQ(r.count(Error::SelfIntersection), 0u);
  for (const auto& pr : r.intersecting_pairs) {
    EXPECT_LT(pr.first, 12u);
    EXPECT_GE(pr.second, 12u);
  }
  // Faces in a common plane overlapping (a cube shifted along x only) are found too.
  SurfaceMesh t;
  add_cube(t, 0, 0, 0, 2);
  add_cube(t, 1, 0, 0, 2);
  EXPECT_GT(validate_surface(t).count(Error::IntersectingShells), 0u);
  // A tet whose edge lies on the cube's top face touches it: that is an intersection too.
  SurfaceMesh u;
  add_cube(u, 0, 0, 0, 1);
  const double a[3] = {0.2, 0.5, 1}, b[3] = {0.8, 0.5, 1}, c[3] = {0.5, 0.2, 2},
               d[3] = {0.5, 0.8, 2};
  test::add_tet(u, a, b, c, d);
  const ValidationReport ru = validate_surface(u);
  EXPECT_GT(ru.count(Error::IntersectingShells), 0u) << ru.summary();
}

TEST(Validate, MergesDuplicateVerticesOfASoup) {
  const SurfaceMesh c = test::cube();
  SurfaceMesh soup;  // every triangle with its own three vertices (as STL stores them)
  for (size_t t = 0; t < c.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const double* p = c.point(c.tri[3 * t + k]);
      soup.add_vertex(p[0], p[1], p[2]);
    }
    const auto v = static_cast<uint32_t>(3 * t);
    soup.add_triangle(v, v + 1, v + 2);
  }
  const ValidationReport r = validate_surface(soup);
  EXPECT_TRUE(r.ok()) << r.summary();
  EXPECT_EQ(soup.num_vertices(), 8u);
  ASSERT_NE(find_repair(r, "merged_duplicate_vertices"), nullptr);
  EXPECT_EQ(find_repair(r, "merged_duplicate_vertices")->count, 28u);
  EXPECT_EQ(r.vertex_map.size(), 36u);
  // Without the repair the soup is open everywhere.
  ValidationOptions keep;
  keep.merge_duplicate_vertices = false;
  SurfaceMesh soup2;
  for (size_t t = 0; t < c.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const double* p = c.point(c.tri[3 * t + k]);
      soup2.add_vertex(p[0], p[1], p[2]);
    }
    const auto v = static_cast<uint32_t>(3 * t);
    soup2.add_triangle(v, v + 1, v + 2);
  }
  EXPECT_EQ(validate_surface(soup2, keep).count(Error::OpenBoundary), 36u);
}

TEST(Validate, UnreferencedVertexIsAWarning) {
  SurfaceMesh s = test::cube();
  s.add_vertex(7, 7, 7);
  const ValidationReport r = validate_surface(s);
  EXPECT_TRUE(r.ok()) << r.summary();
  const Problem* p = r.find("unreferenced_vertex");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->severity, Severity::Warning);
  EXPECT_EQ(p->count, 1u);
  EXPECT_EQ(p->examples[0].vertices[0], 8u);
  EXPECT_EQ(s.num_vertices(), 9u);  // kept
}

TEST(Validate, ExamplesAreCappedAndJsonIsComplete) {
  SurfaceMesh s;
  for (int i = 0; i < 10; ++i) add_cube(s, 3.0 * i, 0, 0, 1);
  // Remove one triangle from each cube: 10 x 3 boundary edges.
  SurfaceMesh open;
  open.xyz = s.xyz;
  for (size_t t = 0; t < s.num_triangles(); ++t) {
    if (t % 12 != 11) open.add_triangle(s.tri[3 * t], s.tri[3 * t + 1], s.tri[3 * t + 2]);
  }
  ValidationOptions opt;
  opt.max_examples = 4;
  const ValidationReport r = validate_surface(open, opt);
  const Problem* p = r.find("open_boundary");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->count, 30u);
  EXPECT_EQ(p->examples.size(), 4u);
  const nlohmann::json j = nlohmann::json::parse(report_to_json(r));
  EXPECT_FALSE(j["ok"].get<bool>());
  EXPECT_EQ(j["status"]["name"], "open_boundary");
  EXPECT_EQ(j["status"]["code"], static_cast<int>(Error::OpenBoundary));
  EXPECT_EQ(j["problems"][0]["count"], 30);
  EXPECT_EQ(j["problems"][0]["examples"].size(), 4u);
  EXPECT_EQ(j["shells"].size(), 10u);
}

TEST(Validate, ResultDoesNotDependOnThreads) {
  SurfaceMesh base = test::sphere(5);
  // Crumple it: shift every 3rd vertex by about two edge lengths so that its fan folds over.
  for (size_t v = 0; v < base.num_vertices(); v += 3) {
    base.xyz[3 * v] += 0.09;
    base.xyz[3 * v + 1] -= 0.05;
  }
  ValidationOptions one, two;
  one.num_threads = 1;
  two.num_threads = 2;
  SurfaceMesh a = base, b = base;
  const ValidationReport ra = validate_surface(a, one);
  const ValidationReport rb = validate_surface(b, two);
  EXPECT_GT(ra.intersecting_pairs.size(), 100u);
  EXPECT_EQ(ra.intersecting_pairs, rb.intersecting_pairs);
  EXPECT_EQ(report_to_json(ra), report_to_json(rb));
}

}  // namespace
}  // namespace anitet
