// The solver-format writers checked against their formats' rules without the solvers: patch
// names, SU2 (counts, markers, indices, orientation) and the OpenFOAM polyMesh invariants (each
// face once, owner < neighbour, upper-triangular order, orientation by cell volumes, patches),
// parsed back from the files written.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "io/mesh_faces.hpp"
#include "io/surface_io.hpp"
#include "io/volume_io.hpp"
#include "io_test_util.hpp"

#ifdef ANITET_HAVE_CGNS
#include <cgnslib.h>
#endif
#ifdef ANITET_HAVE_EXODUS
#include <exodusII.h>
#endif

namespace anitet {
namespace {

using Tri = std::array<uint32_t, 3>;

Tri sorted(Tri t) {
  std::sort(t.begin(), t.end());
  return t;
}

double volume6(const double* a, const double* b, const double* c, const double* d) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

// An n x n x n grid of unit cubes, each split into 6 positive tets (Kuhn), the tets shuffled;
// boundary triangles on the 6 sides with labels 1..6 (x-, x+, y-, y+, z-, z+), each triangle
// written in a random rotation and orientation; region 1 for x < n/2, else 2.
VolumeMesh grid_mesh(int n, unsigned seed) {
  VolumeMesh m;
  auto id = [n](int i, int j, int k) { return uint32_t((k * (n + 1) + j) * (n + 1) + i); };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) m.xyz.insert(m.xyz.end(), {double(i), double(j), 0.5 * k});
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          std::array<uint32_t, 4> t;
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[size_t(s) + 1] = id(c[0], c[1], c[2]);
          }
          if (volume6(m.point(t[0]), m.point(t[1]), m.point(t[2]), m.point(t[3])) < 0) std::swap(t[2], t[3]);
          m.tet.insert(m.tet.end(), t.begin(), t.end());
          m.region.push_back(i < n / 2 ? 1 : 2);
        }
  std::mt19937 rng(seed);
  std::vector<size_t> order(m.num_tets());
  for (size_t t = 0; t < order.size(); ++t) order[t] = t;
  std::shuffle(order.begin(), order.end(), rng);
  VolumeMesh shuffled = m;
  for (size_t t = 0; t < order.size(); ++t) {
    for (int q = 0; q < 4; ++q) shuffled.tet[4 * t + size_t(q)] = m.tet[4 * order[t] + size_t(q)];
    shuffled.region[t] = m.region[order[t]];
  }
  m = shuffled;
  std::map<Tri, int> count;
  for (size_t t = 0; t < m.num_tets(); ++t)
    for (const auto& f : kOutwardFace) ++count[sorted({m.tet[4 * t + size_t(f[0])], m.tet[4 * t + size_t(f[1])], m.tet[4 * t + size_t(f[2])]})];
  for (const auto& [tri, c] : count) {
    if (c != 1) continue;
    int label = 0;
    for (int axis = 0; axis < 3 && label == 0; ++axis) {
      const double hi = axis == 2 ? 0.5 * n : n;
      bool all_lo = true, all_hi = true;
      for (uint32_t v : tri) {
        all_lo = all_lo && m.point(v)[axis] == 0.0;
        all_hi = all_hi && m.point(v)[axis] == hi;
      }
      if (all_lo) label = 2 * axis + 1;
      if (all_hi) label = 2 * axis + 2;
    }
    Tri t = tri;
    std::rotate(t.begin(), t.begin() + rng() % 3, t.end());
    if (rng() % 2) std::swap(t[1], t[2]);
    m.bnd_tri.insert(m.bnd_tri.end(), t.begin(), t.end());
    m.bnd_patch.push_back(label);
  }
  return m;
}

const PatchNames kNames = {{1, "wall"}, {2, "FarField_out"}, {5, "symmetry_bottom"}};

std::map<int32_t, std::set<Tri>> triangles_by_patch(const VolumeMesh& m) {
  std::map<int32_t, std::set<Tri>> out;
  for (size_t b = 0; b < m.num_boundary_triangles(); ++b)
    out[m.bnd_patch[b]].insert(sorted({m.bnd_tri[3 * b], m.bnd_tri[3 * b + 1], m.bnd_tri[3 * b + 2]}));
  return out;
}

// The right-hand normal of (a, b, c) dotted with (p - a): negative when p is behind the face.
double side(const VolumeMesh& m, const Tri& t, const double* p) {
  return volume6(m.point(t[0]), m.point(t[1]), m.point(t[2]), p);
}

std::array<double, 3> centroid(const VolumeMesh& m, const uint32_t* v, int n) {
  std::array<double, 3> c{0, 0, 0};
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) c[size_t(k)] += m.point(v[i])[k] / n;
  return c;
}

// --- patch names ---

TEST(PatchNames, ParsesAndRefuses) {
  Result<PatchNames> ok = parse_patch_names(" 1=wall, 2 = farfield,-3=neg_3,");
  ASSERT_TRUE(ok.ok()) << ok.status().message();
  EXPECT_EQ(ok.value(), (PatchNames{{1, "wall"}, {2, "farfield"}, {-3, "neg_3"}}));
  for (const char* bad : {"", "1", "=wall", "x=wall", "1.5=wall", "1=wall,1=other", "1=wall,2=wall", "1=2abc",
                          "1=a-b", "1=a b", "1=_x", "1=abcdefghijklmnopqrstuvwxyz0123456", "1=wall,,2=x"}) {
    Result<PatchNames> r = parse_patch_names(bad);
    EXPECT_FALSE(r.ok()) << "'" << bad << "' was accepted";
    if (!r.ok()) {
      EXPECT_EQ(r.status().code(), Error::InvalidArgument) << bad;
    }
  }
  EXPECT_TRUE(parse_patch_names("1=abcdefghijklmnopqrstuvwxyz012345").ok());  // 32 characters
  EXPECT_EQ(patch_name({}, 3), "patch3");
  EXPECT_EQ(patch_name({}, -3), "patch_m3");
  EXPECT_EQ(patch_name(kNames, 1), "wall");
  EXPECT_EQ(region_name(0), "region0");
  EXPECT_EQ(patch_kind("wall"), PatchKind::Wall);
  EXPECT_EQ(patch_kind("FarField_out"), PatchKind::Farfield);
  EXPECT_EQ(patch_kind("SYMMETRY"), PatchKind::Symmetry);
  EXPECT_EQ(patch_kind("Inlet_1"), PatchKind::Inlet);
  EXPECT_EQ(patch_kind("main_inflow"), PatchKind::Inlet);
  EXPECT_EQ(patch_kind("OUTLET"), PatchKind::Outlet);
  EXPECT_EQ(patch_kind("outflow2"), PatchKind::Outlet);
  EXPECT_EQ(patch_kind(PatchTypes{{3, PatchKind::Patch}}, 3, "wall"), PatchKind::Patch);
  EXPECT_EQ(patch_kind(PatchTypes{{3, PatchKind::Patch}}, 4, "inlet"), PatchKind::Inlet);
}

