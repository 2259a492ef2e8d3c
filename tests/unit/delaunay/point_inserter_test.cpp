#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <vector>

#include "core/tet_ops.hpp"
#include "delaunay/delaunay.hpp"
#include "test_points.hpp"

namespace anitet {
namespace {

using test::kScale;
using Triangle = std::array<uint32_t, 3>;

Triangle sorted_facet(const TetMesh& m, uint32_t t, int i) {
  Triangle f = {m.vertex(t, kFacetVertex[i][0]), m.vertex(t, kFacetVertex[i][1]), m.vertex(t, kFacetVertex[i][2])};
  std::sort(f.begin(), f.end());
  return f;
}

void protect(TetMesh& m, uint32_t t, int i) {
  m.set_facet_protected(t, i, true);
  m.set_facet_protected(m.neighbour(t, i), m.neighbour_facet(t, i), true);
}

// Protects about one in `one_in` facets between two real tets (each real tet's facets in turn).
void protect_random_facets(TetMesh& m, std::mt19937_64& rng, unsigned one_in) {
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
    if (m.is_deleted(t) || m.is_ghost(t)) continue;
    for (int i = 0; i < 4; ++i)
      if (!m.is_ghost(m.neighbour(t, i)) && rng() % one_in == 0) protect(m, t, i);
  }
}

// The protected facets of the mesh, as sorted vertex triples.
std::set<Triangle> protected_facets(const TetMesh& m) {
  std::set<Triangle> out;
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t)
    if (!m.is_deleted(t))
      for (int i = 0; i < 4; ++i)
        if (m.facet_protected(t, i)) out.insert(sorted_facet(m, t, i));
  return out;
}

// After an insertion: every new tet is live, has the new vertex, and is positive (exactly).
void expect_new_tets_valid(const TetMesh& m, const std::vector<uint32_t>& tets, uint32_t v) {
  ASSERT_FALSE(tets.empty());
  for (uint32_t t : tets) {
    ASSERT_FALSE(m.is_deleted(t));
    bool has_v = false;
    for (int k = 0; k < 4; ++k) has_v = has_v || m.vertex(t, k) == v;
    ASSERT_TRUE(has_v) << "new tet " << t << " lacks the new vertex";
    if (m.is_ghost(t)) continue;
    ASSERT_GT(predicates::orient3d(m.point(m.vertex(t, 0)), m.point(m.vertex(t, 1)),
                                   m.point(m.vertex(t, 2)), m.point(m.vertex(t, 3))),
              0)
        << "new tet " << t << " is not positive";
  }
}

Status check_delaunay(const TetMesh& m) {
  MeshCheckOptions o;
  o.check_delaunay = true;
  return check_mesh(m, o);
}

// Point by point from a few seeds, points outside the hull included: the same Delaunay mesh as
// the bulk build.
TEST(PointInserter, IncrementalInsertionIsDelaunay) {
  const size_t n = 3000 / kScale;
  const std::vector<double> xyz = test::random_cube(n, 11);
  TetMesh mesh;
  ASSERT_TRUE(delaunay_tetrahedralize(mesh, xyz.data(), 6).ok());
  PointInserter inserter(mesh);
  for (size_t i = 6; i < n; ++i) {
    const InsertResult r = inserter.insert(&xyz[3 * i]);
    ASSERT_EQ(r.status, InsertStatus::kInserted) << insert_status_name(r.status) << " at point " << i;
    ASSERT_EQ(r.vertex, i);
    expect_new_tets_valid(mesh, inserter.new_tets(), r.vertex);
  }
  const Status st = check_delaunay(mesh);
  ASSERT_TRUE(st.ok()) << st.message();
  TetMesh bulk;
  ASSERT_TRUE(delaunay_tetrahedralize(bulk, xyz.data(), n).ok());
  EXPECT_EQ(mesh.num_live_tets(), bulk.num_live_tets());
}

