// Stages 1-2 and the coupling on Lake Superior (the paper's 2D example) and small inputs: the
// triangulation is valid and every input segment is one of its edges.
#include <gtest/gtest.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "mesh2d/domain.hpp"
#include "mesh2d/mesher2.hpp"
#include "mesh2d/pslg_io.hpp"
#include "mesh2d/stages.hpp"
#include "metric/metric_field.hpp"

namespace anitet::mesh2d {
namespace {

void expect_segments_kept(const Pslg& p, const Triangulation& m) {
  for (size_t s = 0; s < p.num_segments(); ++s) {
    uint32_t t;
    int k;
    const bool found = find_edge_of_points(m, p.seg[2 * s], p.seg[2 * s + 1], t, k);
    ASSERT_TRUE(found) << "segment " << s;
    EXPECT_EQ(m.edge_tag(t, k), int32_t(s));
  }
}

TEST(Mesh2dStages, SuperiorIsBoundaryConstrained) {
  Result<Pslg> p = read_pslg(std::string(ANITET_SURFACES_DIR) + "/superior.poly");
  ASSERT_TRUE(p.ok()) << p.status().message();
  EXPECT_EQ(p->num_points(), 518u);
  EXPECT_EQ(p->num_segments(), 518u);
  EXPECT_EQ(p->num_holes(), 6u);
  Result<Domain> d = analyse_domain(p.value());
  ASSERT_TRUE(d.ok()) << d.status().message();
  StageStats stats;
  Result<Triangulation> m = boundary_constrained_triangulation(p.value(), d.value(), FrontOptions{}, &stats);
  ASSERT_TRUE(m.ok()) << m.status().message();
  ASSERT_TRUE(check_triangulation(m.value()).ok()) << check_triangulation(m.value()).message();
  expect_segments_kept(p.value(), m.value());
  // One triangle per input front edge, but a closed corner consumes its neighbour too.
  EXPECT_LE(stats.t1_triangles, 518u);
  EXPECT_GE(stats.t1_triangles, 518u - stats.closed);
  std::printf("T1 %zu (closed %zu, halvings %zu), S1 %zu, T2 %zu, Steiner %zu, coupled %zu\n", stats.t1_triangles,
              stats.closed, stats.halvings, stats.s1_edges, stats.t2_triangles, stats.steiner_on_s1, stats.coupled);
}

}  // namespace
}  // namespace anitet::mesh2d

namespace anitet::mesh2d {
namespace {

// A constant anisotropic metric (sizes 0.1 in x, 0.2 in y) on the square minus a disk: the
// bottom side's first front triangle is tall, and its new edge from the corner passed within
// 1e-10 of the left side's apex (the two lie on one line in exact arithmetic); stage 2's rounded
// midpoints then put that apex on the wrong side and split toward it forever. Stage 1 now keeps
// front points and new edges apart by more than rounding.
TEST(Mesh2dStages, ConstantAnisotropicMetricOnTheRing) {
  Result<Pslg> p = read_pslg(std::string(ANITET_TEST_DATA_DIR) + "/mesh2d/square_minus_disk.poly");
  ASSERT_TRUE(p.ok()) << p.status().message();
  const double lo[3] = {-0.5, -0.5, -0.5}, hi[3] = {1.5, 1.5, 1.5};
  Result<metric::MetricField> field = metric::MetricField::from_function(
      [](const double*, double m[6]) {
        const double tensor[6] = {100.0, 0.0, 25.0, 0.0, 0.0, 6.25};
        std::copy(tensor, tensor + 6, m);
      },
      lo, hi, 0.5);
  ASSERT_TRUE(field.ok()) << field.status().message();
  Mesh2dOptions o;
  o.sizing.metric = &field.value();
  Result<TriMesh2> m = mesh_pslg(p.value(), o);
  ASSERT_TRUE(m.ok()) << m.status().message();
  EXPECT_EQ(m->edge_label.size(), p->num_segments());
}

}  // namespace
}  // namespace anitet::mesh2d

