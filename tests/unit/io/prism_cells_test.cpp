// Boundary-layer prisms as prism cells: merge_bl_prisms (core/bl_prisms.hpp) on a hand-built
// two-layer slab split into tets as stage 1 splits them, and the writers that take prisms
// (OpenFOAM polyMesh, VTU read back by meshio), the boundary check and the refusals; the pyramids
// where a column stopped in its layer, likewise.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <map>
#include <set>
#include <string>

#include "core/bl_prisms.hpp"
#include "io/file_bytes.hpp"
#include "io/volume_io.hpp"
#include "io_test_util.hpp"

namespace anitet {
namespace {

constexpr uint32_t kNo = ~uint32_t{0};

double volume(const VolumeMesh& m, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
  const double* p = m.point(a);
  double u[3][3];
  for (int k = 0; k < 3; ++k) {
    u[0][k] = m.point(b)[k] - p[k];
    u[1][k] = m.point(c)[k] - p[k];
    u[2][k] = m.point(d)[k] - p[k];
  }
  return u[0][0] * (u[1][1] * u[2][2] - u[1][2] * u[2][1]) - u[0][1] * (u[1][0] * u[2][2] - u[1][2] * u[2][0]) +
         u[0][2] * (u[1][0] * u[2][1] - u[1][1] * u[2][0]);
}

std::array<uint32_t, 3> sorted(std::array<uint32_t, 3> a) {
  std::sort(a.begin(), a.end());
  return a;
}

// A unit square wall (triangles 0 1 2 and 0 2 3, patch 1) under two layers of height 0.1 (patch 2
// on top, 3 on the sides); vertex 4 k + i is wall vertex i pushed k times. Each prism ABC-A'B'C'
// (A < B < C, the push order) is the tets A B C A', A' B C B', A' B' C C', all region 1.
struct Slab {
  VolumeMesh mesh;
  std::vector<uint32_t> origin;
};

Slab slab() {
  Slab s;
  const double corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int k = 0; k < 3; ++k)
    for (const auto& c : corner) s.mesh.xyz.insert(s.mesh.xyz.end(), {c[0], c[1], 0.1 * k});
  s.origin.assign(12, kNo);
  for (uint32_t v = 4; v < 12; ++v) s.origin[v] = v - 4;
  for (uint32_t k = 0; k < 2; ++k)
    for (const auto& t : {std::array<uint32_t, 3>{0, 1, 2}, std::array<uint32_t, 3>{0, 2, 3}}) {
      const uint32_t a = 4 * k + t[0], b = 4 * k + t[1], c = 4 * k + t[2];
      for (std::array<uint32_t, 4> tet : {std::array<uint32_t, 4>{a, b, c, a + 4}, {a + 4, b, c, b + 4},
                                          {a + 4, b + 4, c, c + 4}}) {
        if (volume(s.mesh, tet[0], tet[1], tet[2], tet[3]) < 0) std::swap(tet[0], tet[1]);
        s.mesh.tet.insert(s.mesh.tet.end(), tet.begin(), tet.end());
        s.mesh.region.push_back(1);
      }
    }
  // Boundary: the faces of one tet; bottom patch 1, top 2, sides 3.
  std::map<std::array<uint32_t, 3>, int> count;
  for (size_t t = 0; t < s.mesh.num_tets(); ++t)
    for (const auto& f : kOutwardFace)
      ++count[sorted({s.mesh.tet[4 * t + size_t(f[0])], s.mesh.tet[4 * t + size_t(f[1])], s.mesh.tet[4 * t + size_t(f[2])]})];
  for (const auto& [f, n] : count) {
    if (n != 1) continue;
    s.mesh.bnd_tri.insert(s.mesh.bnd_tri.end(), f.begin(), f.end());
    s.mesh.bnd_patch.push_back(f[2] < 4 ? 1 : f[0] >= 8 ? 2 : 3);
  }
  return s;
}

TEST(PrismCells, MergesEachPrismsThreeTets) {
  Slab s = slab();
  Result<PrismMergeStats> merged = merge_bl_prisms(s.mesh, s.origin, 1);
  ASSERT_TRUE(merged.ok()) << merged.status().message();
  EXPECT_EQ(merged->bl_tets, 12u);
  EXPECT_EQ(merged->prisms, 4u);
  EXPECT_EQ(merged->kept_tets, 0u);
  EXPECT_EQ(s.mesh.num_tets(), 0u);
  ASSERT_EQ(s.mesh.num_prisms(), 4u);
  EXPECT_EQ(s.mesh.prism_region, std::vector<int32_t>(4, 1));
  for (size_t p = 0; p < 4; ++p) {
    const uint32_t* v = &s.mesh.prism[6 * p];
    for (int i = 0; i < 3; ++i) EXPECT_EQ(s.origin[v[3 + i]], v[i]) << "prism " << p;  // edges 0-3, 1-4, 2-5
    EXPECT_GT(volume(s.mesh, v[0], v[1], v[2], v[3]), 0) << "prism " << p;  // 0 1 2 ccw seen from the top
  }
  EXPECT_TRUE(check_boundary_elements(s.mesh, /*cover=*/true).ok());
}

TEST(PrismCells, TellsEachTetsPrism) {
  Slab s = slab();
  const VolumeMesh before = s.mesh;
  s.mesh.tet.erase(s.mesh.tet.begin(), s.mesh.tet.begin() + 4);  // the first prism stays tets
  s.mesh.region.erase(s.mesh.region.begin());
  std::vector<int32_t> tet_prism;
  // Without pyramids: the prism's two tets left would be one.
  Result<PrismMergeStats> merged = merge_bl_prisms(s.mesh, s.origin, 1, &tet_prism, /*make_pyramids=*/false);
  ASSERT_TRUE(merged.ok());
  ASSERT_EQ(tet_prism.size(), 11u);
  std::vector<int> tets_of(merged->prisms, 0);
  size_t kept = 0;
  for (size_t t = 0; t < 11; ++t) {
    if (tet_prism[t] < 0) {
      ++kept;
      continue;
    }
    ASSERT_LT(size_t(tet_prism[t]), merged->prisms);
    ++tets_of[size_t(tet_prism[t])];
    // The tet's vertices are its prism's (tet t of the mesh given is tet t + 1 of the slab).
    const uint32_t* p = &s.mesh.prism[6 * size_t(tet_prism[t])];
    for (int i = 0; i < 4; ++i) EXPECT_NE(std::find(p, p + 6, before.tet[4 * (t + 1) + size_t(i)]), p + 6);
  }
  EXPECT_EQ(kept, merged->kept_tets);
  EXPECT_EQ(tets_of, std::vector<int>(merged->prisms, 3));
}

TEST(PrismCells, KeepsTetsWhereNoExactPrism) {
  Slab s = slab();
  // Only the BL regions merge.
  VolumeMesh other = s.mesh;
  ASSERT_EQ(merge_bl_prisms(other, s.origin, 2)->prisms, 0u);
  // A prism missing a tet stays tets, and so does a prism whose quad side would lie on its tets
  // (without pyramids: its two tets left are one, PyramidCells below).
  s.mesh.tet.erase(s.mesh.tet.begin(), s.mesh.tet.begin() + 4);
  s.mesh.region.erase(s.mesh.region.begin());
  Result<PrismMergeStats> merged = merge_bl_prisms(s.mesh, s.origin, 1, nullptr, /*make_pyramids=*/false);
  ASSERT_TRUE(merged.ok());
  EXPECT_EQ(merged->bl_tets, 11u);
  EXPECT_GE(merged->prisms, 2u);  // the upper layer's at least
  EXPECT_LE(merged->prisms, 3u);
  EXPECT_EQ(merged->kept_tets, 11u - 3 * merged->prisms);
  EXPECT_EQ(s.mesh.num_tets(), merged->kept_tets);
  // No prism quad side on a face of the remaining tets.
  std::map<std::array<uint32_t, 3>, int> tet_faces;
  for (size_t t = 0; t < s.mesh.num_tets(); ++t)
    for (const auto& f : kOutwardFace)
      ++tet_faces[sorted({s.mesh.tet[4 * t + size_t(f[0])], s.mesh.tet[4 * t + size_t(f[1])], s.mesh.tet[4 * t + size_t(f[2])]})];
  for (size_t p = 0; p < s.mesh.num_prisms(); ++p)
    for (int f = 0; f < 3; ++f)
      for (int skip = 0; skip < 4; ++skip) {
        std::array<uint32_t, 3> t{};
        for (int i = 0, n = 0; i < 4; ++i)
          if (i != skip) t[size_t(n++)] = s.mesh.prism[6 * p + size_t(kPrismFace[f][i])];
        EXPECT_EQ(tet_faces.count(sorted(t)), 0u) << "prism " << p << " side " << f;
      }
  // Bad provenance is an error, not a guess.
  Slab bad = slab();
  bad.origin[0] = 4;  // a cycle 0 -> 4 -> 0
  EXPECT_EQ(merge_bl_prisms(bad.mesh, bad.origin, 1).status().code(), Error::InvalidArgument);
  EXPECT_EQ(merge_bl_prisms(bad.mesh, {}, 1).status().code(), Error::InvalidArgument);
}

// A strip of `squares` unit squares along x under two layers (no boundary triangles): vertex
// (2 squares + 2) k + 2 i + j is wall vertex (i, j) pushed k times; each square's two triangles
// meet on its diagonal (i, 0)-(i + 1, 1), split as slab() splits them.
Slab strip(uint32_t squares) {
  Slab s;
  const uint32_t nw = 2 * squares + 2;
  for (int k = 0; k < 3; ++k)
    for (uint32_t i = 0; i <= squares; ++i)
      for (int j = 0; j < 2; ++j) s.mesh.xyz.insert(s.mesh.xyz.end(), {double(i), double(j), 0.1 * k});
  s.origin.assign(3 * nw, kNo);
  for (uint32_t v = nw; v < 3 * nw; ++v) s.origin[v] = v - nw;
  for (uint32_t k = 0; k < 2; ++k)
    for (uint32_t i = 0; i < squares; ++i)
      for (const auto& t : {std::array<uint32_t, 3>{0, 2, 3}, std::array<uint32_t, 3>{0, 1, 3}}) {
        const uint32_t a = nw * k + 2 * i + t[0], b = nw * k + 2 * i + t[1], c = nw * k + 2 * i + t[2];
        for (std::array<uint32_t, 4> tet : {std::array<uint32_t, 4>{a, b, c, a + nw}, {a + nw, b, c, b + nw},
                                            {a + nw, b + nw, c, c + nw}}) {
          if (volume(s.mesh, tet[0], tet[1], tet[2], tet[3]) < 0) std::swap(tet[0], tet[1]);
          s.mesh.tet.insert(s.mesh.tet.end(), tet.begin(), tet.end());
          s.mesh.region.push_back(1);
        }
      }
  return s;
}

TEST(PrismCells, SaysWhyPrismsStayTets) {
  // 6 prisms per layer; the lower layer's first prism misses a tet (without pyramids, as around a
  // column that stopped): its two neighbours (across the diagonal and in the next square) have a quad side on
  // its tets, and the rest of the lower layer, one beside the other, a quad side on those. The
  // upper layer merges.
  Slab s = strip(3);
  Result<PrismMergeStats> whole = merge_bl_prisms(s.mesh, s.origin, 1);
  ASSERT_TRUE(whole.ok()) << whole.status().message();
  EXPECT_EQ(whole->prisms, 12u);
  EXPECT_EQ(whole->exact_prisms, 12u);
  EXPECT_EQ(whole->beside_other_cells + whole->beside_kept, 0u);
  // With pyramids, the two tets left are one (its base the quad to the next square's prism,
  // which stays a prism), and only the prism across the diagonal, whose quad lies on the missing
  // tet's face and the pyramid's side triangle, stays tets (its other sides are on the boundary).
  s = strip(3);
  s.mesh.tet.erase(s.mesh.tet.begin(), s.mesh.tet.begin() + 4);
  s.mesh.region.erase(s.mesh.region.begin());
  Result<PrismMergeStats> pyramid = merge_bl_prisms(s.mesh, s.origin, 1);
  ASSERT_TRUE(pyramid.ok()) << pyramid.status().message();
  EXPECT_EQ(pyramid->pyramids, 1u);
  EXPECT_EQ(pyramid->prisms, 10u);
  EXPECT_EQ(pyramid->beside_other_cells, 1u);
  EXPECT_EQ(pyramid->beside_kept, 0u);
  EXPECT_EQ(pyramid->kept_tets, 3u);
  s = strip(3);
  s.mesh.tet.erase(s.mesh.tet.begin(), s.mesh.tet.begin() + 4);
  s.mesh.region.erase(s.mesh.region.begin());
  Result<PrismMergeStats> merged = merge_bl_prisms(s.mesh, s.origin, 1, nullptr, /*make_pyramids=*/false);
  ASSERT_TRUE(merged.ok()) << merged.status().message();
  EXPECT_EQ(merged->exact_prisms, 11u);
  EXPECT_EQ(merged->beside_other_cells, 2u);
  EXPECT_EQ(merged->beside_kept, 3u);
  EXPECT_EQ(merged->prisms, 6u);
  EXPECT_EQ(merged->kept_tets, 2u + 3u * 5u);
  for (size_t p = 0; p < merged->prisms; ++p) EXPECT_GE(s.mesh.prism[6 * p], 8u) << "prism " << p << " is the upper layer's";
}

TEST(PrismCells, PolyMeshHasQuadFacesOwnedInOrder) {
  Slab s = slab();
  ASSERT_TRUE(merge_bl_prisms(s.mesh, s.origin, 1).ok());
  Result<PolyMesh> pm = to_polymesh(s.mesh);
  ASSERT_TRUE(pm.ok()) << pm.status().message();
  // Internal: 2 caps between the layers, the diagonal quad in each layer. Boundary: 2 + 2 caps,
  // 4 quads per layer on the sides.
  ASSERT_EQ(pm->face_size.size(), 16u);
  EXPECT_EQ(pm->num_internal_faces(), 4u);
  EXPECT_EQ(std::count(pm->face_size.begin(), pm->face_size.end(), 4), 10);
  EXPECT_EQ(pm->face.size(), 6u * 3 + 10u * 4);
  for (size_t f = 0; f < pm->num_internal_faces(); ++f) {
    EXPECT_LT(pm->owner[f], pm->neighbour[f]);
    if (f > 0) {
      EXPECT_LE(pm->owner[f - 1], pm->owner[f]);
    }
  }
  EXPECT_EQ(*std::max_element(pm->owner.begin(), pm->owner.end()), 3u);
  size_t boundary = 0;
  for (const PolyMeshPatch& p : pm->patches) boundary += p.size;
  EXPECT_EQ(boundary, 12u);
  // Each face's normal points from its owner: the owner's centroid is behind it.
  for (size_t f = 0, at = 0; f < pm->face_size.size(); at += pm->face_size[f++]) {
    double c[3] = {0, 0, 0}, q[3] = {0, 0, 0};
    const uint32_t* pv = &s.mesh.prism[6 * size_t(pm->owner[f])];
    for (int i = 0; i < 6; ++i)
      for (int k = 0; k < 3; ++k) c[k] += s.mesh.point(pv[i])[k] / 6;
    for (size_t i = 0; i < pm->face_size[f]; ++i)
      for (int k = 0; k < 3; ++k) q[k] += s.mesh.point(pm->face[at + i])[k] / pm->face_size[f];
    const double* a = s.mesh.point(pm->face[at]);
    const double* b = s.mesh.point(pm->face[at + 1]);
    const double* d = s.mesh.point(pm->face[at + 2]);
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    EXPECT_GT(n[0] * (q[0] - c[0]) + n[1] * (q[1] - c[1]) + n[2] * (q[2] - c[2]), 0) << "face " << f;
  }
}

TEST(PrismCells, BoundaryCheckCoversQuadSides) {
  Slab s = slab();
  ASSERT_TRUE(merge_bl_prisms(s.mesh, s.origin, 1).ok());
  // A side quad given by one triangle only: refused, naming the quad.
  VolumeMesh half = s.mesh;
  size_t side = 0;
  while (half.bnd_patch[side] != 3) ++side;
  half.bnd_tri.erase(half.bnd_tri.begin() + std::ptrdiff_t(3 * side), half.bnd_tri.begin() + std::ptrdiff_t(3 * side + 3));
  half.bnd_patch.erase(half.bnd_patch.begin() + std::ptrdiff_t(side));
  Status st = check_boundary_elements(half, true);
  EXPECT_EQ(st.code(), Error::InvalidMesh);
  EXPECT_NE(st.message().find("quad side"), std::string::npos) << st.message();
  // Its two triangles on two patches: refused too.
  VolumeMesh split = s.mesh;
  split.bnd_patch[side] = 4;
  EXPECT_EQ(check_boundary_elements(split, true).code(), Error::InvalidMesh);
  // A cap missing: the cover check names it.
  VolumeMesh capless = s.mesh;
  capless.bnd_tri.erase(capless.bnd_tri.begin(), capless.bnd_tri.begin() + 3);
  capless.bnd_patch.erase(capless.bnd_patch.begin());
  EXPECT_EQ(check_boundary_elements(capless, true).code(), Error::InvalidMesh);
}

TEST(PrismCells, FormatsWithoutPrismsRefuse) {
  Slab s = slab();
  ASSERT_TRUE(merge_bl_prisms(s.mesh, s.origin, 1).ok());
  const std::string dir = test::temp_dir();
  for (const char* name : {"slab.su2", "slab.msh", "slab.mesh", "slab.meshb", "slab.cgns", "slab.exo"}) {
    const Status st = write_volume_mesh(s.mesh, dir + "/" + name);
    EXPECT_EQ(st.code(), Error::UnsupportedFormat) << name;
    EXPECT_NE(st.message().find("prisms"), std::string::npos) << st.message();
  }
  EXPECT_TRUE(write_volume_mesh(s.mesh, dir + "/slab-prisms/constant/polyMesh").ok());
  Result<std::string> faces = read_file_bytes(dir + "/slab-prisms/constant/polyMesh/faces");
  ASSERT_TRUE(faces.ok());
  EXPECT_NE(faces->find("\n4("), std::string::npos);
}

TEST(PrismCells, VtuWedgesReadByMeshio) {
  if (std::system("/usr/bin/python3 -c 'import meshio' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "/usr/bin/python3 has no meshio";
  Slab s = slab();
  ASSERT_TRUE(merge_bl_prisms(s.mesh, s.origin, 1).ok());
  const std::string dir = test::temp_dir();
  ASSERT_TRUE(write_volume_mesh(s.mesh, dir + "/slab.vtu").ok());
  // In the file, VTK's wedge: 0 1 2's right-hand normal points away from 3 4 5. meshio reorders
  // wedges to its own order (Gmsh's, and VolumeMesh::prism's), where it points towards them.
  const std::string script = R"(
import sys, warnings
import xml.etree.ElementTree as ET
import numpy as np
import meshio
warnings.simplefilter("ignore")
path = sys.argv[1] + "/slab.vtu"
m = meshio.read(path)
kinds = {c.type: len(c.data) for c in m.cells}
assert kinds == {"wedge": 4, "triangle": 20}, kinds
p = m.points
def towards_top(c):
    n = np.cross(p[c[1]] - p[c[0]], p[c[2]] - p[c[0]])
    return np.dot(n, p[c[3:6]].mean(0) - p[c[:3]].mean(0))
for c in m.get_cells_type("wedge"):
    assert towards_top(c) > 0, c
arrays = {a.get("Name"): a.text.split() for a in ET.parse(path).iter("DataArray")}
raw = np.array(arrays["connectivity"], dtype=int)[:24].reshape(4, 6)
for c in raw:
    assert towards_top(c) < 0, c
region = m.cell_data["region"][[c.type for c in m.cells].index("wedge")]
assert list(region) == [1, 1, 1, 1], region
print("meshio read the wedges")
)";
  ASSERT_TRUE(write_file_bytes(dir + "/check_wedges.py", script).ok());
  EXPECT_EQ(std::system(("/usr/bin/python3 '" + dir + "/check_wedges.py' '" + dir + "' 1>&2").c_str()), 0);
}

// A grid of nx x ny unit squares (each split along (i, j)-(i + 1, j + 1)) under `layers` layers
// of height 0.1 (2 or 3), split as stage 1 splits them, with wall vertex `stop` not pushed in
// layer 1 (its column stops there: two tets, a pyramid, on each triangle around it, the
// degenerate third tet left out) and pushed again in layer 2, a layer lower than the others;
// boundary triangles: the wall patch 1, the top 2, the four sides 3.
Slab stopped_grid(uint32_t nx, uint32_t ny, uint32_t stop, uint32_t layers = 2) {
  Slab s;
  const uint32_t nw = (nx + 1) * (ny + 1);
  std::vector<uint32_t> id((layers + 1) * nw, kNo);  // (level k, wall vertex w) -> vertex
  for (uint32_t k = 0; k <= layers; ++k)
    for (uint32_t w = 0; w < nw; ++w) {
      if (k == 2 && w == stop) {
        id[2 * nw + w] = id[nw + w];
        continue;
      }
      id[k * nw + w] = uint32_t(s.origin.size());
      const uint32_t from = k == 0 ? kNo : id[(k - 1) * nw + w];
      s.origin.push_back(from);
      const double z = from == kNo ? 0.0 : s.mesh.point(from)[2] + 0.1;
      s.mesh.xyz.insert(s.mesh.xyz.end(), {double(w % (nx + 1)), double(w / (nx + 1)), z});
    }
  for (uint32_t k = 0; k < layers; ++k)
    for (uint32_t j = 0; j < ny; ++j)
      for (uint32_t i = 0; i < nx; ++i) {
        const uint32_t a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
        for (std::array<uint32_t, 3> t : {std::array<uint32_t, 3>{a, b, c}, std::array<uint32_t, 3>{a, c, d}}) {
          t = sorted(t);  // the push order: each quad side split along one diagonal from both sides
          std::array<uint32_t, 3> lo{}, hi{};
          for (size_t m = 0; m < 3; ++m) lo[m] = id[k * nw + t[m]], hi[m] = id[(k + 1) * nw + t[m]];
          for (std::array<uint32_t, 4> tet : {std::array<uint32_t, 4>{lo[0], lo[1], lo[2], hi[0]},
                                              {hi[0], lo[1], lo[2], hi[1]}, {hi[0], hi[1], lo[2], hi[2]}}) {
            if (std::set<uint32_t>(tet.begin(), tet.end()).size() < 4) continue;
            if (volume(s.mesh, tet[0], tet[1], tet[2], tet[3]) < 0) std::swap(tet[0], tet[1]);
            s.mesh.tet.insert(s.mesh.tet.end(), tet.begin(), tet.end());
            s.mesh.region.push_back(1);
          }
        }
      }
  std::map<std::array<uint32_t, 3>, int> count;
  for (size_t t = 0; t < s.mesh.num_tets(); ++t)
    for (const auto& f : kOutwardFace) {
      const uint32_t* v = &s.mesh.tet[4 * t];
      ++count[sorted({v[f[0]], v[f[1]], v[f[2]]})];
    }
  for (const auto& [f, n] : count) {
    if (n != 1) continue;
    auto all = [&](int axis, double value) {
      return std::all_of(f.begin(), f.end(), [&](uint32_t v) { return s.mesh.point(v)[axis] == value; });
    };
    s.mesh.bnd_tri.insert(s.mesh.bnd_tri.end(), f.begin(), f.end());
    const bool side = all(0, 0) || all(0, nx) || all(1, 0) || all(1, ny);
    s.mesh.bnd_patch.push_back(side ? 3 : all(2, 0) ? 1 : 2);
  }
  return s;
}

// 3 x 2 squares, 12 triangles; the interior wall vertex (1, 1) is in 6 of them. Its copy in layer
// 1, the apex, is vertex 12 + 5 (layers 0 and 1 are whole).
constexpr uint32_t kStop = 5, kApex = 17;

TEST(PyramidCells, StoppedColumnGivesPyramidsAndThePrismsBesideStay) {
  Slab s = stopped_grid(3, 2, kStop);
  Result<PrismMergeStats> merged = merge_bl_prisms(s.mesh, s.origin, 1);
  ASSERT_TRUE(merged.ok()) << merged.status().message();
  EXPECT_EQ(merged->bl_tets, 12u * 3 + 6u * 3 + 6u * 2);
  EXPECT_EQ(merged->exact_prisms, 18u);
  EXPECT_EQ(merged->exact_pyramids, 6u);
  EXPECT_EQ(merged->prisms, 18u);
  EXPECT_EQ(merged->pyramids, 6u);
  EXPECT_EQ(merged->kept_tets, 0u);
  EXPECT_EQ(merged->beside_other_cells + merged->beside_kept, 0u);
  EXPECT_EQ(s.mesh.num_tets(), 0u);
  ASSERT_EQ(s.mesh.num_pyramids(), 6u);
  EXPECT_EQ(s.mesh.pyramid_region, std::vector<int32_t>(6, 1));
  ASSERT_EQ(s.origin[kApex], kStop);
  for (size_t y = 0; y < 6; ++y) {
    const uint32_t* v = &s.mesh.pyramid[5 * y];
    EXPECT_EQ(v[4], kApex) << "pyramid " << y;
    // The base: two columns, each edge 0-1 / 2-3 or 1-2 / 3-0 one pushed from the other.
    const bool pairs01 = s.origin[v[1]] == v[0] || s.origin[v[0]] == v[1];
    EXPECT_TRUE(pairs01 ? (s.origin[v[2]] == v[3] || s.origin[v[3]] == v[2])
                        : (s.origin[v[2]] == v[1] || s.origin[v[1]] == v[2]))
        << "pyramid " << y;
    for (int i = 0; i < 4; ++i)  // 0 1 2 3 counter-clockwise seen from the apex, either diagonal
      EXPECT_GT(volume(s.mesh, v[i], v[(i + 1) % 4], v[(i + 2) % 4], v[4]), 0) << "pyramid " << y;
  }
  EXPECT_TRUE(check_boundary_elements(s.mesh, /*cover=*/true).ok());

  // Without pyramids (the C ABI's path): the stopped column's tets and its layer's prisms stay tets.
  Slab old = stopped_grid(3, 2, kStop);
  std::vector<int32_t> tet_prism, tet_pyramid;
  Result<PrismMergeStats> tets = merge_bl_prisms(old.mesh, old.origin, 1, &tet_prism, false, &tet_pyramid);
  ASSERT_TRUE(tets.ok()) << tets.status().message();
  EXPECT_EQ(tets->prisms, 12u);
  EXPECT_EQ(tets->pyramids, 0u);
  EXPECT_EQ(tets->exact_pyramids, 0u);
  EXPECT_EQ(tets->kept_tets, 66u - 36u);
  EXPECT_EQ(tets->beside_other_cells + tets->beside_kept, 6u);
  EXPECT_EQ(std::count(tet_pyramid.begin(), tet_pyramid.end(), -1), 66);
}

TEST(PyramidCells, ColumnPushedAgainInTheNextLayerStaysConforming) {
  // Layer 2's prisms on the stopped column's triangles have one column a layer lower: grouped by
  // lowest depth, the triangles where that column is first in the push order take layer 1's
  // pyramid and one tet of layer 2 as a prism (and the rest of layer 2 as a pyramid), the others
  // do not, so their quads differ: those cells stay tets, and what is written still conforms.
  Slab s = stopped_grid(3, 2, kStop, 3);
  Result<PrismMergeStats> merged = merge_bl_prisms(s.mesh, s.origin, 1);
  ASSERT_TRUE(merged.ok()) << merged.status().message();
  EXPECT_EQ(merged->bl_tets, 12u * 3 * 2 + 6u * 3 + 6u * 2);
  EXPECT_EQ(merged->kept_tets, merged->bl_tets - 3 * merged->prisms - 2 * merged->pyramids);
  EXPECT_GE(merged->prisms, 12u);  // layer 0's at least
  for (size_t p = 0; p < merged->prisms; ++p) {
    const uint32_t* v = &s.mesh.prism[6 * p];
    for (int i = 0; i < 3; ++i) EXPECT_EQ(s.origin[v[3 + i]], v[i]) << "prism " << p;
    EXPECT_GT(volume(s.mesh, v[0], v[1], v[2], v[3]), 0) << "prism " << p;
  }
  const Status faces = check_boundary_elements(s.mesh, /*cover=*/true);
  EXPECT_TRUE(faces.ok()) << faces.message();
  const Result<PolyMesh> pm = to_polymesh(s.mesh);
  EXPECT_TRUE(pm.ok()) << pm.status().message();
}

TEST(PyramidCells, TellsEachTetsCell) {
  Slab s = stopped_grid(3, 2, kStop);
  const VolumeMesh before = s.mesh;
  std::vector<int32_t> tet_prism, tet_pyramid;
  Result<PrismMergeStats> merged = merge_bl_prisms(s.mesh, s.origin, 1, &tet_prism, true, &tet_pyramid);
  ASSERT_TRUE(merged.ok());
  ASSERT_EQ(tet_pyramid.size(), before.num_tets());
  std::vector<int> tets_of(merged->pyramids, 0);
  for (size_t t = 0; t < before.num_tets(); ++t) {
    EXPECT_TRUE((tet_prism[t] < 0) != (tet_pyramid[t] < 0)) << "tet " << t << " is in one cell";
    if (tet_pyramid[t] < 0) continue;
    ++tets_of[size_t(tet_pyramid[t])];
    const uint32_t* y = &s.mesh.pyramid[5 * size_t(tet_pyramid[t])];
    for (int i = 0; i < 4; ++i) EXPECT_NE(std::find(y, y + 5, before.tet[4 * t + size_t(i)]), y + 5);
  }
  EXPECT_EQ(tets_of, std::vector<int>(merged->pyramids, 2));
}

TEST(PyramidCells, NoPyramidWhereTheApexIsNotAboveItsBase) {
  // The apex moved to (2.5, 1) crosses the planes of two pyramids' bases (over the wall edges
  // (1,0)-(2,1) and (2,1)-(2,2)): those stay tets, and so do the 5 prisms of the upper layer
  // beside them, one beside the other; the pyramid over (0,1)-(1,2) and the prism beside it, and
  // the three pyramids whose bases are on the sides, stay cells.
  Slab s = stopped_grid(3, 2, kStop);
  s.mesh.xyz[3 * kApex] = 2.5;
  Result<PrismMergeStats> merged = merge_bl_prisms(s.mesh, s.origin, 1);
  ASSERT_TRUE(merged.ok());
  EXPECT_EQ(merged->exact_pyramids, 4u);
  EXPECT_EQ(merged->pyramids, 4u);
  EXPECT_EQ(merged->prisms, 13u);
  EXPECT_EQ(merged->beside_other_cells + merged->beside_kept, 5u);
  EXPECT_EQ(merged->kept_tets, 66u - 3u * 13 - 2u * 4);
  EXPECT_TRUE(check_boundary_elements(s.mesh, /*cover=*/true).ok());
}

TEST(PyramidCells, WritersWriteThemAndTheOthersRefuse) {
  Slab s = stopped_grid(3, 2, kStop);
  ASSERT_TRUE(merge_bl_prisms(s.mesh, s.origin, 1).ok());
  const size_t cells = s.mesh.num_prisms() + s.mesh.num_pyramids();
  Result<PolyMesh> pm = to_polymesh(s.mesh);
  ASSERT_TRUE(pm.ok()) << pm.status().message();
  EXPECT_EQ(size_t(*std::max_element(pm->owner.begin(), pm->owner.end())) + 1, cells);
  // Each cell's faces: 5 for prisms and pyramids; a quad between a pyramid and a prism for each
  // pyramid whose base is not on the sides.
  std::vector<int> faces_of(cells, 0), pyramid_prism_quads(1, 0);
  for (size_t f = 0; f < pm->face_size.size(); ++f) {
    ++faces_of[pm->owner[f]];
    if (f < pm->num_internal_faces()) {
      ++faces_of[pm->neighbour[f]];
      const bool py_owner = pm->owner[f] >= s.mesh.num_prisms(), py_neigh = pm->neighbour[f] >= s.mesh.num_prisms();
      if (pm->face_size[f] == 4 && py_owner != py_neigh) ++pyramid_prism_quads[0];
    }
  }
  EXPECT_EQ(faces_of, std::vector<int>(cells, 5));
  EXPECT_EQ(pyramid_prism_quads[0], 3);
  const std::string dir = test::temp_dir();
  ASSERT_TRUE(write_volume_mesh(s.mesh, dir + "/grid/constant/polyMesh").ok());
  Result<std::string> owner = read_file_bytes(dir + "/grid/constant/polyMesh/owner");
  ASSERT_TRUE(owner.ok());
  EXPECT_NE(owner->find("nCells:24 "), std::string::npos);
  for (const char* name : {"grid.su2", "grid.msh", "grid.mesh", "grid.meshb", "grid.cgns", "grid.exo"}) {
    VolumeMesh pyramids_only = s.mesh;
    pyramids_only.prism.clear();
    pyramids_only.prism_region.clear();
    const Status st = write_volume_mesh(pyramids_only, dir + "/" + name);
    EXPECT_EQ(st.code(), Error::UnsupportedFormat) << name;
    EXPECT_NE(st.message().find("6 pyramids"), std::string::npos) << st.message();
  }
  if (std::system("/usr/bin/python3 -c 'import meshio' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "/usr/bin/python3 has no meshio";
  ASSERT_TRUE(write_volume_mesh(s.mesh, dir + "/grid.vtu").ok());
  // VTK_PYRAMID (14): the base 0 1 2 3's right-hand normal points to the apex 4.
  const std::string script = R"(
import sys, warnings
import xml.etree.ElementTree as ET
import numpy as np
import meshio
warnings.simplefilter("ignore")
path = sys.argv[1] + "/grid.vtu"
arrays = {a.get("Name"): a.text.split() for a in ET.parse(path).iter("DataArray")}
types = [int(t) for t in arrays["types"]]
assert types.count(13) == 18 and types.count(14) == 6 and types.count(10) == 0, types
m = meshio.read(path)
kinds = {c.type: len(c.data) for c in m.cells}
assert kinds["wedge"] == 18 and kinds["pyramid"] == 6, kinds
p = m.points
for c in m.get_cells_type("pyramid"):
    for i in range(4):
        a, b, d = p[c[i]], p[c[(i + 1) % 4]], p[c[(i + 2) % 4]]
        assert np.dot(np.cross(b - a, d - a), p[c[4]] - a) > 0, c
region = m.cell_data["region"][[c.type for c in m.cells].index("pyramid")]
assert list(region) == [1] * 6, region
print("meshio read the pyramids")
)";
  ASSERT_TRUE(write_file_bytes(dir + "/check_pyramids.py", script).ok());
  EXPECT_EQ(std::system(("/usr/bin/python3 '" + dir + "/check_pyramids.py' '" + dir + "' 1>&2").c_str()), 0);
}

}  // namespace
}  // namespace anitet