// Cospherical and coplanar points one at a time, including on the hull's planes.
TEST(PointInserter, IncrementalGridIsDelaunay) {
  const std::vector<double> xyz = test::grid(kScale == 1 ? 8 : 5);
  const size_t n = xyz.size() / 3;
  std::vector<double> shuffled = xyz;
  std::mt19937_64 rng(3);
  for (size_t i = n - 1; i > 0; --i) {
    const size_t j = rng() % (i + 1);
    for (int c = 0; c < 3; ++c) std::swap(shuffled[3 * i + c], shuffled[3 * j + c]);
  }
  TetMesh mesh;
  auto r0 = delaunay_tetrahedralize(mesh, shuffled.data(), 5);
  size_t start = 5;
  while (!r0.ok() && start < n) r0 = delaunay_tetrahedralize(mesh, shuffled.data(), ++start);
  ASSERT_TRUE(r0.ok());
  PointInserter inserter(mesh);
  for (size_t i = start; i < n; ++i) {
    const InsertResult r = inserter.insert(&shuffled[3 * i]);
    ASSERT_EQ(r.status, InsertStatus::kInserted) << insert_status_name(r.status) << " at point " << i;
  }
  const Status st = check_delaunay(mesh);
  ASSERT_TRUE(st.ok()) << st.message();
}

TEST(PointInserter, DuplicateLeavesMeshUnchanged) {
  const std::vector<double> xyz = test::random_cube(200, 12);
  TetMesh mesh;
  ASSERT_TRUE(delaunay_tetrahedralize(mesh, xyz.data(), 200).ok());
  const TetMesh before = mesh;
  std::vector<uint32_t> new_tets = {1, 2, 3};
  // The point's own storage, which the insertion may reallocate.
  const InsertResult r = insert_point(mesh, mesh.point(77), TetMesh::kNone, {}, &new_tets);
  EXPECT_EQ(r.status, InsertStatus::kDuplicate);
  EXPECT_EQ(r.vertex, 77u);
  EXPECT_TRUE(new_tets.empty());
  EXPECT_EQ(mesh.xyz, before.xyz);
  EXPECT_EQ(mesh.tet_v, before.tet_v);
  EXPECT_EQ(mesh.tet_flags, before.tet_flags);
}

// The tet holding p strictly (kNone when p is on a facet or outside).
uint32_t holder_of(const TetMesh& mesh, const double* p) {
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t) {
    if (mesh.is_deleted(t) || mesh.is_ghost(t)) continue;
    bool inside = true;
    for (int i = 0; i < 4 && inside; ++i) {
      const int* f = kFacetVertex[i];
      inside = predicates::orient3d(mesh.point(mesh.vertex(t, f[0])), mesh.point(mesh.vertex(t, f[1])),
                                    mesh.point(mesh.vertex(t, f[2])), p) > 0;
    }
    if (inside) return t;
  }
  return TetMesh::kNone;
}

bool joined_to_all(const TetMesh& mesh, const std::vector<uint32_t>& new_tets, const uint32_t* verts) {
  for (int k = 0; k < 4; ++k) {
    bool joined = false;
    for (uint32_t t : new_tets)
      for (int j = 0; j < 4; ++j) joined = joined || mesh.vertex(t, j) == verts[k];
    if (!joined) return false;
  }
  return true;
}

// keep_tets: a tet the point's Delaunay cavity does not reach makes the insertion refused, with
// the mesh unchanged; tets it does reach go, and the new vertex is joined to all their vertices.
TEST(PointInserter, KeepTetsAreInTheCavityOrTheInsertionIsRefused) {
  const std::vector<double> xyz = test::random_cube(400, 15);
  TetMesh mesh;
  ASSERT_TRUE(delaunay_tetrahedralize(mesh, xyz.data(), 400).ok());
  const double p[3] = {0.5, 0.5, 0.5};
  // A live tet whose circumsphere misses p (the far corner's), and the tet holding p.
  uint32_t far = TetMesh::kNone;
  for (uint32_t t = 0; t < mesh.num_tet_slots() && far == TetMesh::kNone; ++t) {
    if (mesh.is_deleted(t) || mesh.is_ghost(t)) continue;
    if (predicates::insphere(mesh.point(mesh.vertex(t, 0)), mesh.point(mesh.vertex(t, 1)),
                             mesh.point(mesh.vertex(t, 2)), mesh.point(mesh.vertex(t, 3)), p) < 0)
      far = t;
  }
  uint32_t holder = holder_of(mesh, p);
  ASSERT_NE(far, TetMesh::kNone);
  ASSERT_NE(holder, TetMesh::kNone);
  const TetMesh before = mesh;
  InsertOptions keep_far;
  keep_far.keep_tets = &far;
  keep_far.keep_count = 1;
  EXPECT_EQ(insert_point(mesh, p, TetMesh::kNone, keep_far).status, InsertStatus::kBlocked);
  EXPECT_EQ(mesh.xyz, before.xyz);
  EXPECT_EQ(mesh.tet_v, before.tet_v);
  EXPECT_EQ(mesh.tet_adj, before.tet_adj);
  uint32_t holder_v[4];
  for (int k = 0; k < 4; ++k) holder_v[k] = mesh.vertex(holder, k);
  InsertOptions keep_holder;
  keep_holder.keep_tets = &holder;
  keep_holder.keep_count = 1;
  std::vector<uint32_t> new_tets;
  const InsertResult r = insert_point(mesh, p, TetMesh::kNone, keep_holder, &new_tets);
  ASSERT_EQ(r.status, InsertStatus::kInserted);
  EXPECT_TRUE(joined_to_all(mesh, new_tets, holder_v)) << "a vertex of the kept tet is not joined to the new one";
}

