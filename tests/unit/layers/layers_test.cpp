// Stage 1 (advancing-front layers): the sizing interface, the dynamic front and its index, the
// exact fit test, and build_layers on built-in shapes and shared surfaces, audited by
// check_layers (validity, input faces kept, S1 closed and off S, volumes).
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "core/sizing.hpp"
#include "io/surface_io.hpp"
#include "layers/front.hpp"
#include "layers/layers.hpp"
#include "layers/layers_check.hpp"
#include "layers/loose_octree.hpp"
#include "layers/tet_fit.hpp"
#include "shapes.hpp"
#include "validate/validate.hpp"

namespace anitet {
namespace {

double signed_volume(const SurfaceMesh& s) {
  double v = 0.0;
  for (size_t t = 0; t < s.num_triangles(); ++t) {
    const double* a = s.point(s.tri[3 * t]);
    const double* b = s.point(s.tri[3 * t + 1]);
    const double* c = s.point(s.tri[3 * t + 2]);
    v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
         a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return v / 6.0;
}

SurfaceMesh shared_surface(const std::string& name) {
  Result<SurfaceMesh> read = read_surface(std::string(ANITET_SURFACES_DIR) + "/" + name);
  EXPECT_TRUE(read.ok()) << read.status().message();
  if (!read.ok()) return SurfaceMesh();
  SurfaceMesh s = std::move(read).value();
  // Orientation repair and structure checks; the exact self-intersection search is validate's
  // own test (the shared clean surfaces have none).
  ValidationOptions options;
  options.check_self_intersections = false;
  const ValidationReport report = validate_surface(s, options);
  EXPECT_TRUE(report.ok()) << report.summary();
  return s;
}

LayersOutput run_layers(const SurfaceMesh& s, int layers,
                        LayerScheme scheme = LayerScheme::kPushOnly) {
  IsotropicSurfaceSizing sizing(s);
  LayersOptions options;
  options.layers = layers;
  options.scheme = scheme;
  Result<LayersOutput> out = build_layers(s, sizing, options);
  EXPECT_TRUE(out.ok()) << out.status().message();
  return out.ok() ? std::move(out).value() : LayersOutput();
}

void expect_valid_layers(const SurfaceMesh& s, const LayersOutput& out, int layers) {
  const LayersCheck c = check_layers(s, out);
  EXPECT_TRUE(c.mesh_valid) << c.problems;
  EXPECT_TRUE(c.input_vertices_kept) << c.problems;
  EXPECT_TRUE(c.input_faces_present) << c.problems;
  EXPECT_TRUE(c.boundary_is_s_and_s1) << c.problems;
  EXPECT_TRUE(c.front_manifold) << c.problems;
  EXPECT_TRUE(c.front_off_input) << c.problems;
  EXPECT_TRUE(c.front_disjoint) << c.problems;
  EXPECT_TRUE(c.front_tets_match) << c.problems;
  EXPECT_LE(c.volume_rel_error, 1e-12) << "vol(T1) " << c.volume_t1 << " vol(S) " << c.volume_s
                                       << " vol(S1) " << c.volume_s1;
  EXPECT_GT(c.volume_t1, 0.0);
  EXPECT_EQ(out.stats.per_layer.size(), size_t(layers));
  EXPECT_EQ(out.stats.tets, out.mesh.num_tet_slots());
}

// ---- Sizing -------------------------------------------------------------------------------------

TEST(Sizing, MetricHelpers) {
  double m[6];
  isotropic_metric(0.5, m);
  const double e[3] = {1.0, 0.0, 0.0};
  EXPECT_DOUBLE_EQ(metric_norm(m, e), 2.0);
  const double a[3] = {0, 0, 0}, b[3] = {0, 3, 4};
  EXPECT_DOUBLE_EQ(metric_edge_length(m, a, b), 10.0);
  // An anisotropic metric: lengths along z count 3 times.
  const double aniso[6] = {1, 0, 1, 0, 0, 9};
  const double z[3] = {0, 0, 2}, xy[3] = {3, 4, 0};
  EXPECT_DOUBLE_EQ(metric_norm(aniso, z), 6.0);
  EXPECT_DOUBLE_EQ(metric_norm(aniso, xy), 5.0);
}

TEST(Sizing, SurfaceSizingIsTheNearestVertexsMeanEdge) {
  const SurfaceMesh s = test::grid_cube(4);  // edges 0.25 and diagonals 0.25 sqrt(2)
  IsotropicSurfaceSizing sizing(s);
  // Vertex 0 is a cube corner: its incident edges, computed by hand from the triangles.
  double sum = 0.0;
  int count = 0;
  for (size_t t = 0; t < s.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t x = s.tri[3 * t + k], y = s.tri[3 * t + (k + 1) % 3];
      if (x != 0 && y != 0) continue;
      const double* p = s.point(x);
      const double* q = s.point(y);
      sum += std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                       (p[2] - q[2]) * (p[2] - q[2]));
      ++count;
    }
  EXPECT_NEAR(sizing.size(s.point(0)), sum / count, 1e-15);
  // Near vertex 0 (inside the cube), the same size; every size is an incident-edge mean.
  const double near0[3] = {s.point(0)[0] + 0.01, s.point(0)[1] + 0.02, s.point(0)[2] + 0.01};
  EXPECT_DOUBLE_EQ(sizing.size(near0), sizing.size(s.point(0)));
  const double centre[3] = {0.5, 0.5, 0.5};
  EXPECT_GE(sizing.size(centre), 0.25);
  EXPECT_LE(sizing.size(centre), 0.25 * std::sqrt(2.0));
  double m[6];
  sizing.metric(near0, m);
  EXPECT_NEAR(m[0], 1.0 / (sizing.size(near0) * sizing.size(near0)), 1e-12);
  EXPECT_EQ(m[1], 0.0);
  IsotropicSurfaceSizing doubled(s, 2.0);
  EXPECT_DOUBLE_EQ(doubled.size(near0), 2.0 * sizing.size(near0));
}

TEST(Sizing, NearestVertexMatchesBruteForce) {
  const SurfaceMesh s = test::icosphere(2);
  IsotropicSurfaceSizing sizing(s);
  IsotropicSurfaceSizing reference(s);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  // Per-vertex sizes by brute force nearest vertex.
  for (int i = 0; i < 200; ++i) {
    const double p[3] = {u(rng), u(rng), u(rng)};
    size_t best = 0;
    double best_d2 = 1e300;
    for (size_t v = 0; v < s.num_vertices(); ++v) {
      const double* q = s.point(v);
      const double d2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                        (p[2] - q[2]) * (p[2] - q[2]);
      if (d2 < best_d2) best_d2 = d2, best = v;
    }
    EXPECT_DOUBLE_EQ(sizing.size(p), reference.size(s.point(best)));
  }
}

// ---- Loose octree and front ---------------------------------------------------------------------

TEST(LooseOctree, QueriesFindEveryOverlappingBox) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pos(0.0, 1.0), expo(-5.0, 0.0);
  Box3 bounds{{0, 0, 0}, {1, 1, 1}};
  layers::LooseOctree index;
  index.reset(bounds);
  std::vector<Box3> boxes;
  std::vector<bool> alive;
  for (uint32_t i = 0; i < 2000; ++i) {
    Box3 b;
    const double size = std::pow(10.0, expo(rng));  // 1e-5 .. 1: CAD-like spread
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = pos(rng) * (1.0 - size);
      b.hi[k] = b.lo[k] + size * pos(rng);
    }
    boxes.push_back(b);
    alive.push_back(true);
    index.insert(i, b);
  }
  for (uint32_t i = 0; i < 2000; i += 3) {
    index.erase(i);
    alive[i] = false;
  }
  EXPECT_EQ(index.size(), size_t(2000 - 667));
  auto overlap = [](const Box3& a, const Box3& b) {
    for (int k = 0; k < 3; ++k)
      if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
    return true;
  };
  for (int q = 0; q < 300; ++q) {
    Box3 query;
    const double size = std::pow(10.0, expo(rng));
    for (int k = 0; k < 3; ++k) {
      query.lo[k] = pos(rng) * (1.0 - size);
      query.hi[k] = query.lo[k] + size;
    }
    std::vector<uint32_t> found;
    index.query(query, [&](uint32_t id) {
      found.push_back(id);
      return true;
    });
    std::sort(found.begin(), found.end());
    for (uint32_t i = 0; i < boxes.size(); ++i) {
      const bool listed = std::binary_search(found.begin(), found.end(), i);
      if (alive[i] && overlap(boxes[i], query)) {
        EXPECT_TRUE(listed) << "box " << i;
      }
      if (!alive[i]) {
        EXPECT_FALSE(listed) << "erased box " << i;
      }
    }
  }
}

