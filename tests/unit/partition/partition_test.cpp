// The partition module: every tet own in exactly one part, ghost layers as their definition
// says (checked by brute force), owners, halo lists that agree between neighbours, the quality
// figures, bytes, and the errors. Meshes: grids of cubes of 6 tets each.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <array>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "partition/partition.hpp"

namespace anitet::partition {
namespace {

// A box of nx x ny x nz unit cubes at `origin`, 6 tets each (Kuhn: all around the cube's
// diagonal), appended to m; its outside faces as boundary triangles with patch `patch`.
void add_box(VolumeMesh& m, int nx, int ny, int nz, const std::array<double, 3>& origin, int patch, int region) {
  const uint32_t first = uint32_t(m.num_vertices());
  auto id = [&](int i, int j, int k) { return first + uint32_t((k * (ny + 1) + j) * (nx + 1) + i); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) m.xyz.insert(m.xyz.end(), {origin[0] + i, origin[1] + j, origin[2] + k});
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  std::map<std::array<uint32_t, 3>, std::array<uint32_t, 3>> faces;  // sorted -> outward, count by presence
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          std::array<uint32_t, 4> t{id(i, j, k), 0, 0, 0};
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[size_t(s) + 1] = id(c[0], c[1], c[2]);
          }
          // Orientation from the permutation's parity: odd permutations are negative.
          const bool odd = (p[0] == 0 && p[1] == 2) || (p[0] == 1 && p[1] == 0) || (p[0] == 2 && p[1] == 1);
          if (odd) std::swap(t[2], t[3]);
          m.tet.insert(m.tet.end(), t.begin(), t.end());
          m.region.push_back(region);
          const int out[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
          for (const auto& f : out) {
            std::array<uint32_t, 3> tri{t[size_t(f[0])], t[size_t(f[1])], t[size_t(f[2])]};
            std::array<uint32_t, 3> key = tri;
            std::sort(key.begin(), key.end());
            if (!faces.erase(key)) faces[key] = tri;
          }
        }
  for (const auto& [key, tri] : faces) {
    m.bnd_tri.insert(m.bnd_tri.end(), tri.begin(), tri.end());
    m.bnd_patch.push_back(patch);
  }
}

VolumeMesh box(int nx, int ny, int nz) {
  VolumeMesh m;
  add_box(m, nx, ny, nz, {0, 0, 0}, 1, 0);
  return m;
}

double volume6(const VolumeMesh& m, const uint32_t* t) {
  const double *a = m.point(t[0]), *b = m.point(t[1]), *c = m.point(t[2]), *d = m.point(t[3]);
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]},
               w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

// Ghost layers by their definition, over the whole mesh: layer[t] for part p (-1: not held).
std::vector<int> brute_layers(const VolumeMesh& m, const std::vector<int32_t>& tet_part, int p, int depth) {
  std::vector<int> layer(m.num_tets(), -1);
  std::vector<char> held_vertex(m.num_vertices(), 0);
  for (size_t t = 0; t < m.num_tets(); ++t)
    if (tet_part[t] == p) {
      layer[t] = 0;
      for (int k = 0; k < 4; ++k) held_vertex[m.tet[4 * t + size_t(k)]] = 1;
    }
  for (int l = 1; l <= depth; ++l) {
    std::vector<size_t> fresh;
    for (size_t t = 0; t < m.num_tets(); ++t) {
      if (layer[t] >= 0) continue;
      for (int k = 0; k < 4; ++k)
        if (held_vertex[m.tet[4 * t + size_t(k)]]) {
          fresh.push_back(t);
          break;
        }
    }
    for (size_t t : fresh) {
      layer[t] = l;
      for (int k = 0; k < 4; ++k) held_vertex[m.tet[4 * t + size_t(k)]] = 1;
    }
  }
  return layer;
}

