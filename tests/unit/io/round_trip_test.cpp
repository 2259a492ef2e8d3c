// Writer -> reader round trips: coordinates come back bit-exact (STL: as floats), and so do
// connectivity and labels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <tuple>

#include "io/surface_io.hpp"
#include "io/volume_io.hpp"
#include "io_test_util.hpp"

namespace anitet {
namespace {

// Coordinates that are hard to print: random bit patterns, subnormals, huge, signed zeros,
// values with 17 significant digits, infinities.
std::vector<double> tricky_coordinates(size_t count, std::mt19937_64& rng) {
  std::vector<double> xyz;
  const double specials[] = {0.0,
                             -0.0,
                             0.1,
                             1.0 / 3.0,
                             5e-324,
                             -2.2250738585072014e-308,
                             1e308,
                             -1.7976931348623157e308,
                             123456789.12345679,
                             1e-7,
                             std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity()};
  for (size_t i = 0; i < 3 * count; ++i) {
    double v;
    if (i < sizeof specials / sizeof specials[0]) {
      v = specials[i];
    } else if (i % 2) {
      do {
        uint64_t bits = rng();
        std::memcpy(&v, &bits, sizeof v);
      } while (!std::isfinite(v));
    } else {
      v = std::uniform_real_distribution<double>(-10, 10)(rng);
    }
    xyz.push_back(v);
  }
  return xyz;
}

void expect_bits_equal(const std::vector<double>& a, const std::vector<double>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_TRUE(test::same_bits(a[i], b[i])) << "value " << i << ": " << a[i] << " vs " << b[i];
  }
}

SurfaceMesh random_surface(std::mt19937_64& rng, size_t nv, size_t nt, bool labels) {
  SurfaceMesh mesh;
  mesh.xyz = tricky_coordinates(nv, rng);
  for (size_t t = 0; t < nt; ++t) {
    uint32_t a = static_cast<uint32_t>(t % nv), b = static_cast<uint32_t>(rng() % nv),
             c = static_cast<uint32_t>(rng() % nv);
    // Label runs 1, 2, ... in order of first appearance (the OBJ reader numbers groups so).
    mesh.add_triangle(a, b, c, labels ? static_cast<int32_t>(1 + t / 7) : 0);
  }
  return mesh;
}

VolumeMesh random_volume(std::mt19937_64& rng, size_t nv, size_t nt, size_t nb,
                         std::vector<int32_t> label_set) {
  VolumeMesh mesh;
  mesh.xyz = tricky_coordinates(nv, rng);
  for (size_t t = 0; t < nt; ++t) {
    for (int k = 0; k < 4; ++k) {
      mesh.tet.push_back(static_cast<uint32_t>(k == 0 ? t % nv : rng() % nv));
    }
    mesh.region.push_back(label_set[rng() % label_set.size()]);
  }
  for (size_t b = 0; b < nb; ++b) {
    for (int k = 0; k < 3; ++k) mesh.bnd_tri.push_back(static_cast<uint32_t>(rng() % nv));
    mesh.bnd_patch.push_back(label_set[rng() % label_set.size()]);
  }
  return mesh;
}

TEST(SurfaceRoundTrip, OffObjMeditAreBitExact) {
  std::mt19937_64 rng(1);
  for (bool labels : {false, true}) {
    SurfaceMesh mesh = random_surface(rng, 300, 500, labels);
    Result<std::string> off = to_off(mesh), obj = to_obj(mesh), medit = to_medit(mesh);
    ASSERT_TRUE(off.ok() && obj.ok() && medit.ok());
    for (const auto& [read, data, keeps_labels] :
         {std::make_tuple(&read_off, off.value(), false),
          std::make_tuple(&read_obj, obj.value(), true),
          std::make_tuple(&read_medit_surface, medit.value(), true)}) {
      Result<SurfaceMesh> back = read(data, "round trip");
      ASSERT_TRUE(back.ok()) << back.status().message();
      expect_bits_equal(back->xyz, mesh.xyz);
      EXPECT_EQ(back->tri, mesh.tri);
      if (keeps_labels) {
        EXPECT_EQ(back->patch, mesh.patch);
      }
    }
  }
}

TEST(SurfaceRoundTrip, BinaryStlKeepsFloatCoordinates) {
  std::mt19937_64 rng(2);
  SurfaceMesh mesh;
  // Distinct float points, all used, so merging gives back the same vertices in order.
  for (int v = 0; v < 200; ++v) {
    mesh.add_vertex(float(v * 0.37), float(std::sin(v)), float(-v * 1e-3));
  }
  for (uint32_t t = 0; t + 2 < 200; ++t) mesh.add_triangle(t, t + 1, t + 2);
  Result<std::string> stl = to_stl_binary(mesh);
  ASSERT_TRUE(stl.ok());
  EXPECT_NE(stl->substr(0, 5), "solid");
  Result<SurfaceMesh> back = read_stl(stl.value(), "round trip");
  ASSERT_TRUE(back.ok()) << back.status().message();
  expect_bits_equal(back->xyz, mesh.xyz);
  EXPECT_EQ(back->tri, mesh.tri);
}

TEST(SurfaceRoundTrip, ThroughFiles) {
  std::mt19937_64 rng(3);
  SurfaceMesh mesh = random_surface(rng, 50, 80, true);
  for (const char* ext : {"off", "obj", "mesh"}) {
    const std::string path = test::temp_dir() + "/surface." + ext;
    ASSERT_TRUE(write_surface(mesh, path).ok()) << ext;
    Result<SurfaceMesh> back = read_surface(path);
    ASSERT_TRUE(back.ok()) << back.status().message();
    expect_bits_equal(back->xyz, mesh.xyz);
    EXPECT_EQ(back->tri, mesh.tri);
  }
  EXPECT_EQ(write_surface(mesh, test::temp_dir() + "/surface.ply").code(),
            Error::UnsupportedFormat);
  mesh.tri.back() = 50;
  EXPECT_EQ(write_surface(mesh, test::temp_dir() + "/bad.off").code(), Error::BadIndex);
}

TEST(VolumeRoundTrip, MeditGmshVtuAreBitExact) {
  std::mt19937_64 rng(4);
  VolumeMesh mesh = random_volume(rng, 400, 900, 300, {3, 7, 12, 40000});
  for (const char* ext : {"mesh", "msh", "vtu"}) {
    const std::string path = test::temp_dir() + "/volume." + ext;
    // The writers' text, written as is: these random tets are no mesh, so write_volume_mesh's
    // check of the boundary elements would refuse them; the codecs are what is tested here.
    const std::string e = ext;
    Result<std::string> text = e == "mesh" ? to_medit(mesh)
                               : e == "msh" ? to_gmsh(mesh)
                                            : to_vtu(mesh, {{"quality", std::vector<double>(900, 0.5)}});
    ASSERT_TRUE(text.ok()) << text.status().message();
    ASSERT_TRUE(write_file_bytes(path, text.value()).ok());
    Result<VolumeMesh> back = read_volume_mesh(path);
    ASSERT_TRUE(back.ok()) << back.status().message();
    expect_bits_equal(back->xyz, mesh.xyz);
    // Gmsh groups elements by label; the others keep the order.
    if (std::string(ext) != "msh") {
      EXPECT_EQ(back->tet, mesh.tet) << ext;
      EXPECT_EQ(back->region, mesh.region) << ext;
      EXPECT_EQ(back->bnd_tri, mesh.bnd_tri) << ext;
      EXPECT_EQ(back->bnd_patch, mesh.bnd_patch) << ext;
    }
  }
}

// The multiset of (label, vertices) of each element, to compare meshes up to element order.
template <int N>
std::vector<std::vector<int64_t>> element_set(const std::vector<uint32_t>& v,
                                              const std::vector<int32_t>& labels) {
  std::vector<std::vector<int64_t>> out;
  for (size_t e = 0; e < labels.size(); ++e) {
    std::vector<int64_t> item = {labels[e]};
    for (int k = 0; k < N; ++k) item.push_back(v[N * e + k]);
    out.push_back(item);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(VolumeRoundTrip, GmshKeepsPositiveLabelsAndRenumbersOthersInOrder) {
  std::mt19937_64 rng(5);
  VolumeMesh mesh = random_volume(rng, 100, 200, 60, {3, 7, 12});
  Result<std::string> text = to_gmsh(mesh);
  ASSERT_TRUE(text.ok());
  Result<VolumeMesh> back = read_gmsh_volume(text.value(), "round trip");
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(element_set<4>(back->tet, back->region), element_set<4>(mesh.tet, mesh.region));
  EXPECT_EQ(element_set<3>(back->bnd_tri, back->bnd_patch),
            element_set<3>(mesh.bnd_tri, mesh.bnd_patch));

  // Labels 0 and -5 cannot be physical tags: {-5, 0, 9} become 1, 2, 3.
  VolumeMesh zero = random_volume(rng, 50, 100, 0, {0, -5, 9});
  Result<VolumeMesh> renumbered = read_gmsh_volume(to_gmsh(zero).value(), "round trip");
  ASSERT_TRUE(renumbered.ok()) << renumbered.status().message();
  std::vector<int32_t> expected = zero.region;
  for (int32_t& r : expected) r = r == -5 ? 1 : r == 0 ? 2 : 3;
  EXPECT_EQ(element_set<4>(renumbered->tet, renumbered->region),
            element_set<4>(zero.tet, expected));
  EXPECT_TRUE(renumbered->bnd_tri.empty());
}

TEST(VolumeRoundTrip, EmptyRegionMeansZero) {
  std::mt19937_64 rng(6);
  VolumeMesh mesh = random_volume(rng, 20, 30, 10, {1});
  mesh.region.clear();
  Result<VolumeMesh> medit = read_medit_volume(to_medit(mesh).value(), "r");
  ASSERT_TRUE(medit.ok());
  EXPECT_EQ(medit->region, std::vector<int32_t>(30, 0));
  Result<VolumeMesh> vtu = read_vtu(to_vtu(mesh).value(), "r");
  ASSERT_TRUE(vtu.ok()) << vtu.status().message();
  EXPECT_EQ(vtu->region, std::vector<int32_t>(30, 0));
}

}  // namespace
}  // namespace anitet