TEST(Front, RollbackRestoresTheFrontExactly) {
  const SurfaceMesh s = test::grid_cube(2);
  std::vector<double> xyz = s.xyz;
  Box3 bounds{{0, 0, 0}, {1, 1, 1}};
  layers::Front front(xyz, bounds);
  for (size_t t = 0; t < s.num_triangles(); ++t)
    front.add(s.tri[3 * t], s.tri[3 * t + 1], s.tri[3 * t + 2], layers::Front::kNone);
  front.remove(5);  // outside a transaction: slot 5 is free for reuse
  const size_t alive_before = front.num_alive();
  std::vector<std::vector<uint32_t>> stars;
  for (uint32_t v = 0; v < s.num_vertices(); ++v) {
    std::vector<uint32_t> st = front.star(v);
    std::sort(st.begin(), st.end());
    stars.push_back(st);
  }
  front.begin();
  front.remove(0);
  front.remove(1);
  const uint32_t added = front.add(0, 1, 2, 7);
  front.remove(added);
  front.add(3, 4, 5, 8);
  front.rollback();
  EXPECT_EQ(front.num_alive(), alive_before);
  EXPECT_TRUE(front.alive(0));
  EXPECT_TRUE(front.alive(1));
  EXPECT_FALSE(front.alive(5));
  for (uint32_t v = 0; v < s.num_vertices(); ++v) {
    std::vector<uint32_t> st = front.star(v);
    std::sort(st.begin(), st.end());
    EXPECT_EQ(st, stars[v]) << "vertex " << v;
  }
  EXPECT_EQ(front.find(s.tri[0], s.tri[2], s.tri[1]), 0u);
  // After a commit, removed slots are reused.
  front.begin();
  front.remove(2);
  front.commit();
  EXPECT_FALSE(front.alive(2));
  const uint32_t reused = front.add(0, 1, 2, 9);
  EXPECT_TRUE(reused == 2 || reused == 5);
}