TEST(PatchTypes, ParsesAndRefuses) {
  Result<PatchTypes> ok = parse_patch_types(" 1=wall, 2 = Inlet,-3=OUTLET,4=farfield,5=symmetry,6=patch,");
  ASSERT_TRUE(ok.ok()) << ok.status().message();
  EXPECT_EQ(ok.value(), (PatchTypes{{1, PatchKind::Wall}, {2, PatchKind::Inlet}, {-3, PatchKind::Outlet},
                                    {4, PatchKind::Farfield}, {5, PatchKind::Symmetry}, {6, PatchKind::Patch}}));
  for (PatchKind kind : {PatchKind::Wall, PatchKind::Inlet, PatchKind::Outlet, PatchKind::Farfield,
                         PatchKind::Symmetry, PatchKind::Patch}) {
    Result<PatchTypes> back = parse_patch_types("7=" + std::string(patch_kind_name(kind)));
    ASSERT_TRUE(back.ok());
    EXPECT_EQ(back.value().at(7), kind);
  }
  for (const char* bad : {"", "1", "=wall", "x=wall", "1.5=wall", "1=wall,1=inlet", "1=symmetryPlane", "1=",
                          "1=wall,,2=inlet"}) {
    Result<PatchTypes> r = parse_patch_types(bad);
    EXPECT_FALSE(r.ok()) << "'" << bad << "' was accepted";
    if (!r.ok()) {
      EXPECT_EQ(r.status().code(), Error::InvalidArgument) << bad;
    }
  }
  // A type for a label no boundary triangle has is refused by the writers.
  const VolumeMesh m = grid_mesh(1, 2);
  const Status s = write_volume_mesh(m, test::temp_dir() + "/types.su2", PatchNames{}, PatchTypes{{9, PatchKind::Inlet}});
  EXPECT_EQ(s.code(), Error::InvalidArgument);
  EXPECT_NE(s.message().find("patch label 9 (of type inlet)"), std::string::npos) << s.message();
}

TEST(PatchNames, WritersRefuseNamesTheMeshCannotCarry) {
  const VolumeMesh m = grid_mesh(2, 1);
  const std::string dir = test::temp_dir();
  // Label 9 is on no triangle; labels 2 and 3 would both be "patch3".
  for (const PatchNames& bad : {PatchNames{{9, "nine"}}, PatchNames{{2, "patch3"}}, PatchNames{{1, "bad name"}}}) {
    for (const char* file : {"/bad.su2", "/bad.msh", "/bad.mesh", "/bad.vtu", "/bad/constant/polyMesh", "/bad.cgns",
                             "/bad.exo"}) {
      const Status s = write_volume_mesh(m, dir + file, bad);
      const bool library = std::string(file).find(".cgns") != std::string::npos ? cgns_available()
                           : std::string(file).find(".exo") != std::string::npos ? exodus_available()
                                                                                   : true;
      EXPECT_EQ(s.code(), library ? Error::InvalidArgument : Error::NotImplemented) << file << ": " << s.message();
    }
  }
}

TEST(PatchNames, GmshAndMeditCarryTheNames) {
  const VolumeMesh m = grid_mesh(2, 2);
  Result<std::string> msh = to_gmsh(m, kNames);
  ASSERT_TRUE(msh.ok()) << msh.status().message();
  const std::string& g = msh.value();
  const size_t begin = g.find("$PhysicalNames\n8\n"), end = g.find("$EndPhysicalNames");
  ASSERT_NE(begin, std::string::npos);
  const std::string names = g.substr(begin, end - begin);
  for (const char* line : {"2 1 \"wall\"", "2 2 \"FarField_out\"", "2 3 \"patch3\"", "2 5 \"symmetry_bottom\"",
                           "2 6 \"patch6\"", "3 1 \"region1\"", "3 2 \"region2\""}) {
    EXPECT_NE(names.find(std::string(line) + "\n"), std::string::npos) << line;
  }
  Result<VolumeMesh> back = read_gmsh_volume(g, "names.msh");
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(triangles_by_patch(back.value()), triangles_by_patch(m));

  Result<std::string> medit = to_medit(m, kNames);
  ASSERT_TRUE(medit.ok());
  EXPECT_NE(medit.value().find("\n# patch 1 wall\n# patch 2 FarField_out\n# patch 3 patch3\n"), std::string::npos);
  Result<VolumeMesh> mback = read_medit_volume(medit.value(), "names.mesh");
  ASSERT_TRUE(mback.ok()) << mback.status().message();
  EXPECT_EQ(triangles_by_patch(mback.value()), triangles_by_patch(m));
}

// --- SU2 ---