// force_keep: a kept tet outside the point's empty-sphere cavity joins it anyway, so the insertion
// that keep_tets alone refuses goes through whenever the cavity is still star-shaped; the new
// vertex is then joined to every vertex of the kept tet and the mesh stays valid.
TEST(PointInserter, ForcedKeepTetsJoinTheCavityWhateverTheEmptySphereTest) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(0.2, 0.8);
  size_t refused_unforced = 0, forced_in = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const std::vector<double> xyz = test::random_cube(300, 100 + trial);
    TetMesh mesh;
    ASSERT_TRUE(delaunay_tetrahedralize(mesh, xyz.data(), 300).ok());
    const double p[3] = {u(rng), u(rng), u(rng)};
    const uint32_t holder = holder_of(mesh, p);
    if (holder == TetMesh::kNone) continue;
    // A neighbour of the holder's neighbours whose circumsphere misses p.
    uint32_t far = TetMesh::kNone;
    for (int i = 0; i < 4 && far == TetMesh::kNone; ++i) {
      const uint32_t n = mesh.neighbour(holder, i);
      for (int j = 0; j < 4 && far == TetMesh::kNone; ++j) {
        const uint32_t m = mesh.neighbour(n, j);
        if (mesh.is_ghost(m) || m == holder) continue;
        if (predicates::insphere(mesh.point(mesh.vertex(m, 0)), mesh.point(mesh.vertex(m, 1)),
                                 mesh.point(mesh.vertex(m, 2)), mesh.point(mesh.vertex(m, 3)), p) < 0)
          far = m;
      }
    }
    if (far == TetMesh::kNone) continue;
    const uint32_t n = [&] {
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
          if (mesh.neighbour(mesh.neighbour(holder, i), j) == far) return mesh.neighbour(holder, i);
      return TetMesh::kNone;
    }();
    const uint32_t chain[3] = {holder, n, far};
    uint32_t far_v[4];
    for (int k = 0; k < 4; ++k) far_v[k] = mesh.vertex(far, k);
    InsertOptions plain;
    plain.keep_tets = chain;
    plain.keep_count = 3;
    TetMesh copy = mesh;
    EXPECT_EQ(insert_point(copy, p, TetMesh::kNone, plain).status, InsertStatus::kBlocked);
    ++refused_unforced;
    InsertOptions forced = plain;
    forced.force_keep = true;
    std::vector<uint32_t> new_tets;
    const InsertResult r = insert_point(mesh, p, TetMesh::kNone, forced, &new_tets);
    if (r.status == InsertStatus::kBlocked) continue;
    ASSERT_EQ(r.status, InsertStatus::kInserted);
    ++forced_in;
    EXPECT_TRUE(joined_to_all(mesh, new_tets, far_v));
    const Status st = check_mesh(mesh);
    ASSERT_TRUE(st.ok()) << st.message();
  }
  EXPECT_GT(refused_unforced, 10u);
  EXPECT_GT(forced_in, 0u) << "force_keep never let a non-conflicting tet into a cavity";
}