// Everything part.hpp promises, checked against the mesh and the assignment.
void check_partition(const VolumeMesh& m, const Partition& result, int num_parts, int depth) {
  ASSERT_EQ(result.parts.size(), size_t(num_parts));
  ASSERT_EQ(result.tet_part.size(), m.num_tets());
  std::vector<int> own_count(m.num_tets(), 0);
  std::vector<int32_t> vertex_owner(m.num_vertices(), INT32_MAX);
  for (size_t t = 0; t < m.num_tets(); ++t)
    for (int k = 0; k < 4; ++k)
      vertex_owner[m.tet[4 * t + size_t(k)]] = std::min(vertex_owner[m.tet[4 * t + size_t(k)]], result.tet_part[t]);
  for (int p = 0; p < num_parts; ++p) {
    const Part& part = result.parts[size_t(p)];
    SCOPED_TRACE("part " + std::to_string(p));
    ASSERT_TRUE(check_part(part).ok()) << check_part(part).message();
    EXPECT_EQ(part.index, p);
    EXPECT_EQ(part.num_parts, num_parts);
    // Tets: own ones are exactly the part's, ghosts exactly the brute-force layers, each in the
    // promised order, every ghost's owner the part that owns it.
    const std::vector<int> layer = brute_layers(m, result.tet_part, p, depth);
    std::vector<std::pair<int, int64_t>> expected;
    for (size_t t = 0; t < m.num_tets(); ++t)
      if (layer[t] >= 0) expected.emplace_back(layer[t], int64_t(t));
    std::sort(expected.begin(), expected.end());
    ASSERT_EQ(part.num_tets(), int64_t(expected.size()));
    for (size_t i = 0; i < expected.size(); ++i) {
      const int64_t g = part.tet_global[i];
      EXPECT_EQ(g, expected[i].second);
      EXPECT_EQ(part.tet_layer[i], expected[i].first);
      EXPECT_EQ(part.tet_owner[i], result.tet_part[size_t(g)]);
      EXPECT_EQ(part.region[i], m.region[size_t(g)]);
      if (part.tet_layer[i] == 0) ++own_count[size_t(g)];
      for (int k = 0; k < 4; ++k)
        EXPECT_EQ(part.vertex_global[size_t(part.tet[4 * i + size_t(k)])], int64_t(m.tet[4 * size_t(g) + size_t(k)]));
    }
    EXPECT_EQ(part.owned_tets, int64_t(std::count(part.tet_layer.begin(), part.tet_layer.end(), 0)));
    // Vertices: every vertex of a local tet once, own (lowest part of its tets) first, ascending.
    std::set<int64_t> vertices;
    for (int64_t g : part.tet_global)
      for (int k = 0; k < 4; ++k) vertices.insert(m.tet[4 * size_t(g) + size_t(k)]);
    ASSERT_EQ(part.num_vertices(), int64_t(vertices.size()));
    for (int64_t i = 0; i < part.num_vertices(); ++i) {
      const int64_t g = part.vertex_global[size_t(i)];
      EXPECT_EQ(part.vertex_owner[size_t(i)], vertex_owner[size_t(g)]);
      EXPECT_EQ(part.vertex_owner[size_t(i)] == p, i < part.owned_vertices);
      if (i > 0 && i != part.owned_vertices) {
        EXPECT_LT(part.vertex_global[size_t(i) - 1], g);
      }
      for (int c = 0; c < 3; ++c) EXPECT_EQ(part.xyz[3 * size_t(i) + size_t(c)], m.xyz[3 * size_t(g) + size_t(c)]);
    }
    // Halo lists: recv from q names exactly the local items q owns; send to q is q's recv from p.
    for (int kind = 0; kind < 2; ++kind) {
      const HaloList& recv = part.halo[kind == 0 ? kVertexRecv : kTetRecv];
      const HaloList& send = part.halo[kind == 0 ? kVertexSend : kTetSend];
      const std::vector<int32_t>& owner = kind == 0 ? part.vertex_owner : part.tet_owner;
      const std::vector<int64_t>& global = kind == 0 ? part.vertex_global : part.tet_global;
      std::vector<int> seen(owner.size(), 0);
      for (size_t n = 0; n < part.neighbours.size(); ++n) {
        const int32_t q = part.neighbours[n];
        EXPECT_NE(q, p);
        const Part& other = result.parts[size_t(q)];
        const auto at = std::lower_bound(other.neighbours.begin(), other.neighbours.end(), p);
        ASSERT_TRUE(at != other.neighbours.end() && *at == p) << "neighbours are mutual";
        const size_t back = size_t(at - other.neighbours.begin());
        const HaloList& their_recv = other.halo[kind == 0 ? kVertexRecv : kTetRecv];
        const std::vector<int64_t>& their_global = kind == 0 ? other.vertex_global : other.tet_global;
        ASSERT_EQ(send.start[n + 1] - send.start[n], their_recv.start[back + 1] - their_recv.start[back]);
        for (int64_t k = 0; k < send.start[n + 1] - send.start[n]; ++k) {
          const int32_t mine = send.items[size_t(send.start[n] + k)];
          EXPECT_EQ(owner[size_t(mine)], p);
          EXPECT_EQ(global[size_t(mine)], their_global[size_t(their_recv.items[size_t(their_recv.start[back] + k)])]);
          if (k > 0) {
            EXPECT_LT(global[size_t(send.items[size_t(send.start[n] + k - 1)])], global[size_t(mine)]);
          }
        }
        for (int64_t k = recv.start[n]; k < recv.start[n + 1]; ++k) {
          EXPECT_EQ(owner[size_t(recv.items[size_t(k)])], q);
          ++seen[size_t(recv.items[size_t(k)])];
        }
      }
      for (size_t i = 0; i < owner.size(); ++i) EXPECT_EQ(seen[i], owner[i] == p ? 0 : 1) << "item " << i;
    }
    // Boundary triangles: those that are faces of local tets, own first.
    for (int64_t i = 0; i < part.num_boundary_triangles(); ++i) {
      const int64_t b = part.bnd_global[size_t(i)];
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(part.vertex_global[size_t(part.bnd_tri[3 * size_t(i) + size_t(k)])], int64_t(m.bnd_tri[3 * size_t(b) + size_t(k)]));
      EXPECT_EQ(part.bnd_patch[size_t(i)], m.bnd_patch[size_t(b)]);
    }
  }
  for (size_t t = 0; t < m.num_tets(); ++t) EXPECT_EQ(own_count[t], 1) << "tet " << t;
  // Every boundary triangle is own in exactly one part.
  std::vector<int> bnd_own(m.num_boundary_triangles(), 0);
  for (const Part& part : result.parts)
    for (int64_t i = 0; i < part.owned_boundary_triangles; ++i) ++bnd_own[size_t(part.bnd_global[size_t(i)])];
  for (int c : bnd_own) EXPECT_EQ(c, 1);
}