TEST(Su2, FollowsTheFormatRules) {
  const VolumeMesh m = grid_mesh(3, 3);
  Result<std::string> text = to_su2(m, kNames);
  ASSERT_TRUE(text.ok()) << text.status().message();
  std::istringstream in(text.value());
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line[0], '%');  // comment
  auto keyword = [&](const std::string& key) {
    std::getline(in, line);
    EXPECT_EQ(line.rfind(key + "= ", 0), 0u) << "expected " << key << ", found '" << line << "'";
    return std::stoll(line.substr(key.size() + 2));
  };
  EXPECT_EQ(keyword("NDIME"), 3);
  ASSERT_EQ(keyword("NELEM"), int64_t(m.num_tets()));
  for (size_t t = 0; t < m.num_tets(); ++t) {
    int64_t type, v[4], index;
    ASSERT_TRUE(in >> type >> v[0] >> v[1] >> v[2] >> v[3] >> index);
    EXPECT_EQ(type, 10);
    EXPECT_EQ(index, int64_t(t));
    for (int q = 0; q < 4; ++q) EXPECT_EQ(v[q], int64_t(m.tet[4 * t + size_t(q)]));  // 0-based, positive as given
  }
  std::getline(in, line);
  ASSERT_EQ(keyword("NPOIN"), int64_t(m.num_vertices()));
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    double x[3];
    int64_t index;
    ASSERT_TRUE(in >> x[0] >> x[1] >> x[2] >> index);
    EXPECT_EQ(index, int64_t(v));
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(test::same_bits(x[k], m.point(v)[k]));
  }
  std::getline(in, line);
  ASSERT_EQ(keyword("NMARK"), 6);
  const std::map<int32_t, std::set<Tri>> expected = triangles_by_patch(m);
  const std::vector<std::string> tags = {"wall", "FarField_out", "patch3", "patch4", "symmetry_bottom", "patch6"};
  const double centre[3] = {1.5, 1.5, 0.75};
  for (int marker = 0; marker < 6; ++marker) {
    std::getline(in, line);
    EXPECT_EQ(line, "MARKER_TAG= " + tags[size_t(marker)]);
    const int64_t count = keyword("MARKER_ELEMS");
    const std::set<Tri>& want = expected.at(marker + 1);
    ASSERT_EQ(count, int64_t(want.size()));
    std::set<Tri> got;
    for (int64_t e = 0; e < count; ++e) {
      int64_t type;
      Tri t;
      ASSERT_TRUE(in >> type >> t[0] >> t[1] >> t[2]);
      EXPECT_EQ(type, 5);
      for (uint32_t v : t) ASSERT_LT(v, m.num_vertices());
      EXPECT_LT(side(m, t, centre), 0.0) << "marker triangle not oriented out of the (convex) domain";
      got.insert(sorted(t));
    }
    std::getline(in, line);
    EXPECT_EQ(got, want) << tags[size_t(marker)];
  }
  EXPECT_FALSE(std::getline(in, line) && !line.empty()) << "trailing '" << line << "'";
}

// --- OpenFOAM polyMesh ---

// The body of an OpenFOAM list file (after the FoamFile header): the count, then the items.
std::istringstream foam_body(const std::string& path, size_t& count) {
  const std::string text = test::load(path);
  size_t pos = text.find("FoamFile");
  EXPECT_NE(pos, std::string::npos) << path;
  pos = text.find('}', pos);
  std::istringstream in(text.substr(pos + 1));
  in >> count;
  char open = 0;
  in >> open;
  EXPECT_EQ(open, '(') << path;
  return in;
}

std::vector<uint32_t> read_labels(const std::string& path) {
  size_t n = 0;
  std::istringstream in = foam_body(path, n);
  std::vector<uint32_t> out(n);
  for (uint32_t& v : out) EXPECT_TRUE(in >> v) << path;
  char close = 0;
  in >> close;
  EXPECT_EQ(close, ')') << path;
  return out;
}

struct FoamPatch {
  std::string name, type;
  size_t n = 0, start = 0;
};