// ---- The exact fit test ---------------------------------------------------------------------------

TEST(TetFit, AcceptsAFittingTetAndRejectsCrossingOnes) {
  // Front: the grid cube with 2 cells per side (outward normals: the region is the cube).
  const SurfaceMesh s = test::grid_cube(2);
  std::vector<double> xyz = s.xyz;
  Box3 bounds{{0, 0, 0}, {1, 1, 1}};
  layers::Front front(xyz, bounds);
  for (size_t t = 0; t < s.num_triangles(); ++t)
    front.add(s.tri[3 * t], s.tri[3 * t + 1], s.tri[3 * t + 2], layers::Front::kNone);
  // Base: front triangle 0; apex over its centroid, into the cube.
  const uint32_t a = s.tri[0], b = s.tri[1], c = s.tri[2];
  double n[3], mid[3];
  const double *pa = s.point(a), *pb = s.point(b), *pc = s.point(c);
  const double e1[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
  const double e2[3] = {pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]};
  n[0] = e1[1] * e2[2] - e1[2] * e2[1];
  n[1] = e1[2] * e2[0] - e1[0] * e2[2];
  n[2] = e1[0] * e2[1] - e1[1] * e2[0];
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (int k = 0; k < 3; ++k) mid[k] = (pa[k] + pb[k] + pc[k]) / 3.0;
  auto apex_at = [&](double h) {
    xyz.resize(3 * s.num_vertices());
    for (int k = 0; k < 3; ++k) xyz.push_back(mid[k] - h * n[k] / len);
    return static_cast<uint32_t>(s.num_vertices());
  };
  layers::FitCounters counters;
  uint32_t closing[4];
  {
    const uint32_t p = apex_at(0.2);
    const uint32_t v[4] = {a, c, b, p};
    EXPECT_TRUE(layers::tet_fits(front, xyz, v, closing, counters));
    EXPECT_EQ(closing[3], 0u);  // the base
    EXPECT_EQ(closing[0], layers::Front::kNone);
  }
  {
    const uint32_t p = apex_at(1.5);  // through the opposite face
    const uint32_t v[4] = {a, c, b, p};
    EXPECT_FALSE(layers::tet_fits(front, xyz, v, closing, counters));
  }
  {
    const uint32_t p = apex_at(-0.2);  // outside the region: negative tet
    const uint32_t v[4] = {a, c, b, p};
    EXPECT_FALSE(layers::tet_fits(front, xyz, v, closing, counters));
    const uint32_t w[4] = {a, b, c, p};  // positive, but on the wrong side of its base
    EXPECT_FALSE(layers::tet_fits(front, xyz, w, closing, counters));
  }
  EXPECT_GT(counters.tests, 0u);
  EXPECT_GT(counters.tri_tests, 0u);
}