// A constrained edge whose whole ring is kept (forced) cannot keep a tet out of the cavity: the
// insertion is refused rather than the edge lost.
TEST(PointInserter, ForcedKeepNeverDestroysAConstrainedEdge) {
  size_t refused = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const std::vector<double> xyz = test::random_cube(300, 200 + trial);
    TetMesh mesh;
    ASSERT_TRUE(delaunay_tetrahedralize(mesh, xyz.data(), 300).ok());
    // An interior edge (no ghost around it) of a tet near the middle.
    const double mid[3] = {0.5, 0.5, 0.5};
    const uint32_t t0 = holder_of(mesh, mid);
    ASSERT_NE(t0, TetMesh::kNone);
    const uint32_t a = mesh.vertex(t0, 0), b = mesh.vertex(t0, 1);
    std::vector<uint32_t> ring, ring_v;
    ASSERT_TRUE(meshops::edge_ring(mesh, a, b, t0, ring, ring_v));
    if (std::count(ring_v.begin(), ring_v.end(), TetMesh::kGhost) > 0) continue;
    for (uint32_t t : ring)
      for (int k = 0; k < 6; ++k) {
        const uint32_t x = mesh.vertex(t, kEdgeVertex[k][0]), y = mesh.vertex(t, kEdgeVertex[k][1]);
        if ((x == a && y == b) || (x == b && y == a))
          mesh.set_edge_constrained(t, k, true);
      }
    // Near the edge's middle, inside t0.
    double p[3];
    for (int d = 0; d < 3; ++d) {
      double c = 0;
      for (int k = 0; k < 4; ++k) c += 0.25 * mesh.point(mesh.vertex(t0, k))[d];
      p[d] = 0.9 * 0.5 * (mesh.point(a)[d] + mesh.point(b)[d]) + 0.1 * c;
    }
    if (holder_of(mesh, p) != t0) continue;
    InsertOptions forced;
    forced.keep_tets = ring.data();
    forced.keep_count = ring.size();
    forced.force_keep = true;
    const InsertResult r = insert_point(mesh, p, TetMesh::kNone, forced);
    if (r.status == InsertStatus::kBlocked) {
      ++refused;
      continue;
    }
    ASSERT_EQ(r.status, InsertStatus::kInserted);
    bool edge_left = false;
    for (uint32_t t = 0; t < mesh.num_tet_slots() && !edge_left; ++t) {
      if (mesh.is_deleted(t)) continue;
      bool has_a = false, has_b = false;
      for (int k = 0; k < 4; ++k) {
        has_a = has_a || mesh.vertex(t, k) == a;
        has_b = has_b || mesh.vertex(t, k) == b;
      }
      edge_left = has_a && has_b;
    }
    EXPECT_TRUE(edge_left) << "the constrained edge was destroyed";
  }
  EXPECT_GT(refused, 0u);
}