TEST(OpenFoam, PolyMeshInvariants) {
  const VolumeMesh m = grid_mesh(3, 4);
  const std::string dir = test::temp_dir() + "/case/constant/polyMesh/";
  ASSERT_TRUE(write_volume_mesh(m, test::temp_dir() + "/case/constant/polyMesh", kNames).ok());

  size_t np = 0, nf = 0;
  std::istringstream pin = foam_body(dir + "points", np);
  ASSERT_EQ(np, m.num_vertices());
  for (size_t v = 0; v < np; ++v) {
    char open, close;
    double x[3];
    ASSERT_TRUE(pin >> open >> x[0] >> x[1] >> x[2] >> close);
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(test::same_bits(x[k], m.point(v)[k]));
  }
  std::istringstream fin = foam_body(dir + "faces", nf);
  std::vector<Tri> faces(nf);
  for (Tri& f : faces) {
    std::string item;
    ASSERT_TRUE(fin >> item);  // "3(a"
    ASSERT_EQ(item.rfind("3(", 0), 0u) << item;
    f[0] = uint32_t(std::stoul(item.substr(2)));
    ASSERT_TRUE(fin >> f[1] >> item);  // "c)"
    f[2] = uint32_t(std::stoul(item));
    for (uint32_t v : f) ASSERT_LT(v, np);
  }
  const std::vector<uint32_t> owner = read_labels(dir + "owner");
  const std::vector<uint32_t> neighbour = read_labels(dir + "neighbour");
  ASSERT_EQ(owner.size(), nf);
  const size_t ni = neighbour.size(), nt = m.num_tets();

  // Each tet face exactly once; internal faces = the shared ones.
  std::map<Tri, int> tet_faces;
  for (size_t t = 0; t < nt; ++t)
    for (const auto& f : kOutwardFace) ++tet_faces[sorted({m.tet[4 * t + size_t(f[0])], m.tet[4 * t + size_t(f[1])], m.tet[4 * t + size_t(f[2])]})];
  size_t shared = 0;
  for (const auto& entry : tet_faces) shared += entry.second == 2;
  EXPECT_EQ(ni, shared);
  EXPECT_EQ(nf, tet_faces.size());
  std::set<Tri> seen;
  for (const Tri& f : faces) EXPECT_TRUE(seen.insert(sorted(f)).second) << "a face written twice";
  for (const auto& entry : tet_faces) EXPECT_TRUE(seen.count(entry.first));

  // Upper-triangular order: owner < neighbour, (owner, neighbour) strictly increasing; boundary
  // faces after. Orientation: the face's normal points from owner to neighbour, and per cell the
  // signed volumes of the cones from the centroid over its faces add up to the tet's volume.
  std::vector<double> cell_volume6(nt, 0.0);
  std::vector<int> cell_faces(nt, 0);
  for (size_t f = 0; f < nf; ++f) {
    ASSERT_LT(owner[f], nt);
    const std::array<double, 3> co = centroid(m, &m.tet[4 * owner[f]], 4);
    const double* p[3] = {m.point(faces[f][0]), m.point(faces[f][1]), m.point(faces[f][2])};
    EXPECT_LT(side(m, faces[f], co.data()), 0.0) << "face " << f << " does not point out of its owner";
    cell_volume6[owner[f]] += volume6(co.data(), p[0], p[1], p[2]);
    ++cell_faces[owner[f]];
    if (f < ni) {
      ASSERT_LT(neighbour[f], nt);
      EXPECT_LT(owner[f], neighbour[f]) << "face " << f;
      if (f > 0) {
        EXPECT_TRUE(std::pair(owner[f - 1], neighbour[f - 1]) < std::pair(owner[f], neighbour[f])) << f;
      }
      const std::array<double, 3> cn = centroid(m, &m.tet[4 * neighbour[f]], 4);
      EXPECT_GT(side(m, faces[f], cn.data()), 0.0) << "face " << f << " does not point to its neighbour";
      cell_volume6[neighbour[f]] -= volume6(cn.data(), p[0], p[1], p[2]);
      ++cell_faces[neighbour[f]];
    }
  }
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t* v = &m.tet[4 * t];
    EXPECT_EQ(cell_faces[t], 4) << t;
    // The cones from the centroid over the outward faces fill the tet: their volumes add up.
    EXPECT_NEAR(cell_volume6[t], volume6(m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3])), 1e-12) << t;
  }

  // boundary: the patches in label order, contiguous after the internal faces, each holding
  // exactly its input triangles; types from the names.
  const std::string btext = test::load(dir + "boundary");
  std::istringstream bin(btext.substr(btext.find('}') + 1));
  size_t npatch = 0;
  char paren = 0;
  ASSERT_TRUE(bin >> npatch >> paren);
  ASSERT_EQ(npatch, 6u);
  std::vector<FoamPatch> patches(npatch);
  for (FoamPatch& p : patches) {
    std::string word;
    ASSERT_TRUE(bin >> p.name >> word);
    ASSERT_EQ(word, "{");
    while (bin >> word && word != "}") {
      std::string value;
      std::getline(bin, value, ';');
      value.erase(0, value.find_first_not_of(' '));
      if (word == "type") p.type = value;
      if (word == "nFaces") p.n = std::stoul(value);
      if (word == "startFace") p.start = std::stoul(value);
    }
  }
  const std::vector<std::pair<std::string, std::string>> want = {
      {"wall", "wall"}, {"FarField_out", "patch"}, {"patch3", "wall"},
      {"patch4", "wall"}, {"symmetry_bottom", "symmetryPlane"}, {"patch6", "wall"}};
  const std::map<int32_t, std::set<Tri>> expected = triangles_by_patch(m);
  size_t next = ni;
  for (size_t p = 0; p < npatch; ++p) {
    EXPECT_EQ(patches[p].name, want[p].first);
    EXPECT_EQ(patches[p].type, want[p].second);
    EXPECT_EQ(patches[p].start, next);
    EXPECT_EQ(patches[p].n, expected.at(int32_t(p) + 1).size());
    std::set<Tri> got;
    for (size_t f = patches[p].start; f < patches[p].start + patches[p].n && f < nf; ++f) got.insert(sorted(faces[f]));
    EXPECT_EQ(got, expected.at(int32_t(p) + 1)) << patches[p].name;
    next += patches[p].n;
  }
  EXPECT_EQ(next, nf);

  // cellZones: region1 and region2 with their tets.
  const std::string ztext = test::load(dir + "cellZones");
  for (int32_t r : {1, 2}) {
    const size_t at = ztext.find("region" + std::to_string(r) + "\n{");
    ASSERT_NE(at, std::string::npos);
    std::istringstream zin(ztext.substr(ztext.find("List<label>", at) + 11));
    size_t n = 0;
    char open = 0;
    ASSERT_TRUE(zin >> n >> open);
    std::vector<uint32_t> cells(n);
    for (uint32_t& c : cells) ASSERT_TRUE(zin >> c);
    std::vector<uint32_t> expected_cells;
    for (size_t t = 0; t < nt; ++t)
      if (m.region[t] == r) expected_cells.push_back(uint32_t(t));
    EXPECT_EQ(cells, expected_cells);
  }
}

// --patch-types over the names' kinds: inlet, outlet, farfield and patch are OpenFOAM `patch`es; a
// symmetry patch is a symmetryPlane when planar, else the general `symmetry`.
TEST(OpenFoam, PatchTypesOverTheNames) {
  VolumeMesh m = grid_mesh(2, 5);
  for (int32_t& label : m.bnd_patch)
    if (label == 4) label = 3;  // y- and y+ as one non-planar patch 3
  const PatchTypes types = {{1, PatchKind::Inlet}, {2, PatchKind::Outlet}, {3, PatchKind::Symmetry},
                            {5, PatchKind::Wall}, {6, PatchKind::Patch}};
  Result<PolyMesh> pm = to_polymesh(m, kNames, types);
  ASSERT_TRUE(pm.ok()) << pm.status().message();
  std::vector<std::pair<std::string, std::string>> got;
  for (const PolyMeshPatch& p : pm.value().patches) got.emplace_back(p.name, p.type);
  EXPECT_EQ(got, (std::vector<std::pair<std::string, std::string>>{{"wall", "patch"},
                                                                   {"FarField_out", "patch"},
                                                                   {"patch3", "symmetry"},
                                                                   {"symmetry_bottom", "wall"},
                                                                   {"patch6", "patch"}}));
  m.bnd_patch = grid_mesh(2, 5).bnd_patch;  // patch 3 planar again: a symmetryPlane
  Result<PolyMesh> planar = to_polymesh(m, kNames, types);
  ASSERT_TRUE(planar.ok());
  EXPECT_EQ(planar.value().patches[2].type, "symmetryPlane");
  EXPECT_EQ(planar.value().patches[3].type, "wall");  // patch4 by its default name
}

