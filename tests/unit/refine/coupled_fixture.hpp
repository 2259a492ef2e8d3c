// Test fixture: the coupled mesh of stages 1-3a (layers, recovery of S1, coupling) for a surface,
// i.e. the input of refinement and optimization, plus checks shared by their tests.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <set>
#include <vector>

#include "core/sizing.hpp"
#include "core/surface_mesh.hpp"
#include "core/tet_mesh.hpp"
#include "couple/couple.hpp"
#include "layers/layers.hpp"
#include "recovery/recovery.hpp"

namespace anitet::test {

inline Result<CoupledMesh> coupled_mesh(const SurfaceMesh& surface, int layers = 1) {
  const IsotropicSurfaceSizing sizing(surface);
  LayersOptions lo;
  lo.layers = layers;
  Result<LayersOutput> t1 = build_layers(surface, sizing, lo);
  if (!t1.ok()) return t1.status();
  std::vector<uint32_t> map;
  const SurfaceMesh s1 = front_surface(t1.value(), &map);
  Result<RecoveryOutput> t2 = recover_boundary(s1);
  if (!t2.ok()) return t2.status();
  return couple_meshes(surface, std::move(t1).value(), map, t2.value());
}

// The protected facets of the live tets as sorted vertex triples.
inline std::multiset<std::array<uint32_t, 3>> protected_facets(const TetMesh& mesh) {
  std::multiset<std::array<uint32_t, 3>> out;
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t) {
    if (mesh.is_deleted(t)) continue;
    for (int i = 0; i < 4; ++i) {
      if (!mesh.facet_protected(t, i)) continue;
      std::array<uint32_t, 3> k = {mesh.vertex(t, kFacetVertex[i][0]), mesh.vertex(t, kFacetVertex[i][1]),
                                   mesh.vertex(t, kFacetVertex[i][2])};
      std::sort(k.begin(), k.end());
      out.insert(k);
    }
  }
  return out;
}

// Every input triangle is a protected facet, and there is no other.
inline void expect_surface_kept(const SurfaceMesh& surface, const TetMesh& mesh, const char* what) {
  std::multiset<std::array<uint32_t, 3>> want;
  for (size_t t = 0; t < surface.num_triangles(); ++t) {
    std::array<uint32_t, 3> k = {surface.tri[3 * t], surface.tri[3 * t + 1], surface.tri[3 * t + 2]};
    std::sort(k.begin(), k.end());
    want.insert(k);
  }
  EXPECT_TRUE(protected_facets(mesh) == want) << what << ": the protected facets are not S's triangles";
  for (size_t i = 0; i < surface.xyz.size(); ++i)
    ASSERT_EQ(mesh.xyz[i], surface.xyz[i]) << what << ": a vertex of S moved";
}

// Radius-ratio mean and min of the tets with no vertex on S (the ones optimization fully
// controls; the paper's Table 4 split).
struct InteriorQuality {
  size_t tets = 0;
  double mean = 0.0, min = 1.0;
};
inline InteriorQuality interior_quality(const TetMesh& mesh, double (*measure)(const TetMesh&, uint32_t)) {
  InteriorQuality q;
  double sum = 0.0;
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t) {
    if (mesh.is_deleted(t)) continue;
    bool touches = false;
    for (int i = 0; i < 4; ++i) touches |= (mesh.vflags[mesh.vertex(t, i)] & vflag::kOnInputSurface) != 0;
    if (touches) continue;
    const double r = measure(mesh, t);
    ++q.tets;
    sum += r;
    q.min = std::min(q.min, r);
  }
  q.mean = q.tets ? sum / double(q.tets) : 0.0;
  return q;
}

// A constant isotropic size.
class ConstantSizing final : public SizingField {
 public:
  explicit ConstantSizing(double h) : h_(h) {}
  void metric(const double[3], double m[6]) const override { isotropic_metric(h_, m); }

 private:
  double h_;
};

}  // namespace anitet::test