// InsertOptions::early_refusal only saves work: forced chains of kept tets (as the split
// recovery's walks make them) in a mesh with protected facets and constrained edges, each point
// inserted with and without it into two copies, give the same outcome and the same mesh, and
// some refusals do come early.
TEST(PointInserter, EarlyRefusalNeverChangesTheOutcome) {
  size_t early = 0, inserted = 0, refused = 0;
  for (int seed = 1; seed <= 3; ++seed) {
    std::mt19937_64 rng(seed);
    const std::vector<double> xyz = test::random_cube(300, 400 + seed);
    TetMesh a;
    ASSERT_TRUE(delaunay_tetrahedralize(a, xyz.data(), 300).ok());
    protect_random_facets(a, rng, 8);
    // Constrained edges: every tet around each chosen edge carries its bit.
    for (int e = 0; e < 40; ++e) {
      const auto t0 = uint32_t(rng() % a.num_tet_slots());
      if (a.is_deleted(t0) || a.is_ghost(t0)) continue;
      const uint32_t u = a.vertex(t0, 0), w = a.vertex(t0, 1);
      std::vector<uint32_t> ring, ring_v;
      if (!meshops::edge_ring(a, u, w, t0, ring, ring_v)) continue;
      for (uint32_t t : ring)
        for (int k = 0; k < 6; ++k) {
          const uint32_t x = a.vertex(t, kEdgeVertex[k][0]), y = a.vertex(t, kEdgeVertex[k][1]);
          if ((x == u && y == w) || (x == w && y == u))
            a.set_edge_constrained(t, k, true);
        }
    }
    TetMesh b = a;
    PointInserter with(a, seed), without(b, seed);
    std::uniform_real_distribution<double> u(0.2, 0.8);
    for (int trial = 0; trial < 400 / int(kScale); ++trial) {
      const double p[3] = {u(rng), u(rng), u(rng)};
      const uint32_t holder = holder_of(a, p);
      if (holder == TetMesh::kNone) continue;
      // A chain from the holder through 1 to 6 random neighbours.
      std::vector<uint32_t> chain = {holder};
      const int length = 1 + int(rng() % 6);
      for (int step = 0; step < length; ++step) {
        const uint32_t n = a.neighbour(chain.back(), int(rng() % 4));
        if (n == TetMesh::kNone || a.is_ghost(n) || std::count(chain.begin(), chain.end(), n)) break;
        chain.push_back(n);
      }
      InsertOptions o;
      o.keep_tets = chain.data();
      o.keep_count = chain.size();
      o.force_keep = true;
      InsertOptions plain = o;
      plain.early_refusal = false;
      const InsertResult ra = with.insert(p, holder, o);
      const InsertResult rb = without.insert(p, holder, plain);
      ASSERT_EQ(ra.status, rb.status) << "seed " << seed << ", trial " << trial;
      ASSERT_EQ(ra.vertex, rb.vertex);
      ASSERT_EQ(a.tet_v, b.tet_v) << "seed " << seed << ", trial " << trial;
      ASSERT_EQ(a.tet_adj, b.tet_adj);
      ASSERT_EQ(a.tet_flags, b.tet_flags);
      (ra.ok() ? inserted : refused) += 1;
    }
    early += with.stats().early_refusals;
    EXPECT_EQ(without.stats().early_refusals, 0u);
    const Status st = check_mesh(a);
    ASSERT_TRUE(st.ok()) << st.message();
  }
  std::printf("early refusal: %zu inserted, %zu refused, %zu of them early\n", inserted, refused, early);
  EXPECT_GT(inserted, 0u);
  EXPECT_GT(early, 0u);
  EXPECT_LT(early, refused);
}

TEST(PointInserter, InvalidInputs) {
  TetMesh empty;
  const double p[3] = {0.5, 0.5, 0.5};
  EXPECT_EQ(insert_point(empty, p).status, InsertStatus::kInvalidMesh);
  const std::vector<double> xyz = test::random_cube(50, 14);
  TetMesh mesh;
  ASSERT_TRUE(delaunay_tetrahedralize(mesh, xyz.data(), 50).ok());
  const double nan[3] = {0.5, std::nan(""), 0.5};
  EXPECT_EQ(insert_point(mesh, nan).status, InsertStatus::kInvalidPoint);
  EXPECT_EQ(mesh.num_vertices(), 50u);
  EXPECT_STREQ(insert_status_name(InsertStatus::kBlocked), "blocked");
}

// An oracle that calls flat every tet holding vertices a and b (a hull edge) and a point inserted
// later (as if they were on one segment): with it, no insertion makes such a tet; without it,
// some do.
class EdgeOracle : public DegeneracyOracle {
 public:
  EdgeOracle(uint32_t a, uint32_t b, uint32_t n0) : a_(a), b_(b), n0_(n0) {}
  bool flat(uint32_t a, uint32_t b, uint32_t c, uint32_t d) const override {
    const uint32_t v[4] = {a, b, c, d};
    bool has0 = false, has1 = false, later = false;
    for (uint32_t x : v) {
      has0 = has0 || x == a_;
      has1 = has1 || x == b_;
      later = later || (x >= n0_ && x != TetMesh::kGhost);
    }
    return has0 && has1 && later;
  }

 private:
  uint32_t a_, b_, n0_;
};