namespace anitet::mesh2d {
namespace {

// The output of mesh_pslg is a valid mesh of the domain: every triangle positive, no two vertices
// at one place, each input segment an edge, the area the domain's.
void expect_valid_output(const Pslg& p, const TriMesh2& m, double area) {
  double sum = 0;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const double* a = &m.xy[2 * size_t(m.tri[3 * t])];
    const double* b = &m.xy[2 * size_t(m.tri[3 * t + 1])];
    const double* c = &m.xy[2 * size_t(m.tri[3 * t + 2])];
    const double twice = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    EXPECT_GT(twice, 0.0) << "triangle " << t;
    sum += 0.5 * twice;
  }
  EXPECT_NEAR(sum, area, 1e-12 * area);
  std::vector<std::pair<double, double>> at;
  for (size_t v = 0; v < m.num_vertices(); ++v) at.emplace_back(m.xy[2 * v], m.xy[2 * v + 1]);
  std::sort(at.begin(), at.end());
  EXPECT_EQ(std::adjacent_find(at.begin(), at.end()), at.end()) << "two vertices at one place";
  std::vector<uint8_t> kept(p.num_segments(), 0);
  for (uint32_t s : m.edge_segment) kept[s] = 1;
  EXPECT_EQ(std::count(kept.begin(), kept.end(), 1), long(p.num_segments()));
}

// Stages 1-2 on p (valid, every segment an edge) into t, then the whole mesher into m (a valid
// output of the domain's area).
void stages_and_mesh(const Pslg& p, double area, Triangulation& t, TriMesh2& m) {
  Result<Domain> d = analyse_domain(p);
  ASSERT_TRUE(d.ok()) << d.status().message();
  Result<Triangulation> staged = boundary_constrained_triangulation(p, d.value(), FrontOptions{}, nullptr);
  ASSERT_TRUE(staged.ok()) << staged.status().message();
  ASSERT_TRUE(check_triangulation(staged.value()).ok()) << check_triangulation(staged.value()).message();
  expect_segments_kept(p, staged.value());
  Result<TriMesh2> meshed = mesh_pslg(p, Mesh2dOptions{});
  ASSERT_TRUE(meshed.ok()) << meshed.status().message();
  expect_valid_output(p, meshed.value(), area);
  t = std::move(staged).value();
  m = std::move(meshed).value();
}

// Two squares touching at a corner (and the fuzzer's GeoJSON bow tie): the triangles around the
// shared point form two fans; the working triangulation gives the second fan a copy of the
// point, the output the point once.
TEST(Mesh2dStages, DomainPinchedAtAPoint) {
  Result<Pslg> p = parse_poly(
      "7 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n5 2 1\n6 2 2\n7 1 2\n"
      "8 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n5 3 5\n6 5 6\n7 6 7\n8 7 3\n0\n",
      "bow tie");
  ASSERT_TRUE(p.ok()) << p.status().message();
  Triangulation t;
  TriMesh2 m;
  ASSERT_NO_FATAL_FAILURE(stages_and_mesh(p.value(), 2.0, t, m));
  ASSERT_EQ(t.copies.size(), 1u);
  EXPECT_EQ(t.copies[0].second, 2u);
  size_t at_pinch = 0;
  for (uint32_t v : m.tri) at_pinch += v == 2;
  EXPECT_GE(at_pinch, 4u);  // triangles of both squares
}

// Stage 1 closes the sharp corner at (22, 2), leaving the input point (1, 2) on S1 on both
// sides of the inner segment: S1 touches itself there, and the carved T2's triangles around it
// form two fans. The coupling used to look for S1's pieces in the carved T2 (a fuzzer's input).
TEST(Mesh2dStages, FrontTouchesItselfAtAnInputPoint) {
  Result<Pslg> p = parse_poly(
      "6 2 0 0\n1 0 0\n2 1 0\n3 2 0\n4 22 2\n5 1 2\n6 0 2\n"
      "7 1\n1 1 2 1\n2 2 3 1\n3 3 4 1\n4 4 5 1\n5 5 6 1\n6 6 1 1\n7 2 5 9\n0\n",
      "spike");
  ASSERT_TRUE(p.ok()) << p.status().message();
  Triangulation t;
  TriMesh2 m;
  ASSERT_NO_FATAL_FAILURE(stages_and_mesh(p.value(), 24.0, t, m));
}

}  // namespace
}  // namespace anitet::mesh2d
