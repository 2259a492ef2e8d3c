// Simulation of Simplicity in insphere_sos: agreement with a concrete tiny perturbation,
// alternation under permutations, and brute-force Delaunay triangulations of fully degenerate
// point sets that must come out as valid triangulations.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <map>
#include <numeric>
#include <vector>

#include "generators.hpp"
#include "predicates/predicates.hpp"
#include "reference.hpp"

namespace anitet::predicates::testing {
namespace {

// Five points drawn from small, highly degenerate lattices: a sphere, a grid, a plane.
std::array<P3, 5> degenerate_five(Rng& rng) {
  static const std::vector<P3> sphere = integer_sphere(25);
  std::array<P3, 5> p;
  const int kind = rng.integer(0, 3);
  for (auto& q : p) {
    if (kind <= 1) {
      q = sphere[size_t(rng.integer(0, int(sphere.size()) - 1))];
    } else if (kind == 2) {
      q = lattice_point(rng, 0, 2);
    } else {
      q = lattice_point(rng, -2, 2);
      q[2] = q[0] + q[1];  // all on one plane
    }
  }
  return p;
}

std::array<unsigned, 5> distinct_ids(Rng& rng) {
  std::array<unsigned, 5> ids;
  for (;;) {
    for (auto& id : ids) id = unsigned(rng.integer(0, 1000));
    auto sorted = ids;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end()) return ids;
  }
}

int sos(const std::array<P3, 5>& p, const std::array<unsigned, 5>& id) {
  return insphere_sos(p[0].data(), p[1].data(), p[2].data(), p[3].data(), p[4].data(), id[0],
                      id[1], id[2], id[3], id[4]);
}

TEST(PredicatesSoS, MatchesConcretePerturbation) {
  Rng rng(31);
  reset_thread_counters();
  int zeros = 0;
  const int n = 40000 / kCaseDivisor;
  for (int t = 0; t < n; ++t) {
    const auto p = degenerate_five(rng);
    const auto ids = distinct_ids(rng);
    const double* q[5] = {p[0].data(), p[1].data(), p[2].data(), p[3].data(), p[4].data()};
    const int got = sos(p, ids);
    ASSERT_EQ(got, ref_insphere_perturbed(q, ids.data())) << "case " << t;
    if (got == 0) {  // only when all five points are coplanar
      ++zeros;
      for (int skip = 0; skip < 5; ++skip) {
        const double* r[4];
        int k = 0;
        for (int j = 0; j < 5; ++j)
          if (j != skip) r[k++] = q[j];
        ASSERT_EQ(ref_orient3d(r[0], r[1], r[2], r[3]), 0);
      }
    }
  }
  EXPECT_GT(zeros, 0);
  EXPECT_GT(thread_counters().sos_ties, uint64_t(n / 10));
}

int parity(const std::array<int, 5>& p) {
  int inv = 0;
  for (int i = 0; i < 5; ++i)
    for (int j = i + 1; j < 5; ++j) inv += p[size_t(i)] > p[size_t(j)];
  return inv % 2 == 0 ? 1 : -1;
}

TEST(PredicatesSoS, AlternatingAndNeighbourConsistent) {
  Rng rng(32);
  const int n = 2000 / kCaseDivisor;
  for (int t = 0; t < n; ++t) {
    const auto p = degenerate_five(rng);
    const auto ids = distinct_ids(rng);
    const int s0 = sos(p, ids);
    std::array<int, 5> perm = {0, 1, 2, 3, 4};
    do {
      std::array<P3, 5> pp;
      std::array<unsigned, 5> pid;
      for (int j = 0; j < 5; ++j) {
        pp[size_t(j)] = p[size_t(perm[size_t(j)])];
        pid[size_t(j)] = ids[size_t(perm[size_t(j)])];
      }
      ASSERT_EQ(parity(perm) * sos(pp, pid), s0);
    } while (std::next_permutation(perm.begin(), perm.end()));
    // Tets abcd and acbe share facet abc: both views agree on whether it is locally Delaunay.
    const std::array<P3, 5> nb = {p[0], p[2], p[1], p[4], p[3]};
    const std::array<unsigned, 5> nb_ids = {ids[0], ids[2], ids[1], ids[4], ids[3]};
    ASSERT_EQ(sos(nb, nb_ids), s0);
  }
}

TEST(PredicatesSoS, NeverZeroForATetAndADistinctPoint) {
  Rng rng(33);
  const int n = 20000 / kCaseDivisor;
  for (int t = 0; t < n; ++t) {
    auto p = degenerate_five(rng);
    if (rng.integer(0, 4) == 0) p[4] = p[size_t(rng.integer(0, 3))];  // a duplicate of a vertex
    if (orient3d(p[0].data(), p[1].data(), p[2].data(), p[3].data()) == 0) continue;
    ASSERT_NE(sos(p, distinct_ids(rng)), 0);
  }
}

// All empty-sphere tets of a point set by brute force, with ties broken by insphere_sos.
struct Tet {
  std::array<int, 4> v;
};
std::vector<Tet> brute_force_delaunay(const std::vector<P3>& p, const std::vector<unsigned>& ids) {
  std::vector<Tet> tets;
  const int n = int(p.size());
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      for (int c = b + 1; c < n; ++c)
        for (int d = c + 1; d < n; ++d) {
          std::array<int, 4> v = {a, b, c, d};
          const int o = orient3d(p[a].data(), p[b].data(), p[c].data(), p[d].data());
          if (o == 0) continue;
          if (o < 0) std::swap(v[0], v[1]);
          bool empty = true;
          for (int e = 0; e < n && empty; ++e) {
            if (e == a || e == b || e == c || e == d) continue;
            empty = insphere_sos(p[v[0]].data(), p[v[1]].data(), p[v[2]].data(), p[v[3]].data(),
                                 p[e].data(), ids[v[0]], ids[v[1]], ids[v[2]], ids[v[3]],
                                 ids[e]) < 0;
          }
          if (empty) tets.push_back({v});
        }
  return tets;
}

// A valid triangulation of the convex hull: every facet is shared by exactly two tets lying on
// opposite sides of it, or belongs to one tet and is a hull facet (no point strictly beyond it).
// Returns 6 * the total volume for integer coordinates.
long long check_triangulation(const std::vector<P3>& p, const std::vector<Tet>& tets) {
  std::map<std::array<int, 3>, std::vector<int>> facet_apex;  // sorted facet -> apices
  long long six_volume = 0;
  for (const Tet& t : tets) {
    const auto& v = t.v;
    const P3 &a = p[v[0]], &b = p[v[1]], &c = p[v[2]], &d = p[v[3]];
    const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
    const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
    const double wx = d[0] - a[0], wy = d[1] - a[1], wz = d[2] - a[2];
    six_volume += llround(ux * (vy * wz - vz * wy) - uy * (vx * wz - vz * wx) +
                          uz * (vx * wy - vy * wx));
    for (int i = 0; i < 4; ++i) {
      std::array<int, 3> f;
      int k = 0;
      for (int j = 0; j < 4; ++j)
        if (j != i) f[size_t(k++)] = v[size_t(j)];
      std::sort(f.begin(), f.end());
      facet_apex[f].push_back(v[size_t(i)]);
    }
  }
  for (const auto& [f, apices] : facet_apex) {
    const double *a = p[f[0]].data(), *b = p[f[1]].data(), *c = p[f[2]].data();
    EXPECT_LE(apices.size(), 2u);
    if (apices.size() == 2) {
      EXPECT_EQ(orient3d(a, b, c, p[apices[0]].data()), -orient3d(a, b, c, p[apices[1]].data()));
    } else {
      const int side = orient3d(a, b, c, p[apices[0]].data());
      for (const P3& q : p) EXPECT_NE(orient3d(a, b, c, q.data()), -side) << "not a hull facet";
    }
  }
  return six_volume;
}

std::vector<unsigned> shuffled_ids(size_t n, Rng& rng) {
  std::vector<unsigned> ids(n);
  std::iota(ids.begin(), ids.end(), 100u);
  std::shuffle(ids.begin(), ids.end(), rng.engine());
  return ids;
}

TEST(PredicatesSoS, DelaunayOfCubeAndGridIsATriangulation) {
  Rng rng(34);
  std::vector<P3> cube, grid;
  for (int i = 0; i < 8; ++i) cube.push_back({double(i & 1), double((i >> 1) & 1), double(i >> 2)});
  for (int x = 0; x < 3; ++x)
    for (int y = 0; y < 3; ++y)
      for (int z = 0; z < 3; ++z) grid.push_back({double(x), double(y), double(z)});
  for (int trial = 0; trial < 3; ++trial) {
    const auto cube_tets = brute_force_delaunay(cube, shuffled_ids(cube.size(), rng));
    EXPECT_EQ(check_triangulation(cube, cube_tets), 6);
    EXPECT_GE(cube_tets.size(), 5u);
    const auto grid_tets = brute_force_delaunay(grid, shuffled_ids(grid.size(), rng));
    EXPECT_EQ(check_triangulation(grid, grid_tets), 6 * 8);
  }
}

TEST(PredicatesSoS, DelaunayOfCosphericalLatticeIsATriangulation) {
  Rng rng(35);
  const std::vector<P3> sphere = integer_sphere(25);  // 30 points, all cospherical
  ASSERT_EQ(sphere.size(), 30u);
  reset_thread_counters();
  const auto tets = brute_force_delaunay(sphere, shuffled_ids(sphere.size(), rng));
  const long long six_volume = check_triangulation(sphere, tets);
  EXPECT_GT(six_volume, 0);
  EXPECT_GT(thread_counters().sos_ties, 1000u);
  // Another id order gives another triangulation of the same hull: same volume.
  const auto tets2 = brute_force_delaunay(sphere, shuffled_ids(sphere.size(), rng));
  EXPECT_EQ(check_triangulation(sphere, tets2), six_volume);
}

// Five cospherical points in convex general position have exactly two triangulations (2 and 3
// tets, together all five tets); the perturbed Delaunay must pick exactly one of them.
TEST(PredicatesSoS, FiveCosphericalPointsGiveOneOfTheTwoTriangulations) {
  Rng rng(36);
  const std::vector<P3> sphere = integer_sphere(50);
  int done = 0;
  while (done < 300) {
    std::vector<P3> p;
    for (int i = 0; i < 5; ++i) p.push_back(sphere[size_t(rng.integer(0, int(sphere.size()) - 1))]);
    bool general = true;
    long long total = 0;
    for (int skip = 0; skip < 5 && general; ++skip) {
      std::vector<const double*> r;
      for (int j = 0; j < 5; ++j)
        if (j != skip) r.push_back(p[size_t(j)].data());
      general = ref_orient3d(r[0], r[1], r[2], r[3]) != 0;
    }
    if (!general) continue;
    ++done;
    const auto tets = brute_force_delaunay(p, shuffled_ids(5, rng));
    ASSERT_TRUE(tets.size() == 2 || tets.size() == 3);
    const long long vol = check_triangulation(p, tets);
    for (int skip = 0; skip < 5; ++skip) {
      std::vector<P3> q;
      for (int j = 0; j < 5; ++j)
        if (j != skip) q.push_back(p[size_t(j)]);
      const double ux = q[1][0] - q[0][0], uy = q[1][1] - q[0][1], uz = q[1][2] - q[0][2];
      const double vx = q[2][0] - q[0][0], vy = q[2][1] - q[0][1], vz = q[2][2] - q[0][2];
      const double wx = q[3][0] - q[0][0], wy = q[3][1] - q[0][1], wz = q[3][2] - q[0][2];
      total += std::llabs(llround(ux * (vy * wz - vz * wy) - uy * (vx * wz - vz * wx) +
                                  uz * (vx * wy - vy * wx)));
    }
    ASSERT_EQ(2 * vol, total);
  }
}

}  // namespace
}  // namespace anitet::predicates::testing