TEST(OpenFoam, RefusesBoundaryFacesOutsideEveryPatch) {
  VolumeMesh m = grid_mesh(2, 5);
  m.bnd_tri.resize(m.bnd_tri.size() - 3);  // one boundary face without a patch
  m.bnd_patch.pop_back();
  Result<PolyMesh> pm = to_polymesh(m);
  ASSERT_FALSE(pm.ok());
  EXPECT_EQ(pm.status().code(), Error::InvalidArgument);
  EXPECT_NE(pm.status().message().find("no boundary triangle"), std::string::npos) << pm.status().message();

  VolumeMesh inner = grid_mesh(2, 5);  // a boundary triangle that is an internal face
  Result<MeshFaces> faces = build_mesh_faces(inner);
  ASSERT_TRUE(faces.ok());
  for (size_t f = 0; f < faces->across.size(); ++f) {
    if (faces->across[f] == MeshFaces::kNone) continue;
    for (int k = 0; k < 3; ++k) inner.bnd_tri.push_back(inner.tet[4 * (f / 4) + size_t(kOutwardFace[f % 4][k])]);
    inner.bnd_patch.push_back(1);
    break;
  }
  pm = to_polymesh(inner);
  ASSERT_FALSE(pm.ok());
  EXPECT_NE(pm.status().message().find("internal face"), std::string::npos) << pm.status().message();
}

TEST(SolverFormats, WriteFailuresNameTheFile) {
  const VolumeMesh m = grid_mesh(1, 8);
  const std::string parent = test::temp_dir() + "/a_file";  // a file where a directory is needed
  ASSERT_TRUE(write_file_bytes(parent, "x").ok());
  std::vector<std::string> paths = {parent + "/x.su2", parent + "/case/constant/polyMesh"};
  if (cgns_available()) paths.push_back(parent + "/x.cgns");
  if (exodus_available()) paths.push_back(parent + "/x.exo");
  for (const std::string& path : paths) {
    const Status s = write_volume_mesh(m, path);
    EXPECT_EQ(s.code(), Error::FileNotFound) << path << ": " << s.message();
    EXPECT_NE(s.message().find(parent), std::string::npos) << s.message();
  }
  EXPECT_EQ(test::load(parent), "x");  // untouched
}

TEST(Su2, BoundaryReadBackAsASurfaceWithItsMarkerNames) {
  const VolumeMesh m = grid_mesh(3, 5);
  Result<std::string> text = to_su2(m, kNames);
  ASSERT_TRUE(text.ok()) << text.status().message();
  PatchNames names;
  Result<SurfaceMesh> read = read_su2_surface(text.value(), "grid.su2", &names);
  ASSERT_TRUE(read.ok()) << read.status().message();
  const SurfaceMesh& s = read.value();
  ASSERT_EQ(s.xyz, m.xyz);  // every point, bit for bit (the volume's too)
  // Markers in increasing label order, labels 1..6 here: the same labels, names and triangles.
  const PatchNames expect = {{1, "wall"}, {2, "FarField_out"}, {3, "patch3"}, {4, "patch4"}, {5, "symmetry_bottom"}, {6, "patch6"}};
  EXPECT_EQ(names, expect);
  std::map<int32_t, std::set<Tri>> got;
  for (size_t t = 0; t < s.num_triangles(); ++t)
    got[s.patch[t]].insert(sorted({s.tri[3 * t], s.tri[3 * t + 1], s.tri[3 * t + 2]}));
  EXPECT_EQ(got, triangles_by_patch(m));
  // Oriented out of the domain: the enclosed volume is the grid's, 3 x 3 x 1.5.
  double vol6 = 0.0;
  const double origin[3] = {0, 0, 0};
  for (size_t t = 0; t < s.num_triangles(); ++t)
    vol6 += volume6(origin, s.point(s.tri[3 * t]), s.point(s.tri[3 * t + 1]), s.point(s.tri[3 * t + 2]));
  EXPECT_NEAR(vol6 / 6.0, 13.5, 1e-12);
  // Through read_surface by the extension, and refusals naming what is wrong.
  EXPECT_EQ(surface_format_from_path("a.SU2").value(), SurfaceFormat::Su2);
  const std::string head = "NDIME= 3\nNELEM= 0\nNPOIN= 3\n0 0 0\n1 0 0\n0 1 0\nNMARK= 1\nMARKER_TAG= w\n";
  auto code = [](const std::string& t) { return read_su2_surface(t, "t.su2").status().code(); };
  EXPECT_EQ(code(head + "MARKER_ELEMS= 1\n5 0 1 2\n"), Error::Ok);
  EXPECT_EQ(code(head + "MARKER_ELEMS= 1\n9 0 1 2 0\n"), Error::Ok);
  EXPECT_EQ(code(head + "MARKER_ELEMS= 1\n5 0 1 3\n"), Error::BadIndex);
  EXPECT_EQ(code(head + "MARKER_ELEMS= 1\n3 0 1\n"), Error::UnsupportedFormat);
  EXPECT_EQ(code(head + "MARKER_ELEMS= 2\n5 0 1 2\n"), Error::Parse);
  EXPECT_EQ(code(head + "MARKER_ELEMS= 0\n"), Error::EmptyInput);
  EXPECT_EQ(code("NDIME= 2\n"), Error::UnsupportedFormat);
  EXPECT_EQ(code("NPOIN= 1\n0 0 0\nNPOIN= 1\n0 0 0\n"), Error::UnsupportedFormat);
  EXPECT_EQ(code("NPOIN= 1511610054\n0 0 0\n"), Error::Parse);  // more points than the file holds
  EXPECT_EQ(read_su2_surface(head + "MARKER_TAG= my-wall\nMARKER_ELEMS= 1\n5 0 1 2\n", "t.su2", &names).status().code(),
            Error::Parse);  // not a valid patch name
}

