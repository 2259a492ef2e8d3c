// A volume mesh as the input surface: every reader that can hold vertices off the surface (.mesh,
// .msh, .vtu, .su2, TetGen .node/.ele) times every writer, on a cube whose interior vertices come
// first, in the middle and last in the file. The boundary elements written must be faces of the
// tets written, cover their boundary once and keep the input's patch labels and names: checked
// here by a face test of the test's own (a std::map of sorted triples), not by anitet's.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <unistd.h>

#include "core/tet_mesh.hpp"
#include "io/surface_io.hpp"
#include "io/volume_io.hpp"
#include "pipeline/mesher.hpp"

using namespace anitet;

namespace {

using Face = std::array<uint32_t, 3>;

Face sorted(uint32_t a, uint32_t b, uint32_t c) {
  Face f{a, b, c};
  std::sort(f.begin(), f.end());
  return f;
}

double volume6(const double* a, const double* b, const double* c, const double* d) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]},
               w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

// The patch of a boundary point set on the unit cube: 1..6 for x=0, x=1, y=0, y=1, z=0, z=1.
int32_t cube_side(const VolumeMesh& m, const uint32_t* tri) {
  for (int axis = 0; axis < 3; ++axis)
    for (int hi = 0; hi < 2; ++hi) {
      bool all = true;
      for (int c = 0; c < 3; ++c) all = all && m.point(tri[c])[axis] == double(hi);
      if (all) return int32_t(1 + 2 * axis + hi);
    }
  return 0;
}

// The unit cube as n^3 cells of 6 tets each (64 vertices, 8 interior, for n = 3), its boundary
// triangles labelled by side; vertices renumbered so that the interior ones come at `where`
// (0: first, 1: in the middle, 2: last).
VolumeMesh cube_mesh(int n, int where) {
  VolumeMesh grid;
  auto id = [n](int i, int j, int k) { return uint32_t((k * (n + 1) + j) * (n + 1) + i); };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) grid.xyz.insert(grid.xyz.end(), {double(i) / n, double(j) / n, double(k) / n});
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
          if (volume6(grid.point(t[0]), grid.point(t[1]), grid.point(t[2]), grid.point(t[3])) < 0) std::swap(t[2], t[3]);
          grid.tet.insert(grid.tet.end(), t.begin(), t.end());
          grid.region.push_back(0);
        }
  // Boundary triangles: the faces of one tet, oriented out of it.
  std::map<Face, int> count;
  const int faces[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};
  for (size_t t = 0; t < grid.num_tets(); ++t)
    for (const auto& f : faces) ++count[sorted(grid.tet[4 * t + f[0]], grid.tet[4 * t + f[1]], grid.tet[4 * t + f[2]])];
  for (size_t t = 0; t < grid.num_tets(); ++t)
    for (const auto& f : faces) {
      const uint32_t tri[3] = {grid.tet[4 * t + f[0]], grid.tet[4 * t + f[1]], grid.tet[4 * t + f[2]]};
      if (count[sorted(tri[0], tri[1], tri[2])] != 1) continue;
      grid.bnd_tri.insert(grid.bnd_tri.end(), tri, tri + 3);
      grid.bnd_patch.push_back(cube_side(grid, tri));
    }
  // The new order: surface vertices in grid order, the interior ones inserted at `where`.
  std::vector<uint32_t> surface, interior;
  for (uint32_t v = 0; v < grid.num_vertices(); ++v) {
    bool inside = true;
    for (int k = 0; k < 3; ++k) inside = inside && grid.point(v)[k] > 0.0 && grid.point(v)[k] < 1.0;
    (inside ? interior : surface).push_back(v);
  }
  const size_t at = where == 0 ? 0 : where == 1 ? surface.size() / 2 : surface.size();
  std::vector<uint32_t> order(surface.begin(), surface.begin() + std::ptrdiff_t(at));
  order.insert(order.end(), interior.begin(), interior.end());
  order.insert(order.end(), surface.begin() + std::ptrdiff_t(at), surface.end());
  std::vector<uint32_t> new_id(order.size());
  VolumeMesh m = grid;
  for (size_t i = 0; i < order.size(); ++i) {
    new_id[order[i]] = uint32_t(i);
    std::copy_n(grid.point(order[i]), 3, &m.xyz[3 * i]);
  }
  for (uint32_t& v : m.tet) v = new_id[v];
  for (uint32_t& v : m.bnd_tri) v = new_id[v];
  return m;
}