// ---- build_layers ---------------------------------------------------------------------------------

struct ShapeCase {
  const char* name;
  SurfaceMesh (*make)();
};

SurfaceMesh make_coarse_cube() { return test::coarse_cube(); }
SurfaceMesh make_grid_cube() { return test::grid_cube(6); }
SurfaceMesh make_sphere() { return test::icosphere(3); }
SurfaceMesh make_nested() { return test::nested_cubes(); }
SurfaceMesh make_slab() { return test::thin_slab(); }

const ShapeCase kShapes[] = {{"coarse_cube", make_coarse_cube},
                             {"grid_cube", make_grid_cube},
                             {"sphere", make_sphere},
                             {"nested_cubes", make_nested},
                             {"thin_slab", make_slab}};

class LayersOnShapes : public ::testing::TestWithParam<std::tuple<int, int>> {};

TEST_P(LayersOnShapes, AreValidAndHideTheSurface) {
  const ShapeCase& shape = kShapes[std::get<0>(GetParam())];
  const int layers = std::get<1>(GetParam());
  const SurfaceMesh s = shape.make();
  ASSERT_NE(signed_volume(s), 0.0);
  const LayersOutput out = run_layers(s, layers);
  SCOPED_TRACE(shape.name);
  expect_valid_layers(s, out, layers);
}

INSTANTIATE_TEST_SUITE_P(Shapes, LayersOnShapes,
                         ::testing::Combine(::testing::Range(0, 5), ::testing::Values(1, 2, 3)),
                         [](const ::testing::TestParamInfo<std::tuple<int, int>>& p) {
                           return std::string(kShapes[std::get<0>(p.param)].name) + "_" +
                                  std::to_string(std::get<1>(p.param)) + "_layers";
                         });

class LayersOnSharedSurfaces
    : public ::testing::TestWithParam<std::tuple<const char*, int>> {};

TEST_P(LayersOnSharedSurfaces, AreValidAndHideTheSurface) {
  const SurfaceMesh s = shared_surface(std::get<0>(GetParam()));
  ASSERT_GT(s.num_triangles(), 0u);
  const int layers = std::get<1>(GetParam());
  const LayersOutput out = run_layers(s, layers);
  expect_valid_layers(s, out, layers);
}