TEST(PointInserter, DegeneracyOracleShrinksTheCavity) {
  const std::vector<double> xyz = test::random_cube(200, 21);
  const std::vector<double> more = test::random_cube(400, 22);
  uint32_t a = TetMesh::kNone, b = TetMesh::kNone;
  {
    TetMesh mesh;
    ASSERT_TRUE(delaunay_tetrahedralize(mesh, xyz.data(), 200).ok());
    for (uint32_t t = 0; t < mesh.num_tet_slots() && a == TetMesh::kNone; ++t)
      if (!mesh.is_deleted(t) && mesh.is_ghost(t)) a = mesh.vertex(t, 0), b = mesh.vertex(t, 1);
  }
  const EdgeOracle oracle(a, b, 200);
  size_t flagged[2] = {0, 0};
  for (int with = 0; with < 2; ++with) {
    TetMesh mesh;
    ASSERT_TRUE(delaunay_tetrahedralize(mesh, xyz.data(), 200).ok());
    PointInserter ins(mesh);
    InsertOptions o;
    o.degeneracy = with ? &oracle : nullptr;
    size_t inserted = 0;
    for (size_t i = 0; i < 400; ++i) {
      if (!ins.insert(&more[3 * i], TetMesh::kNone, o).ok()) continue;
      ++inserted;
      for (uint32_t t : ins.new_tets())  // tets this insertion made
        flagged[with] += oracle.flat(mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2), mesh.vertex(t, 3));
    }
    EXPECT_GT(inserted, 360u);
    const Status st = check_mesh(mesh);
    EXPECT_TRUE(st.ok()) << st.message();
  }
  EXPECT_GT(flagged[0], 0u) << "the case is not exercised";
  EXPECT_EQ(flagged[1], 0u);
}

// A 6^3 grid with every facet of the plane z = 2 protected: a wall splitting the box.
class ProtectedWall : public ::testing::Test {
 protected:
  void SetUp() override {
    xyz_ = test::grid(6);
    ASSERT_TRUE(delaunay_tetrahedralize(mesh_, xyz_.data(), xyz_.size() / 3).ok());
    for (uint32_t t = 0; t < mesh_.num_tet_slots(); ++t) {
      if (mesh_.is_deleted(t) || mesh_.is_ghost(t)) continue;
      for (int i = 0; i < 4; ++i) {
        bool on_wall = true;
        for (int k = 0; k < 3; ++k) on_wall = on_wall && mesh_.point(mesh_.vertex(t, kFacetVertex[i][k]))[2] == 2.0;
        if (on_wall && !mesh_.is_ghost(mesh_.neighbour(t, i))) protect(mesh_, t, i);
      }
    }
    wall_ = protected_facets(mesh_);
    ASSERT_EQ(wall_.size(), 5u * 5 * 2);
  }
  std::vector<double> xyz_;
  TetMesh mesh_;
  std::set<Triangle> wall_;
};

TEST_F(ProtectedWall, PointOnTheWallIsBlocked) {
  const TetMesh before = mesh_;
  const double on_wall[3] = {1.25, 2.5, 2.0};
  std::vector<uint32_t> new_tets;
  const InsertResult r = insert_point(mesh_, on_wall, TetMesh::kNone, {}, &new_tets);
  EXPECT_EQ(r.status, InsertStatus::kBlocked);
  EXPECT_EQ(mesh_.xyz, before.xyz);
  EXPECT_EQ(mesh_.tet_v, before.tet_v);
  EXPECT_EQ(mesh_.tet_adj, before.tet_adj);
  EXPECT_EQ(mesh_.tet_flags, before.tet_flags);

  // Without the protection the same point goes in and splits wall facets.
  InsertOptions ignore;
  ignore.respect_protected = false;
  EXPECT_EQ(insert_point(mesh_, on_wall, TetMesh::kNone, ignore).status, InsertStatus::kInserted);
}