TEST(PartitionGraph, DualGraphOfACube) {
  VolumeMesh m = box(1, 1, 1);
  Result<Csr> g = dual_graph(m);
  ASSERT_TRUE(g.ok()) << g.status().message();
  // Kuhn's six tets around the diagonal: a ring, each tet meets two others.
  for (size_t t = 0; t < 6; ++t) EXPECT_EQ(g->end(t) - g->begin(t), 2);
  Result<Csr> vt = vertex_tets(m);
  ASSERT_TRUE(vt.ok());
  EXPECT_EQ(vt->end(0) - vt->begin(0), 6);  // the diagonal's ends are in every tet
  EXPECT_EQ(vt->end(1) - vt->begin(1), 2);  // another corner: in two
  for (size_t t = 0; t < m.num_tets(); ++t) EXPECT_GT(volume6(m, &m.tet[4 * t]), 0);
  EXPECT_EQ(m.num_boundary_triangles(), 12u);
}

TEST(PartitionGraph, FaceOfThreeTetsIsRefused) {
  VolumeMesh m = box(1, 1, 1);
  m.xyz.insert(m.xyz.end(), {-1, -1, -1, -2, -1, -1});
  const uint32_t extra = uint32_t(m.num_vertices() - 2);
  // Two more tets on a face of tet 0: one face, three tets.
  m.tet.insert(m.tet.end(), {m.tet[0], m.tet[1], m.tet[2], extra, m.tet[0], m.tet[1], m.tet[2], extra + 1});
  Result<Csr> g = dual_graph(m);
  EXPECT_FALSE(g.ok());
  EXPECT_EQ(g.status().code(), Error::InvalidMesh);
}

class PartitionParts : public ::testing::TestWithParam<std::array<int, 2>> {};

TEST_P(PartitionParts, EveryPromiseOfPartHpp) {
  const auto [num_parts, depth] = GetParam();
  const VolumeMesh m = box(8, 6, 5);  // 1440 tets
  PartitionOptions o;
  o.num_parts = num_parts;
  o.ghost_layers = depth;
  Result<Partition> r = partition_mesh(m, o);
  ASSERT_TRUE(r.ok()) << r.status().message();
  check_partition(m, r.value(), num_parts, depth);
  EXPECT_LE(r->quality.imbalance, 0.03 + 1e-12);
  EXPECT_EQ(r->quality.empty_parts, 0);
  EXPECT_EQ(r->quality.total_weight, double(m.num_tets()));
  if (num_parts == 1) {
    EXPECT_EQ(r->quality.edge_cut, 0);
  }
}