INSTANTIATE_TEST_SUITE_P(
    Shared, LayersOnSharedSurfaces,
    ::testing::Combine(::testing::Values("fandisk.off", "decimated-knight.off", "tray_bottom.stl"),
                       ::testing::Values(1, 2, 3)),
    [](const ::testing::TestParamInfo<std::tuple<const char*, int>>& p) {
      std::string name = std::get<0>(p.param);
      for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return name + "_" + std::to_string(std::get<1>(p.param)) + "_layers";
    });

TEST(Layers, PaperSchemeIsValidToo) {
  // (Two layers of it triple the front twice and need many partial pushes: slow, so only on
  // the small shapes.)
  for (const ShapeCase& shape : kShapes) {
    const SurfaceMesh s = shape.make();
    for (int layers : {1, 2}) {
      if (layers == 2 && s.num_triangles() > 400) continue;
      SCOPED_TRACE(std::string(shape.name) + " " + std::to_string(layers));
      const LayersOutput out = run_layers(s, layers, LayerScheme::kFacesThenPush);
      expect_valid_layers(s, out, layers);
      EXPECT_GT(out.stats.face_tets, 0u);
    }
  }
  const SurfaceMesh knight = shared_surface("decimated-knight.off");
  const LayersOutput out = run_layers(knight, 1, LayerScheme::kFacesThenPush);
  expect_valid_layers(knight, out, 1);
  EXPECT_EQ(out.stats.face_tets, knight.num_triangles());
}

TEST(Layers, PrismLayersKeepTheFrontsConnectivityAndQuality) {
  // On a smooth sphere every push sees its whole star: each layer is one prism (3 tets) per
  // triangle, S1 has S's triangle count, and the tets are good.
  const SurfaceMesh s = test::icosphere(3);
  const LayersOutput out = run_layers(s, 2);
  expect_valid_layers(s, out, 2);
  EXPECT_EQ(out.num_front_triangles(), s.num_triangles());
  EXPECT_EQ(out.stats.tets, 2 * 3 * s.num_triangles());
  EXPECT_EQ(out.stats.partial_pushes, 0u);
  const LayersQuality q = layers_quality(out);
  EXPECT_GT(q.mean, 0.6);
  EXPECT_GT(q.min, 0.2);
}

TEST(Layers, ThinPartsGetThinnerLayersButStayValid) {
  const SurfaceMesh s = test::thin_slab();
  const LayersOutput out = run_layers(s, 3);
  expect_valid_layers(s, out, 3);
  // The slab is 0.1 thick: S1 must lie strictly inside it.
  for (uint32_t v : out.front_tri) {
    EXPECT_GT(out.mesh.point(v)[2], 0.0);
    EXPECT_LT(out.mesh.point(v)[2], 0.1);
  }
}

TEST(Layers, OutputConventions) {
  const SurfaceMesh s = test::nested_cubes();
  const LayersOutput out = run_layers(s, 2);
  const TetMesh& m = out.mesh;
  // Input facets are protected, S1 vertices flagged, new vertices after the input ones.
  size_t protected_facets = 0;
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t)
    for (int i = 0; i < 4; ++i) protected_facets += m.facet_protected(t, i);
  EXPECT_EQ(protected_facets, s.num_triangles());
  for (uint32_t v : out.front_tri) EXPECT_TRUE(m.vflags[v] & vflag::kOnFront);
  for (size_t v = 0; v < s.num_vertices(); ++v) EXPECT_FALSE(m.vflags[v] & vflag::kOnFront);
  EXPECT_EQ(out.stats.new_vertices, m.num_vertices() - s.num_vertices());
  // S1 has two shells here (outer and around the cavity): its volume is the region left.
  std::vector<uint32_t> map;
  const SurfaceMesh s1 = front_surface(out, &map);
  EXPECT_EQ(s1.num_triangles(), out.num_front_triangles());
  EXPECT_EQ(map.size(), s1.num_vertices());
  for (size_t i = 0; i < s1.tri.size(); ++i) EXPECT_EQ(map[s1.tri[i]], out.front_tri[i]);
  const LayersCheck c = check_layers(s, out);
  EXPECT_NEAR(signed_volume(s1), c.volume_s1, 1e-9);
  EXPECT_GT(c.volume_s1, 0.0);
  EXPECT_LT(c.volume_s1, c.volume_s);
}