// Random points on both sides and on the wall: the wall survives, and each side stays Delaunay.
// Regions and constrained-edge bits go with the new tets.
TEST_F(ProtectedWall, WallSurvivesRandomInsertions) {
  auto centroid_z = [this](uint32_t t) {
    double z = 0;
    for (int k = 0; k < 4; ++k) z += mesh_.point(mesh_.vertex(t, k))[2];
    return z / 4;
  };
  auto on_wall = [this](uint32_t t, int k) { return mesh_.point(mesh_.vertex(t, k))[2] == 2.0; };
  for (uint32_t t = 0; t < mesh_.num_tet_slots(); ++t) {
    if (mesh_.is_deleted(t) || mesh_.is_ghost(t)) continue;
    mesh_.tet_region[t] = centroid_z(t) < 2.0 ? 1 : 2;
    for (int e = 0; e < 6; ++e)  // every edge lying in the wall is constrained, in every tet
      if (on_wall(t, kEdgeVertex[e][0]) && on_wall(t, kEdgeVertex[e][1]))
        mesh_.set_edge_constrained(t, e, true);
  }
  PointInserter inserter(mesh_, 5);
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(0.0, 5.0);
  size_t inserted = 0, blocked = 0;
  for (int i = 0; i < 4000 / int(kScale); ++i) {
    double p[3] = {u(rng), u(rng), u(rng)};
    if (i % 8 == 0) p[2] = 2.0;
    const InsertResult r = inserter.insert(p);
    if (p[2] == 2.0) {
      EXPECT_NE(r.status, InsertStatus::kInserted) << "point on the wall went in";
      blocked += r.status == InsertStatus::kBlocked;
    } else {
      ASSERT_EQ(r.status, InsertStatus::kInserted) << insert_status_name(r.status);
      expect_new_tets_valid(mesh_, inserter.new_tets(), r.vertex);
      ++inserted;
    }
  }
  EXPECT_GT(blocked, 0u);
  EXPECT_EQ(protected_facets(mesh_), wall_);
  const Status st = check_delaunay(mesh_);  // skips protected facets
  ASSERT_TRUE(st.ok()) << st.message();
  for (uint32_t t = 0; t < mesh_.num_tet_slots(); ++t) {
    if (mesh_.is_deleted(t) || mesh_.is_ghost(t)) continue;
    ASSERT_EQ(mesh_.tet_region[t], centroid_z(t) < 2.0 ? 1 : 2) << "tet " << t << " crossed the wall";
    for (int e = 0; e < 6; ++e) {
      const bool in_wall = on_wall(t, kEdgeVertex[e][0]) && on_wall(t, kEdgeVertex[e][1]);
      ASSERT_EQ(in_wall, mesh_.edge_constrained(t, e))
          << "edge " << e << " of tet " << t;
    }
  }
}