TEST(SolverFormats, ReadersSayTheyOnlyWrite) {
  for (const char* path : {"x.su2", "x.cgns", "x.exo", "x.e", "case/constant/polyMesh", "case/constant/polyMesh/"}) {
    Result<VolumeMesh> r = read_volume_mesh(path);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().code(), Error::UnsupportedFormat) << path;
    EXPECT_NE(r.status().message().find("does not read"), std::string::npos) << r.status().message();
  }
  EXPECT_EQ(check_writable_volume_path("x.node").code(), Error::UnsupportedFormat);
  EXPECT_EQ(check_writable_volume_path("x.foam").code(), Error::UnsupportedFormat);
  EXPECT_TRUE(check_writable_volume_path("out/polyMesh").ok());
  EXPECT_EQ(check_writable_volume_path("x.cgns").code(), cgns_available() ? Error::Ok : Error::NotImplemented);
  EXPECT_EQ(check_writable_volume_path("x.exo").code(), exodus_available() ? Error::Ok : Error::NotImplemented);
}

// --- CGNS, read back with the CGNS library ---

#ifdef ANITET_HAVE_CGNS
TEST(Cgns, ReadBackWithTheCgnsLibrary) {
  ASSERT_TRUE(cgns_available());
  const VolumeMesh m = grid_mesh(2, 6);
  const std::string path = test::temp_dir() + "/grid.cgns";
  // Labels 1, 2, 5: the kinds their names imply; 3, 4, 6 typed by --patch-types.
  const PatchTypes patch_types = {{3, PatchKind::Inlet}, {4, PatchKind::Outlet}, {6, PatchKind::Patch}};
  const Status written = write_volume_mesh(m, path, kNames, patch_types);
  ASSERT_TRUE(written.ok()) << written.message();
  int fn = 0, nbases = 0, nzones = 0, ncoords = 0, nsections = 0, nbocos = 0, cell_dim = 0, phys_dim = 0;
  ASSERT_EQ(cg_open(path.c_str(), CG_MODE_READ, &fn), CG_OK) << cg_get_error();
  char name[64];
  ASSERT_EQ(cg_nbases(fn, &nbases), CG_OK);
  ASSERT_EQ(nbases, 1);
  ASSERT_EQ(cg_base_read(fn, 1, name, &cell_dim, &phys_dim), CG_OK);
  EXPECT_EQ(std::string(name), "Base");
  EXPECT_EQ(cell_dim, 3);
  EXPECT_EQ(phys_dim, 3);
  ASSERT_EQ(cg_nzones(fn, 1, &nzones), CG_OK);
  ASSERT_EQ(nzones, 1);
  cgsize_t size[3];
  ASSERT_EQ(cg_zone_read(fn, 1, 1, name, size), CG_OK);
  CGNS_ENUMT(ZoneType_t) zone_type;
  ASSERT_EQ(cg_zone_type(fn, 1, 1, &zone_type), CG_OK);
  EXPECT_EQ(zone_type, CGNS_ENUMV(Unstructured));
  EXPECT_EQ(size[0], cgsize_t(m.num_vertices()));
  EXPECT_EQ(size[1], cgsize_t(m.num_tets()));
  ASSERT_EQ(cg_ncoords(fn, 1, 1, &ncoords), CG_OK);
  EXPECT_EQ(ncoords, 3);
  const cgsize_t one = 1, nv = cgsize_t(m.num_vertices());
  std::vector<double> xyz[3];
  for (int k = 0; k < 3; ++k) {
    xyz[k].resize(m.num_vertices());
    const char* cname = k == 0 ? "CoordinateX" : k == 1 ? "CoordinateY" : "CoordinateZ";
    ASSERT_EQ(cg_coord_read(fn, 1, 1, cname, CGNS_ENUMV(RealDouble), &one, &nv, xyz[k].data()), CG_OK);
    for (size_t v = 0; v < m.num_vertices(); ++v) EXPECT_TRUE(test::same_bits(xyz[k][v], m.point(v)[k]));
  }
  ASSERT_EQ(cg_nsections(fn, 1, 1, &nsections), CG_OK);
  ASSERT_EQ(nsections, 7);  // the tets, then one per patch
  const std::map<int32_t, std::set<Tri>> expected = triangles_by_patch(m);
  const std::vector<std::string> names = {"GridElements", "wall", "FarField_out", "patch3", "patch4", "symmetry_bottom", "patch6"};
  std::vector<std::pair<cgsize_t, cgsize_t>> ranges;
  const double centre[3] = {1.0, 1.0, 0.5};
  cgsize_t next = 1;
  for (int sec = 1; sec <= nsections; ++sec) {
    CGNS_ENUMT(ElementType_t) type;
    cgsize_t start = 0, end = 0;
    int nbndry = 0, parent = 0;
    ASSERT_EQ(cg_section_read(fn, 1, 1, sec, name, &type, &start, &end, &nbndry, &parent), CG_OK);
    EXPECT_EQ(std::string(name), names[size_t(sec - 1)]);
    EXPECT_EQ(start, next);
    next = end + 1;
    ranges.emplace_back(start, end);
    std::vector<cgsize_t> conn(size_t(end - start + 1) * (sec == 1 ? 4 : 3));
    ASSERT_EQ(cg_elements_read(fn, 1, 1, sec, conn.data(), nullptr), CG_OK);
    if (sec == 1) {
      EXPECT_EQ(type, CGNS_ENUMV(TETRA_4));
      ASSERT_EQ(conn.size(), m.tet.size());
      for (size_t i = 0; i < conn.size(); ++i) EXPECT_EQ(conn[i], cgsize_t(m.tet[i]) + 1);
      continue;
    }
    EXPECT_EQ(type, CGNS_ENUMV(TRI_3));
    std::set<Tri> got;
    for (size_t e = 0; e < conn.size() / 3; ++e) {
      const Tri t = {uint32_t(conn[3 * e] - 1), uint32_t(conn[3 * e + 1] - 1), uint32_t(conn[3 * e + 2] - 1)};
      EXPECT_LT(side(m, t, centre), 0.0) << "not oriented out of the domain";
      got.insert(sorted(t));
    }
    EXPECT_EQ(got, expected.at(sec - 1)) << names[size_t(sec - 1)];
  }
  ASSERT_EQ(cg_nbocos(fn, 1, 1, &nbocos), CG_OK);
  ASSERT_EQ(nbocos, 6);
  const CGNS_ENUMT(BCType_t) types[6] = {CGNS_ENUMV(BCWall),   CGNS_ENUMV(BCFarfield),
                                         CGNS_ENUMV(BCInflow), CGNS_ENUMV(BCOutflow),
                                         CGNS_ENUMV(BCSymmetryPlane), CGNS_ENUMV(BCGeneral)};
  for (int bc = 1; bc <= nbocos; ++bc) {
    CGNS_ENUMT(BCType_t) type;
    CGNS_ENUMT(PointSetType_t) ptset;
    CGNS_ENUMT(DataType_t) normal_type;
    CGNS_ENUMT(GridLocation_t) location;
    cgsize_t npnts = 0, normal_size = 0;
    int normal_index[3], ndataset = 0;
    ASSERT_EQ(cg_boco_info(fn, 1, 1, bc, name, &type, &ptset, &npnts, normal_index, &normal_size, &normal_type,
                           &ndataset),
              CG_OK);
    EXPECT_EQ(std::string(name), names[size_t(bc)]);
    EXPECT_EQ(type, types[bc - 1]) << name;
    EXPECT_EQ(ptset, CGNS_ENUMV(PointRange));
    ASSERT_EQ(npnts, 2);
    cgsize_t range[2];
    ASSERT_EQ(cg_boco_read(fn, 1, 1, bc, range, nullptr), CG_OK);
    EXPECT_EQ(std::pair(range[0], range[1]), ranges[size_t(bc)]) << name;
    ASSERT_EQ(cg_boco_gridlocation_read(fn, 1, 1, bc, &location), CG_OK);
    EXPECT_EQ(location, CGNS_ENUMV(FaceCenter));
  }
  cg_close(fn);
}
#else
TEST(Cgns, SaysItIsNotBuilt) {
  EXPECT_FALSE(cgns_available());
  const Status s = write_volume_mesh(grid_mesh(1, 6), test::temp_dir() + "/grid.cgns");
  EXPECT_EQ(s.code(), Error::NotImplemented);
  EXPECT_NE(s.message().find("not built with CGNS"), std::string::npos) << s.message();
}
#endif