TEST(Layers, IsDeterministic) {
  const SurfaceMesh s = shared_surface("decimated-knight.off");
  const LayersOutput a = run_layers(s, 2);
  const LayersOutput b = run_layers(s, 2);
  EXPECT_EQ(a.mesh.xyz, b.mesh.xyz);
  EXPECT_EQ(a.mesh.tet_v, b.mesh.tet_v);
  EXPECT_EQ(a.front_tri, b.front_tri);
}

// The push tasks (LayersOptions::push_tasks_min_vertices): fandisk's layers are pushed mostly by
// the two tasks, and give the same bits on one thread as on two (the second layer's tasks number
// their tets after the first layer's).
TEST(Layers, PushTasksGiveTheSameLayersOnOneThreadAsOnTwo) {
  const SurfaceMesh s = shared_surface("fandisk.off");
  IsotropicSurfaceSizing sizing(s);
  LayersOptions options;
  options.layers = 2;
  ASSERT_LT(options.push_tasks_min_vertices, s.num_vertices());
  LayersOutput out[2];
  for (int threads = 1; threads <= 2; ++threads) {
    tbb::task_arena arena(threads);
    arena.execute([&] {
      Result<LayersOutput> r = build_layers(s, sizing, options);
      ASSERT_TRUE(r.ok()) << r.status().message();
      out[threads - 1] = std::move(r).value();
    });
  }
  expect_valid_layers(s, out[1], 2);
  EXPECT_GT(out[1].stats.task_pushes, out[1].stats.pushes / 2);
  EXPECT_LT(out[1].stats.task_pushes, out[1].stats.pushes);
  EXPECT_EQ(out[0].mesh.xyz, out[1].mesh.xyz);
  EXPECT_EQ(out[0].mesh.tet_v, out[1].mesh.tet_v);
  EXPECT_EQ(out[0].mesh.tet_flags, out[1].mesh.tet_flags);
  EXPECT_EQ(out[0].front_tri, out[1].front_tri);
  EXPECT_EQ(out[0].tet_column, out[1].tet_column);
  EXPECT_EQ(out[0].vertex_origin, out[1].vertex_origin);
  // Without the tasks: a valid result too, with every push made one by one.
  options.push_tasks_min_vertices = 0;
  Result<LayersOutput> serial = build_layers(s, sizing, options);
  ASSERT_TRUE(serial.ok()) << serial.status().message();
  expect_valid_layers(s, serial.value(), 2);
  EXPECT_EQ(serial->stats.task_pushes, 0u);
}

// The tasks on every small shape (thin slab, nested shells: sides with little room, vertices near
// the cut), forced on by a threshold of one vertex.
TEST(Layers, PushTasksOnSmallShapesAreValid) {
  for (const ShapeCase& shape : kShapes)
    for (int layers = 1; layers <= 3; ++layers) {
      SCOPED_TRACE(std::string(shape.name) + ", " + std::to_string(layers) + " layers");
      const SurfaceMesh s = shape.make();
      IsotropicSurfaceSizing sizing(s);
      LayersOptions options;
      options.layers = layers;
      options.push_tasks_min_vertices = 1;
      Result<LayersOutput> out = build_layers(s, sizing, options);
      ASSERT_TRUE(out.ok()) << out.status().message();
      expect_valid_layers(s, out.value(), layers);
      if (s.num_vertices() >= 100) {
        EXPECT_GT(out->stats.task_pushes, 0u);
      }
    }
}