// The property test: random protected facets, random points (many outside the initial hull):
// no protected facet ever disappears and no tet is ever non-positive.
TEST(PointInserter, ProtectedFacetsSurviveRandomInsertions) {
  const int seeds = 5;
  const int per_seed = 20000 / int(kScale);
  for (int seed = 1; seed <= seeds; ++seed) {
    std::mt19937_64 rng(seed);
    const std::vector<double> xyz = test::random_cube(300, 100 + seed);
    std::vector<double> shrunk = xyz;
    for (double& c : shrunk) c = 0.25 + 0.5 * c;  // the hull is well inside the unit cube
    TetMesh mesh;
    ASSERT_TRUE(delaunay_tetrahedralize(mesh, shrunk.data(), 300).ok());
    protect_random_facets(mesh, rng, 10);
    const std::set<Triangle> wall = protected_facets(mesh);
    ASSERT_GT(wall.size(), 50u);

    PointInserter inserter(mesh, seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    size_t inserted = 0;
    for (int i = 0; i < per_seed; ++i) {
      const double p[3] = {u(rng), u(rng), u(rng)};
      const InsertResult r = inserter.insert(p);
      if (r.ok()) {
        ++inserted;
        expect_new_tets_valid(mesh, inserter.new_tets(), r.vertex);
      }
      if ((i + 1) % 5000 == 0 || i + 1 == per_seed) {
        const Status st = check_mesh(mesh, MeshCheckOptions{false, false, true});
        ASSERT_TRUE(st.ok()) << "seed " << seed << ", insertion " << i << ": " << st.message();
        std::set<Triangle> now = protected_facets(mesh);
        ASSERT_TRUE(std::includes(now.begin(), now.end(), wall.begin(), wall.end()))
            << "seed " << seed << ": a protected facet was destroyed";
      }
    }
    EXPECT_GT(inserted, size_t(per_seed) * 9 / 10);
  }
}

// refuse_frozen_conflict (the parts of distributed/): the tets with x > 0.5 are frozen (region
// -1, every facet protected, as a part's halo). A point whose cavity would take one of them is
// refused; one that goes in leaves no frozen neighbour of its tets holding it in its sphere, and
// the frozen tets stay as they were. Without the option the same points go in.
TEST(PointInserter, FrozenConflictRefusesThePoint) {
  const std::vector<double> xyz = test::random_cube(400, 21);
  TetMesh base;
  ASSERT_TRUE(delaunay_tetrahedralize(base, xyz.data(), 400).ok());
  std::set<std::array<uint32_t, 4>> frozen;
  for (uint32_t t = 0; t < base.num_tet_slots(); ++t) {
    if (base.is_deleted(t) || base.is_ghost(t)) continue;
    double cx = 0.0;
    for (int i = 0; i < 4; ++i) cx += 0.25 * base.point(base.vertex(t, i))[0];
    if (cx <= 0.5) continue;
    base.tet_region[t] = -1;
    for (int i = 0; i < 4; ++i) protect(base, t, i);
    frozen.insert({base.vertex(t, 0), base.vertex(t, 1), base.vertex(t, 2), base.vertex(t, 3)});
  }
  ASSERT_GT(frozen.size(), 100u);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.1, 0.9), ux(0.1, 0.5);
  size_t refused = 0, inserted = 0;
  for (int i = 0; i < 300; ++i) {
    const double p[3] = {ux(rng), u(rng), u(rng)};
    TetMesh with = base, without = base;
    PointInserter a(with), b(without);
    InsertOptions defer;
    defer.refuse_frozen_conflict = true;
    const InsertResult ra = a.insert(p, TetMesh::kNone, defer);
    const InsertResult rb = b.insert(p);
    if (rb.status != InsertStatus::kInserted) continue;
    if (ra.status == InsertStatus::kBlocked) {
      ++refused;
      ASSERT_EQ(with.tet_v, base.tet_v) << "a refused point changed the mesh";
      continue;
    }
    ASSERT_EQ(ra.status, InsertStatus::kInserted) << insert_status_name(ra.status);
    ++inserted;
    expect_new_tets_valid(with, a.new_tets(), ra.vertex);
    for (uint32_t t : a.new_tets())
      for (int k = 0; k < 4; ++k) {
        const uint32_t n = with.neighbour(t, k);
        if (with.is_ghost(t) || with.is_ghost(n) || with.tet_region[n] >= 0) continue;
        const double* q[4];
        for (int j = 0; j < 4; ++j) q[j] = with.point(with.vertex(n, j));
        EXPECT_LE(predicates::insphere(q[0], q[1], q[2], q[3], p), 0) << "a frozen neighbour holds the point";
      }
    std::set<std::array<uint32_t, 4>> still;
    for (uint32_t t = 0; t < with.num_tet_slots(); ++t)
      if (!with.is_deleted(t) && with.tet_region[t] < 0)
        still.insert({with.vertex(t, 0), with.vertex(t, 1), with.vertex(t, 2), with.vertex(t, 3)});
    ASSERT_EQ(still, frozen);
  }
  EXPECT_GT(refused, 10u);
  EXPECT_GT(inserted, 10u);
}

// Meshes without ghost tets (read from a file, or cut to a domain): facets without neighbour
// bound the cavity, and points beyond them are reported.
TEST(PointInserter, MeshWithoutGhosts) {
  const std::vector<double> xyz = test::random_cube(500, 13);
  TetMesh full;
  ASSERT_TRUE(delaunay_tetrahedralize(full, xyz.data(), 500).ok());
  TetMesh mesh = TetMesh::from_volume_mesh(full.to_volume_mesh(false));
  ASSERT_TRUE(mesh.build_adjacency().ok());
  PointInserter inserter(mesh);
  const double outside[3] = {2.0, 0.5, 0.5};
  EXPECT_EQ(inserter.insert(outside).status, InsertStatus::kOutsideMesh);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(0.2, 0.8);
  for (int i = 0; i < 500; ++i) {
    const double p[3] = {u(rng), u(rng), u(rng)};
    const InsertResult r = inserter.insert(p);
    ASSERT_EQ(r.status, InsertStatus::kInserted) << insert_status_name(r.status);
    expect_new_tets_valid(mesh, inserter.new_tets(), r.vertex);
  }
  const Status st = check_mesh(mesh);
  ASSERT_TRUE(st.ok()) << st.message();
}

}  // namespace
}  // namespace anitet