// The test's own face test: every boundary triangle a face of the tets, every face of one tet a
// boundary triangle exactly once, and each triangle's patch the cube side it lies on.
void expect_boundary_elements_right(const VolumeMesh& m, const std::string& what) {
  std::map<Face, int> tets_of, triangles_of;
  for (size_t t = 0; t < m.num_tets(); ++t) {
    const uint32_t* v = &m.tet[4 * t];
    for (int i = 0; i < 4; ++i) ++tets_of[sorted(v[(i + 1) % 4], v[(i + 2) % 4], v[(i + 3) % 4])];
  }
  size_t not_faces = 0, wrong_patch = 0;
  for (size_t b = 0; b < m.num_boundary_triangles(); ++b) {
    const uint32_t* v = &m.bnd_tri[3 * b];
    const Face f = sorted(v[0], v[1], v[2]);
    ++triangles_of[f];
    not_faces += tets_of.count(f) == 0;
    wrong_patch += m.bnd_patch[b] != cube_side(m, v);
  }
  size_t uncovered = 0, repeated = 0;
  for (const auto& [f, n] : tets_of) {
    if (n != 1) continue;
    const auto it = triangles_of.find(f);
    uncovered += it == triangles_of.end();
    repeated += it != triangles_of.end() && it->second > 1;
  }
  EXPECT_GT(m.num_boundary_triangles(), 0u) << what;
  EXPECT_EQ(not_faces, 0u) << what << ": boundary triangles that are no face of the tets";
  EXPECT_EQ(uncovered, 0u) << what << ": boundary faces of the tets without a boundary triangle";
  EXPECT_EQ(repeated, 0u) << what;
  EXPECT_EQ(wrong_patch, 0u) << what << ": boundary triangles whose patch is not their cube side";
}

const PatchNames kNames = {{1, "xlo"}, {2, "xhi"}, {3, "ylo"}, {4, "yhi"}, {5, "zlo"}, {6, "zhi"}};

std::string dir() {
  static const std::string d = [] {
    const std::string path = (std::filesystem::temp_directory_path() / ("anitet_volume_input_" + std::to_string(::getpid()))).string();
    std::filesystem::create_directories(path);
    return path;
  }();
  return d;
}

// TetGen files, written by the test (anitet writes no TetGen): 1-based, region attribute, faces
// with their markers.
void write_tetgen(const VolumeMesh& m, const std::string& base) {
  std::ofstream node(base + ".node"), ele(base + ".ele"), face(base + ".face");
  node.precision(17);
  node << m.num_vertices() << " 3 0 0\n";
  for (size_t v = 0; v < m.num_vertices(); ++v)
    node << v + 1 << " " << m.point(v)[0] << " " << m.point(v)[1] << " " << m.point(v)[2] << "\n";
  ele << m.num_tets() << " 4 0\n";
  for (size_t t = 0; t < m.num_tets(); ++t)
    ele << t + 1 << " " << m.tet[4 * t] + 1 << " " << m.tet[4 * t + 1] + 1 << " " << m.tet[4 * t + 2] + 1 << " "
        << m.tet[4 * t + 3] + 1 << "\n";
  face << m.num_boundary_triangles() << " 1\n";
  for (size_t b = 0; b < m.num_boundary_triangles(); ++b)
    face << b + 1 << " " << m.bnd_tri[3 * b] + 1 << " " << m.bnd_tri[3 * b + 1] + 1 << " " << m.bnd_tri[3 * b + 2] + 1
         << " " << m.bnd_patch[b] << "\n";
}

const char* kWhere[] = {"interior vertices first", "interior vertices in the middle", "interior vertices last"};

}  // namespace

TEST(VolumeInput, EveryReaderTimesEveryWriterKeepsTheBoundaryElements) {
  for (int where = 0; where < 3; ++where) {
    const VolumeMesh input = cube_mesh(3, where);
    expect_boundary_elements_right(input, std::string("the input, ") + kWhere[where]);
    std::vector<std::string> files;
    for (const char* ext : {".mesh", ".msh", ".vtu", ".su2"}) {
      const std::string path = dir() + "/in" + std::to_string(where) + ext;
      ASSERT_TRUE(write_volume_mesh(input, path, kNames).ok()) << path;
      files.push_back(path);
    }
    write_tetgen(input, dir() + "/in" + std::to_string(where));
    files.push_back(dir() + "/in" + std::to_string(where) + ".ele");
    for (const std::string& file : files) {
      const std::string what = file + " (" + kWhere[where] + ")";
      PatchNames names;
      Result<SurfaceMesh> surface = read_surface(file, &names);
      ASSERT_TRUE(surface.ok()) << what << ": " << surface.status().message();
      EXPECT_EQ(surface->num_vertices(), 64u) << what << ": every vertex of the file kept";
      const bool has_names = file.find(".vtu") == std::string::npos && file.find(".ele") == std::string::npos;
      if (has_names) {
        EXPECT_EQ(names, kNames) << what;
      }
      Result<MesherResult> run = Mesher().run(surface.value());
      ASSERT_TRUE(run.ok()) << what << ": " << run.status().message();
      expect_boundary_elements_right(run->mesh, what + " -> mesh");
      // The interior vertices are no output vertices; the others keep their order.
      size_t kept = 0;
      for (uint32_t v : run->input_vertex) kept += v != TetMesh::kNone;
      EXPECT_EQ(kept, 56u) << what;
      for (const char* ext : {".mesh", ".msh", ".vtu", ".su2", "/constant/polyMesh", ".cgns", ".exo"}) {
        const std::string out = dir() + "/out" + ext;
        const Status st = write_volume_mesh(run->mesh, out, names);
        if (st.code() == Error::NotImplemented) continue;  // a build without CGNS or Exodus II
        ASSERT_TRUE(st.ok()) << what << " -> " << out << ": " << st.message();
        if (std::string(ext) == ".mesh" || std::string(ext) == ".msh" || std::string(ext) == ".vtu") {
          Result<VolumeMesh> back = read_volume_mesh(out);
          ASSERT_TRUE(back.ok()) << out << ": " << back.status().message();
          expect_boundary_elements_right(back.value(), what + " -> " + out);
        }
      }
    }
  }
}

