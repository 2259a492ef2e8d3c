// An independent audit of stage 1's output, for tests and `anitet mesh --stop-after layers`: everything
// layers.hpp promises, checked from the output alone (exact predicates where it matters).
#pragma once

#include <cstddef>
#include <string>

#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "layers/layers.hpp"

namespace anitet {

struct LayersCheck {
  bool mesh_valid = false;          // check_mesh: adjacency, exact positive orientation
  bool input_vertices_kept = false; // T1 starts with S's vertices, same coordinates and flags
  bool input_faces_present = false; // every S triangle is a T1 facet, the tet on the inner side
  bool boundary_is_s_and_s1 = false;// T1's unmatched facets are exactly S and S1
  bool front_manifold = false;      // S1 closed, oriented (each directed edge once), vertex-manifold
  bool front_off_input = false;     // S1 uses no vertex of S
  bool front_disjoint = false;      // no S1 triangle meets an S triangle (exact)
  bool front_tets_match = false;    // front_tet / front_facet name S1's triangles
  double volume_t1 = 0.0, volume_s = 0.0, volume_s1 = 0.0;
  double volume_rel_error = 0.0;    // |vol(T1) - (vol(S) - vol(S1))| / vol(S)
  std::string problems;             // the first problems found, for messages

  bool ok(double volume_tolerance = 1e-12) const {
    return mesh_valid && input_vertices_kept && input_faces_present && boundary_is_s_and_s1 &&
           front_manifold && front_off_input && front_disjoint && front_tets_match &&
           volume_rel_error <= volume_tolerance;
  }
};

LayersCheck check_layers(const SurfaceMesh& surface, const LayersOutput& out);

// Radius ratio (3 r / R, Euclidean) over T1's tets.
struct LayersQuality {
  double mean = 0.0, min = 0.0;
  size_t below_0_05 = 0, below_0_1 = 0, above_0_4 = 0, tets = 0;
};
LayersQuality layers_quality(const LayersOutput& out);

// The worst T1 tets and the input triangles they stand on (LayersOutput::tet_column): does a poor
// tet come from a poor input triangle (sliver triangles) or from the construction?
struct WorstTet {
  uint32_t tet = 0;
  double radius_ratio = 0.0;
  int layer = 0;
  uint32_t column = 0;               // input triangle below the tet
  double column_quality = 0.0;       // its shape quality (1 equilateral, 0 flat)
  double column_rank = 0.0;          // share of input triangles of lower quality (0: the worst)
};
struct WorstTets {
  std::vector<WorstTet> tets;        // the k worst, worst first
  double input_quality_min = 0.0, input_quality_median = 0.0;
  double median_rank = 0.0;          // median column_rank over the k worst tets
};
// Triangle shape quality: 4 sqrt(3) area / (sum of squared edge lengths).
double triangle_quality(const double* a, const double* b, const double* c);
WorstTets worst_tets(const SurfaceMesh& surface, const LayersOutput& out, size_t k);

}  // namespace anitet