TEST(Layers, CheckerCatchesBrokenOutputs) {
  const SurfaceMesh s = test::grid_cube(3);
  const LayersOutput good = run_layers(s, 1);
  ASSERT_TRUE(check_layers(s, good).ok());
  {
    LayersOutput bad = good;
    std::swap(bad.mesh.tet_v[0], bad.mesh.tet_v[1]);  // an inverted tet
    EXPECT_FALSE(check_layers(s, bad).ok());
  }
  {
    LayersOutput bad = good;
    std::swap(bad.front_tri[0], bad.front_tri[1]);  // an S1 triangle flipped
    const LayersCheck c = check_layers(s, bad);
    EXPECT_FALSE(c.front_manifold && c.boundary_is_s_and_s1);
  }
  {
    LayersOutput bad = good;
    bad.mesh.xyz[3 * (bad.mesh.num_vertices() - 1)] += 10.0;  // a vertex thrown far away
    EXPECT_FALSE(check_layers(s, bad).ok());
  }
}

TEST(Layers, ReportsHalvingsAndProvenance) {
  // tray_bottom.stl has sliver triangles: pushes get halved there.
  const SurfaceMesh s = shared_surface("tray_bottom.stl");
  const LayersOutput out = run_layers(s, 1);
  expect_valid_layers(s, out, 1);
  const LayersStats& st = out.stats;
  EXPECT_EQ(st.halving_loops, st.face_halvings + st.push_halvings);
  EXPECT_GT(st.halving_loops, 0u);
  EXPECT_GT(st.halved_columns, 0u);
  EXPECT_LE(st.halved_columns, s.num_triangles());
  EXPECT_EQ(st.halved_columns, st.per_layer[0].halved_columns);
  EXPECT_EQ(st.per_layer[0].halvings, st.halving_loops);
  EXPECT_NEAR(st.halved_column_share, double(st.halved_columns) / double(s.num_triangles()), 1e-12);
  // Every tet stands on its column: one of its vertices is a corner of that input triangle or
  // was pushed from one.
  const TetMesh& m = out.mesh;
  ASSERT_EQ(out.tet_layer.size(), m.num_tet_slots());
  ASSERT_EQ(out.tet_column.size(), m.num_tet_slots());
  ASSERT_EQ(out.vertex_origin.size(), m.num_vertices());
  auto root = [&](uint32_t v) {
    while (v >= s.num_vertices() && out.vertex_origin[v] != TetMesh::kNone) v = out.vertex_origin[v];
    return v;
  };
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
    EXPECT_EQ(out.tet_layer[t], 1);
    const uint32_t c = out.tet_column[t];
    ASSERT_LT(c, s.num_triangles());
    bool stands = false;
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) stands = stands || root(m.vertex(t, i)) == s.tri[3 * c + k];
    EXPECT_TRUE(stands) << "tet " << t << " column " << c;
  }
}

TEST(Layers, WorstTetsStandOnPoorInputTriangles) {
  // On a surface with sliver triangles the worst T1 tets come from them, not from the
  // construction: the 10 worst stand on input triangles among the poorest fifth.
  for (const char* name : {"tray_bottom.stl", "turbine.off"}) {
    SCOPED_TRACE(name);
    const SurfaceMesh s = shared_surface(name);
    const LayersOutput out = run_layers(s, 1);
    const WorstTets w = worst_tets(s, out, 10);
    ASSERT_EQ(w.tets.size(), 10u);
    EXPECT_LT(w.input_quality_min, 0.01);
    EXPECT_LT(w.median_rank, 0.2);
    for (size_t i = 1; i < w.tets.size(); ++i)
      EXPECT_LE(w.tets[i - 1].radius_ratio, w.tets[i].radius_ratio);
    std::printf("[%s] worst T1 radius ratio %.2e; the 10 worst on input triangles of median "
                "quality rank %.1f%% (input quality min %.2e, median %.2f)\n",
                name, w.tets[0].radius_ratio, 100.0 * w.median_rank, w.input_quality_min,
                w.input_quality_median);
  }
}