TEST(VolumeInput, TetsWithoutTrianglesGiveTheirBoundary) {
  VolumeMesh input = cube_mesh(2, 1);
  const size_t triangles = input.num_boundary_triangles();
  input.bnd_tri.clear();
  input.bnd_patch.clear();
  const std::string path = dir() + "/tets_only.mesh";
  ASSERT_TRUE(write_volume_mesh(input, path).ok());
  Result<SurfaceMesh> surface = read_surface(path);
  ASSERT_TRUE(surface.ok()) << surface.status().message();
  EXPECT_EQ(surface->num_triangles(), triangles);
  EXPECT_EQ(surface->num_vertices(), input.num_vertices());
  Result<MesherResult> run = Mesher().run(surface.value());
  ASSERT_TRUE(run.ok()) << run.status().message();
  EXPECT_EQ(run->mesh.num_boundary_triangles(), triangles);
}

// The writers' own check: nothing wrong is written, whatever the format.
TEST(VolumeInput, WritersRefuseBoundaryElementsThatAreWrong) {
  const VolumeMesh good = cube_mesh(2, 0);
  VolumeMesh not_a_face = good, uncovered = good, repeated = good, bare = good;
  // Three corners of the side z = 0: a triangle on the boundary, but no face of a tet.
  auto corner = [&](double x, double y) {
    for (uint32_t v = 0; v < good.num_vertices(); ++v)
      if (good.point(v)[0] == x && good.point(v)[1] == y && good.point(v)[2] == 0.0) return v;
    return uint32_t(0);
  };
  not_a_face.bnd_tri[0] = corner(0, 0);
  not_a_face.bnd_tri[1] = corner(1, 0);
  not_a_face.bnd_tri[2] = corner(1, 1);
  uncovered.bnd_tri.resize(uncovered.bnd_tri.size() - 3);
  uncovered.bnd_patch.pop_back();
  repeated.bnd_tri.insert(repeated.bnd_tri.end(), good.bnd_tri.begin(), good.bnd_tri.begin() + 3);
  repeated.bnd_patch.push_back(good.bnd_patch[0]);
  bare.bnd_tri.clear();
  bare.bnd_patch.clear();
  for (const char* ext : {".mesh", ".msh", ".vtu", ".su2", "/constant/polyMesh", ".cgns", ".exo"}) {
    for (const auto& [mesh, what] : {std::pair{&not_a_face, "not a face"}, std::pair{&uncovered, "uncovered"},
                                     std::pair{&repeated, "repeated"}}) {
      const std::string out = dir() + "/bad" + std::to_string(std::hash<std::string>()(what)) + ext;
      const Status st = write_volume_mesh(*mesh, out);
      EXPECT_EQ(st.code(), Error::InvalidMesh) << ext << ", " << what << ": " << st.message();
      EXPECT_FALSE(std::filesystem::exists(out)) << ext << ", " << what;
    }
    // Without any boundary triangle: fine where boundary elements are optional, refused where a
    // solver reads its boundary conditions from them.
    const bool markers = std::string(ext) == ".su2" || std::string(ext) == "/constant/polyMesh" ||
                         std::string(ext) == ".cgns" || std::string(ext) == ".exo";
    const Status st = write_volume_mesh(bare, dir() + "/bare" + ext);
    if (st.code() != Error::NotImplemented) {
      EXPECT_EQ(st.ok(), !markers) << ext << ": " << st.message();
    }
  }
  EXPECT_TRUE(write_volume_mesh(good, dir() + "/good.su2").ok());
}