// --- Exodus II, read back with the Exodus library ---

#ifdef ANITET_HAVE_EXODUS
TEST(Exodus, ReadBackWithTheExodusLibrary) {
  ASSERT_TRUE(exodus_available());
  const VolumeMesh m = grid_mesh(2, 7);
  const std::string path = test::temp_dir() + "/grid.exo";
  const PatchTypes patch_types = {{3, PatchKind::Inlet}, {4, PatchKind::Outlet}, {6, PatchKind::Patch}};
  const Status written = write_volume_mesh(m, path, kNames, patch_types);
  ASSERT_TRUE(written.ok()) << written.message();
  int cpu_ws = sizeof(double), io_ws = 0;
  float version = 0;
  const int id = ex_open(path.c_str(), EX_READ, &cpu_ws, &io_ws, &version);
  ASSERT_GE(id, 0);
  char title[MAX_LINE_LENGTH + 1];
  int ndim = 0, nnodes = 0, nelem = 0, nblocks = 0, nnode_sets = 0, nside_sets = 0;
  ASSERT_GE(ex_get_init(id, title, &ndim, &nnodes, &nelem, &nblocks, &nnode_sets, &nside_sets), 0);
  EXPECT_EQ(ndim, 3);
  EXPECT_EQ(nnodes, int(m.num_vertices()));
  EXPECT_EQ(nelem, int(m.num_tets()));
  ASSERT_EQ(nblocks, 2);
  EXPECT_EQ(nnode_sets, 0);
  ASSERT_EQ(nside_sets, 6);
  std::vector<double> x(m.num_vertices()), y(m.num_vertices()), z(m.num_vertices());
  ASSERT_GE(ex_get_coord(id, x.data(), y.data(), z.data()), 0);
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    EXPECT_TRUE(test::same_bits(x[v], m.point(v)[0]) && test::same_bits(y[v], m.point(v)[1]) &&
                test::same_bits(z[v], m.point(v)[2]));
  }
  auto names_of = [&](ex_entity_type type, int count) {
    std::vector<std::vector<char>> storage(size_t(count), std::vector<char>(MAX_STR_LENGTH + 1, '\0'));
    std::vector<char*> ptrs;
    for (auto& st : storage) ptrs.push_back(st.data());
    EXPECT_GE(ex_get_names(id, type, ptrs.data()), 0);
    std::vector<std::string> out;
    for (auto& st : storage) out.emplace_back(st.data());
    return out;
  };
  // Blocks: region1 (id 1) then region2 (id 2); elements numbered block by block.
  int block_ids[2];
  ASSERT_GE(ex_get_ids(id, EX_ELEM_BLOCK, block_ids), 0);
  EXPECT_EQ(block_ids[0], 1);
  EXPECT_EQ(block_ids[1], 2);
  EXPECT_EQ(names_of(EX_ELEM_BLOCK, 2), (std::vector<std::string>{"region1", "region2"}));
  std::vector<int> element;  // all blocks' connectivity, 4 per Exodus element (1-based nodes)
  std::multiset<std::array<uint32_t, 4>> want_tets, got_tets;
  for (int b = 0; b < 2; ++b) {
    char type[MAX_STR_LENGTH + 1];
    int count = 0, per = 0, edges = 0, faces = 0, attrs = 0;
    ASSERT_GE(ex_get_block(id, EX_ELEM_BLOCK, block_ids[b], type, &count, &per, &edges, &faces, &attrs), 0);
    EXPECT_EQ(std::string(type), "TETRA");
    ASSERT_EQ(per, 4);
    std::vector<int> conn(size_t(count) * 4);
    ASSERT_GE(ex_get_conn(id, EX_ELEM_BLOCK, block_ids[b], conn.data(), nullptr, nullptr), 0);
    for (size_t e = 0; e < size_t(count); ++e) {
      std::array<uint32_t, 4> t;
      for (size_t q = 0; q < 4; ++q) t[q] = uint32_t(conn[4 * e + q] - 1);
      got_tets.insert(t);
      EXPECT_GT(volume6(m.point(t[0]), m.point(t[1]), m.point(t[2]), m.point(t[3])), 0.0);
    }
    element.insert(element.end(), conn.begin(), conn.end());
  }
  for (size_t t = 0; t < m.num_tets(); ++t) {
    want_tets.insert({m.tet[4 * t], m.tet[4 * t + 1], m.tet[4 * t + 2], m.tet[4 * t + 3]});
  }
  EXPECT_EQ(got_tets, want_tets);
  // Side sets: ids 1..6 named after the patches; (element, side) through Exodus's TETRA side
  // table gives exactly the patch's triangles, oriented out of the element.
  int set_ids[6];
  ASSERT_GE(ex_get_ids(id, EX_SIDE_SET, set_ids), 0);
  EXPECT_EQ(names_of(EX_SIDE_SET, 6), (std::vector<std::string>{"wall", "FarField_out", "patch3", "patch4",
                                                                "symmetry_bottom", "patch6"}));
  const int side_nodes[4][3] = {{1, 2, 4}, {2, 3, 4}, {1, 4, 3}, {1, 3, 2}};  // Exodus II manual, TETRA
  const std::map<int32_t, std::set<Tri>> expected = triangles_by_patch(m);
  for (int s = 0; s < 6; ++s) {
    EXPECT_EQ(set_ids[s], s + 1);
    int count = 0, dist = 0;
    ASSERT_GE(ex_get_set_param(id, EX_SIDE_SET, set_ids[s], &count, &dist), 0);
    std::vector<int> elems(static_cast<size_t>(count)), sides(static_cast<size_t>(count));
    ASSERT_GE(ex_get_set(id, EX_SIDE_SET, set_ids[s], elems.data(), sides.data()), 0);
    std::set<Tri> got;
    for (int i = 0; i < count; ++i) {
      ASSERT_GE(elems[size_t(i)], 1);
      ASSERT_LE(elems[size_t(i)], nelem);
      ASSERT_GE(sides[size_t(i)], 1);
      ASSERT_LE(sides[size_t(i)], 4);
      const int* e = &element[4 * size_t(elems[size_t(i)] - 1)];
      const int* sn = side_nodes[sides[size_t(i)] - 1];
      const Tri t = {uint32_t(e[sn[0] - 1] - 1), uint32_t(e[sn[1] - 1] - 1), uint32_t(e[sn[2] - 1] - 1)};
      const uint32_t tet[4] = {uint32_t(e[0] - 1), uint32_t(e[1] - 1), uint32_t(e[2] - 1), uint32_t(e[3] - 1)};
      EXPECT_LT(side(m, t, centroid(m, tet, 4).data()), 0.0) << "side not pointing out of its element";
      got.insert(sorted(t));
    }
    EXPECT_EQ(got, expected.at(s + 1)) << "side set " << s + 1;
  }
  // The patches' kinds as side-set properties (after Exodus's own ID property): 1 where the set
  // has that kind.
  const int nprops = ex_inquire_int(id, EX_INQ_SS_PROP);
  std::vector<std::vector<char>> storage(size_t(nprops), std::vector<char>(MAX_STR_LENGTH + 1, '\0'));
  std::vector<char*> ptrs;
  for (auto& st : storage) ptrs.push_back(st.data());
  ASSERT_GE(ex_get_prop_names(id, EX_SIDE_SET, ptrs.data()), 0);
  std::map<std::string, std::vector<int>> props;
  for (char* name : ptrs) {
    std::vector<int> values(6);
    ASSERT_GE(ex_get_prop_array(id, EX_SIDE_SET, name, values.data()), 0);
    props[name] = values;
  }
  EXPECT_EQ(props, (std::map<std::string, std::vector<int>>{{"ID", {1, 2, 3, 4, 5, 6}},
                                                            {"WALL", {1, 0, 0, 0, 0, 0}},
                                                            {"FARFIELD", {0, 1, 0, 0, 0, 0}},
                                                            {"INLET", {0, 0, 1, 0, 0, 0}},
                                                            {"OUTLET", {0, 0, 0, 1, 0, 0}},
                                                            {"SYMMETRY", {0, 0, 0, 0, 1, 0}},
                                                            {"PATCH", {0, 0, 0, 0, 0, 1}}}));
  ex_close(id);
}
#else
TEST(Exodus, SaysItIsNotBuilt) {
  EXPECT_FALSE(exodus_available());
  const Status s = write_volume_mesh(grid_mesh(1, 7), test::temp_dir() + "/grid.exo");
  EXPECT_EQ(s.code(), Error::NotImplemented);
  EXPECT_NE(s.message().find("not built with Exodus"), std::string::npos) << s.message();
}
#endif

}  // namespace
}  // namespace anitet