INSTANTIATE_TEST_SUITE_P(CountsAndDepths, PartitionParts,
                         ::testing::Values(std::array<int, 2>{1, 1}, std::array<int, 2>{2, 0},
                                           std::array<int, 2>{2, 1}, std::array<int, 2>{5, 1},
                                           std::array<int, 2>{8, 2}, std::array<int, 2>{3, 4}));

TEST(Partition, QualityAgainstMetisOnTheSameGraph) {
  const VolumeMesh m = box(16, 12, 10);  // 11520 tets
  Result<Csr> dual = dual_graph(m);
  Result<Csr> vt = vertex_tets(m);
  ASSERT_TRUE(dual.ok() && vt.ok());
  for (int n : {2, 8, 64}) {
    PartitionOptions o;
    o.num_parts = n;
    Result<Partition> r = partition_mesh(m, o);
    ASSERT_TRUE(r.ok()) << r.status().message();
    // The reported figures are those of the assignment, recounted here.
    int64_t cut = 0;
    for (size_t t = 0; t < m.num_tets(); ++t)
      for (int64_t k = dual->begin(t); k < dual->end(t); ++k)
        cut += dual->items[size_t(k)] > t && r->tet_part[dual->items[size_t(k)]] != r->tet_part[t];
    EXPECT_EQ(r->quality.edge_cut, cut);
    std::vector<int64_t> load(size_t(n), 0);
    for (int32_t p : r->tet_part) ++load[size_t(p)];
    const double imbalance = double(*std::max_element(load.begin(), load.end())) * n / double(m.num_tets()) - 1;
    EXPECT_DOUBLE_EQ(r->quality.imbalance, imbalance);
    EXPECT_LE(imbalance, 0.03 + 1e-12) << n << " parts";
    // METIS's own cut of the same graph with its defaults (as gpmetis runs): within 10%.
    Result<std::vector<int32_t>> metis = cut_dual_graph(dual.value(), n, {}, 0.03);
    ASSERT_TRUE(metis.ok());
    const PartitionQuality q = measure_partition(dual.value(), vt.value(), metis.value(), n, nullptr);
    EXPECT_LE(double(cut), 1.10 * double(q.edge_cut)) << n << " parts";
    check_partition(m, r.value(), n, 1);
  }
}

TEST(Partition, DisconnectedPiecesMaySharePartsAndGhostsStopAtTheGap) {
  VolumeMesh m;
  add_box(m, 6, 4, 4, {0, 0, 0}, 1, 1);
  add_box(m, 3, 4, 4, {10, 0, 0}, 2, 2);  // no vertex in common with the first
  for (int n : {2, 3, 4}) {
    PartitionOptions o;
    o.num_parts = n;
    o.ghost_layers = 2;
    Result<Partition> r = partition_mesh(m, o);
    ASSERT_TRUE(r.ok()) << r.status().message();
    check_partition(m, r.value(), n, 2);
    EXPECT_LE(r->quality.imbalance, 0.03 + 1e-12);
    for (const Part& part : r->parts) {
      std::set<int32_t> own_regions, ghost_regions;
      for (int64_t i = 0; i < part.num_tets(); ++i)
        (i < part.owned_tets ? own_regions : ghost_regions).insert(part.region[size_t(i)]);
      for (int32_t g : ghost_regions) EXPECT_TRUE(own_regions.count(g)) << "a ghost across the gap";
    }
  }
}

TEST(Partition, WeightsBalanceTheWeights) {
  const VolumeMesh m = box(10, 6, 6);
  std::vector<double> w(m.num_tets());
  for (size_t t = 0; t < w.size(); ++t) w[t] = m.point(m.tet[4 * t])[0] < 5 ? 3.0 : 1.0;
  PartitionOptions o;
  o.num_parts = 4;
  o.tet_weights = w.data();
  Result<Partition> r = partition_mesh(m, o);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_LE(r->quality.imbalance, 0.03 + 1e-9);
  double total = 0;
  for (double x : w) total += x;
  EXPECT_DOUBLE_EQ(r->quality.total_weight, total);
  // Balanced in weight, recounted here, hence not in tets: the weights were used.
  std::vector<double> load(4, 0.0);
  std::vector<int64_t> tets(4, 0);
  for (size_t t = 0; t < m.num_tets(); ++t) {
    load[size_t(r->tet_part[t])] += w[t];
    ++tets[size_t(r->tet_part[t])];
  }
  EXPECT_LE(*std::max_element(load.begin(), load.end()) * 4 / total, 1.03 + 1e-9);
  EXPECT_GT(double(*std::max_element(tets.begin(), tets.end())), 1.3 * double(*std::min_element(tets.begin(), tets.end())));
  check_partition(m, r.value(), 4, 1);
}

