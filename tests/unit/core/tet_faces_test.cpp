// census_faces against a plain std::map count of the faces, on a grid of tets with its vertices
// shuffled, and on the cases the writers' check refuses.
#include "core/tet_faces.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <random>
#include <vector>

namespace anitet {
namespace {

using Face = std::array<uint32_t, 3>;

// n^3 cubes of 6 tets each (vertex (i, j, k) is i + (n+1) (j + (n+1) k)), ids shuffled.
std::vector<uint32_t> grid_tets(int n, unsigned seed, size_t& num_vertices) {
  num_vertices = size_t(n + 1) * size_t(n + 1) * size_t(n + 1);
  std::vector<uint32_t> perm(num_vertices);
  std::iota(perm.begin(), perm.end(), 0u);
  std::shuffle(perm.begin(), perm.end(), std::mt19937(seed));
  auto id = [&](int i, int j, int k) { return perm[size_t((k * (n + 1) + j) * (n + 1) + i)]; };
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  std::vector<uint32_t> tets;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          tets.push_back(id(c[0], c[1], c[2]));
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            tets.push_back(id(c[0], c[1], c[2]));
          }
        }
  return tets;
}

std::map<Face, int> reference(const std::vector<uint32_t>& tets) {
  std::map<Face, int> count;
  for (size_t t = 0; t < tets.size() / 4; ++t)
    for (int i = 0; i < 4; ++i) {
      Face f;
      int k = 0;
      for (int j = 0; j < 4; ++j)
        if (j != i) f[size_t(k++)] = tets[4 * t + size_t(j)];
      std::sort(f.begin(), f.end());
      ++count[f];
    }
  return count;
}

TEST(TetFaces, BoundaryFacesMatchAPlainCount) {
  for (bool parallel : {false, true}) {
    size_t nv = 0;
    const std::vector<uint32_t> tets = grid_tets(12, 3, nv);  // 10,368 tets: several chunks of work
    const FaceCensus c = census_faces(tets.data(), tets.size() / 4, nv, parallel);
    std::vector<Face> expected, got;
    for (const auto& [f, n] : reference(tets))
      if (n == 1) expected.push_back(f);
    for (size_t i = 0; i < c.boundary.size(); i += 3) got.push_back({c.boundary[i], c.boundary[i + 1], c.boundary[i + 2]});
    EXPECT_EQ(got.size(), size_t(6 * 2 * 12 * 12));
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, expected);
    EXPECT_EQ(c.shared_by_more_than_two, 0u);
    EXPECT_TRUE(c.tets_of_triangle.empty());
  }
  // The same list, in the same order, on one core and on all.
  size_t nv = 0;
  const std::vector<uint32_t> tets = grid_tets(12, 4, nv);
  EXPECT_EQ(census_faces(tets.data(), tets.size() / 4, nv, false).boundary,
            census_faces(tets.data(), tets.size() / 4, nv, true).boundary);
}

TEST(TetFaces, TrianglesAreCheckedAgainstTheTets) {
  size_t nv = 0;
  std::vector<uint32_t> tets = grid_tets(3, 5, nv);
  const std::map<Face, int> count = reference(tets);
  std::vector<uint32_t> tri;
  Face interior{}, boundary{};
  for (const auto& [f, n] : count) {
    if (n == 1) {
      tri.insert(tri.end(), f.begin(), f.end());
      boundary = f;
    } else {
      interior = f;
    }
  }
  const size_t nb = tri.size() / 3;
  FaceCensus all = census_faces(tets.data(), tets.size() / 4, nv, true, tri.data(), nb);
  EXPECT_TRUE(all.uncovered.empty());
  EXPECT_TRUE(all.repeated.empty());
  EXPECT_EQ(std::count(all.tets_of_triangle.begin(), all.tets_of_triangle.end(), uint8_t(1)), std::ptrdiff_t(nb));
  // An interface (a face of two tets), a repeat, a triangle of no tet, one boundary face left out.
  std::vector<uint32_t> more(tri.begin() + 3, tri.end());
  more.insert(more.end(), interior.begin(), interior.end());
  more.insert(more.end(), boundary.begin(), boundary.end());
  more.insert(more.end(), {tri[3], tri[4], 0u == tri[5] ? 1u : 0u});
  const FaceCensus c = census_faces(tets.data(), tets.size() / 4, nv, false, more.data(), more.size() / 3);
  const size_t n = more.size() / 3;
  EXPECT_EQ(c.tets_of_triangle[n - 3], 2u);  // the interface
  EXPECT_EQ(c.repeated, std::vector<uint32_t>{uint32_t(n - 2)});
  EXPECT_EQ(c.uncovered, (std::vector<uint32_t>{tri[0], tri[1], tri[2]}));
  // Overlapping tets: a face of three.
  tets.insert(tets.end(), tets.begin(), tets.begin() + 4);
  EXPECT_GT(census_faces(tets.data(), tets.size() / 4, nv, false).shared_by_more_than_two, 0u);
}

}  // namespace
}  // namespace anitet