TEST(Layers, IsotropicQualityOnGoodSurfaces) {
  // Input triangles of good shape: one layer. (Measured: see the issue 5 report; the minimum
  // on airplane.obj is set by its trailing-edge wedges, where no prism can be good.)
  const struct {
    const char* name;
    double min, mean;
  } cases[] = {{"elephant.obj", 0.2, 0.6}, {"fandisk.off", 0.1, 0.6}, {"airplane.obj", 0.015, 0.65}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const SurfaceMesh s = shared_surface(c.name);
    const LayersOutput out = run_layers(s, 1);
    expect_valid_layers(s, out, 1);
    const LayersQuality q = layers_quality(out);
    EXPECT_GT(q.min, c.min);
    EXPECT_GT(q.mean, c.mean);
    std::printf("[%s] 1 layer: radius ratio min %.4f mean %.4f, %zu below 0.05\n", c.name, q.min,
                q.mean, q.below_0_05);
  }
}

TEST(Layers, IsotropicQualityWithTwoLayers) {
  // Issue 5's figures (mean >= 0.5, none below 0.05): with two layers the first layer's
  // vertices are inside T1, and the interior smoothing lifts the worst tets around them.
  const struct {
    const char* name;
    double min_without_smoothing;  // measured before it: the smoothing is what meets the target
  } cases[] = {{"fandisk.off", 0.06}, {"airplane.obj", 0.05}, {"elephant.obj", 1.0}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const SurfaceMesh s = shared_surface(c.name);
    IsotropicSurfaceSizing sizing(s);
    LayersOptions options;
    options.layers = 2;
    Result<LayersOutput> out = build_layers(s, sizing, options);
    ASSERT_TRUE(out.ok()) << out.status().message();
    expect_valid_layers(s, out.value(), 2);
    const LayersQuality q = layers_quality(out.value());
    EXPECT_GE(q.min, 0.05);
    EXPECT_GE(q.mean, 0.5);
    EXPECT_GT(out.value().stats.smoothed_vertices, 0u);
    options.interior_smoothing_passes = 0;
    Result<LayersOutput> plain = build_layers(s, sizing, options);
    ASSERT_TRUE(plain.ok()) << plain.status().message();
    const LayersQuality p = layers_quality(plain.value());
    EXPECT_LT(p.min, c.min_without_smoothing);
    EXPECT_GT(q.min, p.min);
    std::printf("[%s] 2 layers: radius ratio min %.4f mean %.4f (without the interior smoothing: %.4f, %.4f)\n",
                c.name, q.min, q.mean, p.min, p.mean);
  }
}

TEST(Layers, RejectsBadInputAndOptions) {
  IsotropicSurfaceSizing sizing(test::grid_cube(2));
  SurfaceMesh cube = test::grid_cube(2);
  LayersOptions options;
  options.layers = 0;
  EXPECT_EQ(build_layers(cube, sizing, options).status().code(), Error::InvalidArgument);
  options = LayersOptions();
  options.shrink = 1.0;
  EXPECT_EQ(build_layers(cube, sizing, options).status().code(), Error::InvalidArgument);

  EXPECT_EQ(build_layers(SurfaceMesh(), sizing).status().code(), Error::EmptyInput);

  SurfaceMesh open = cube;
  open.tri.resize(open.tri.size() - 3);
  open.patch.pop_back();
  const Result<LayersOutput> r = build_layers(open, sizing);
  EXPECT_EQ(r.status().code(), Error::InvalidArgument);
  EXPECT_NE(r.status().message().find("not closed"), std::string::npos) << r.status().message();

  SurfaceMesh flipped = cube;
  std::swap(flipped.tri[0], flipped.tri[1]);
  EXPECT_EQ(build_layers(flipped, sizing).status().code(), Error::InvalidArgument);

  SurfaceMesh bad_index = cube;
  bad_index.tri[4] = 1000;
  EXPECT_EQ(build_layers(bad_index, sizing).status().code(), Error::BadIndex);
}

}  // namespace
}  // namespace anitet