TEST(Partition, BadInput) {
  const VolumeMesh m = box(2, 1, 1);  // 12 tets
  PartitionOptions o;
  for (int n : {0, -1, 13}) {
    o.num_parts = n;
    Result<Partition> r = partition_mesh(m, o);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().code(), Error::InvalidArgument) << n;
  }
  o.num_parts = 12;  // one tet each: allowed
  Result<Partition> all = partition_mesh(m, o);
  ASSERT_TRUE(all.ok()) << all.status().message();
  check_partition(m, all.value(), 12, 1);
  o.num_parts = 2;
  o.ghost_layers = -1;
  EXPECT_EQ(partition_mesh(m, o).status().code(), Error::InvalidArgument);
  o.ghost_layers = 1;
  for (double imbalance : {0.0, -0.1, 1.5, std::nan("")}) {
    o.imbalance = imbalance;
    EXPECT_EQ(partition_mesh(m, o).status().code(), Error::InvalidArgument) << imbalance;
  }
  o.imbalance = 0.03;
  std::vector<double> w(m.num_tets(), 1.0);
  o.tet_weights = w.data();
  for (double bad : {-1.0, std::nan(""), HUGE_VAL}) {
    w[5] = bad;
    EXPECT_EQ(partition_mesh(m, o).status().code(), Error::InvalidArgument) << bad;
  }
  std::fill(w.begin(), w.end(), 0.0);
  EXPECT_EQ(partition_mesh(m, o).status().code(), Error::InvalidArgument);
  o.tet_weights = nullptr;
  EXPECT_EQ(partition_mesh(VolumeMesh{}, o).status().code(), Error::EmptyInput);
  VolumeMesh bad_index = m;
  bad_index.tet[7] = 1000;
  EXPECT_EQ(partition_mesh(bad_index, o).status().code(), Error::BadIndex);
}

TEST(PartitionBytes, BytesRoundTripAndCheckedOnTheWayBack) {
  const VolumeMesh m = box(4, 3, 3);
  PartitionOptions o;
  o.num_parts = 3;
  Result<Partition> r = partition_mesh(m, o);
  ASSERT_TRUE(r.ok());
  for (const Part& part : r->parts) {
    const std::vector<uint8_t> bytes = serialize_part(part);
    Result<Part> back = deserialize_part(bytes.data(), bytes.size());
    ASSERT_TRUE(back.ok()) << back.status().message();
    EXPECT_EQ(serialize_part(back.value()), bytes);
    EXPECT_EQ(back->tet_global, part.tet_global);
    EXPECT_EQ(back->halo[kVertexSend].items, part.halo[kVertexSend].items);
    // Every truncation and a flipped byte in each array's count fail cleanly.
    for (size_t n = 0; n < bytes.size(); n += 7) {
      Result<Part> cut = deserialize_part(bytes.data(), n);
      EXPECT_FALSE(cut.ok());
      EXPECT_EQ(cut.status().code(), Error::Parse);
    }
    std::vector<uint8_t> longer = bytes;
    longer.push_back(0);
    EXPECT_FALSE(deserialize_part(longer.data(), longer.size()).ok());
    for (size_t at = 0; at < bytes.size(); at += 97) {
      std::vector<uint8_t> flipped = bytes;
      flipped[at] ^= 0x5a;
      Result<Part> f = deserialize_part(flipped.data(), flipped.size());
      if (f.ok()) {
        EXPECT_TRUE(check_part(f.value()).ok());  // a coordinate may change harmlessly
      }
    }
  }
  Part wrong = r->parts[0];
  wrong.tet[0] = int32_t(wrong.num_vertices());
  EXPECT_FALSE(check_part(wrong).ok());
  std::vector<uint8_t> bytes = serialize_part(wrong);
  EXPECT_EQ(deserialize_part(bytes.data(), bytes.size()).status().code(), Error::Parse);
}

}  // namespace
}  // namespace anitet::partition
