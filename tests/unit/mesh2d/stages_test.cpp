// Stages 1-2 and the coupling on Lake Superior (the paper's 2D example) and small inputs: the
// triangulation is valid and every input segment is one of its edges.
#include <gtest/gtest.h>

#include "mesh2d/domain.hpp"
#include "mesh2d/pslg_io.hpp"
#include "mesh2d/stages.hpp"

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
