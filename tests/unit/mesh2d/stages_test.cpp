// Stages 1-2 and the coupling on Lake Superior (the paper's 2D example) and small inputs: the
// triangulation is valid and every input segment is one of its edges.
#include <gtest/gtest.h>

#include <algorithm>

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
    const bool found = m.find_edge(p.seg[2 * s], p.seg[2 * s + 1], t, k) || m.find_edge(p.seg[2 * s + 1], p.seg[2 * s], t, k);
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
