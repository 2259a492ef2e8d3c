// The 2D mesher: a PSLG in, a triangle mesh out, through the paper's stages in 2D (front layer,
// conforming recovery of the new front, coupling, metric refinement, CVT and flips).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/sizing.hpp"
#include "core/status.hpp"
#include "mesh2d/optimize2.hpp"
#include "mesh2d/pslg.hpp"
#include "mesh2d/refine2.hpp"
#include "mesh2d/sizing2.hpp"
#include "mesh2d/stages.hpp"

namespace anitet::mesh2d {

// A triangle mesh of the 2D mesher.
struct TriMesh2 {
  std::vector<double> xy;            // 2 per vertex; the input's points first, in order
  std::vector<uint32_t> tri;         // 3 per triangle, counter-clockwise
  std::vector<double> attribute;     // per triangle: its region's attribute (0 without)
  std::vector<uint32_t> edges;       // 2 per edge: the pieces of the input's segments
  std::vector<int32_t> edge_label;   // per edge: its segment's label
  std::vector<uint32_t> edge_segment;  // per edge: its segment (0-based)
  size_t input_points = 0;           // how many vertices are the input's
  std::vector<double> metric;        // per vertex: the sizing field's tensor xx xy yy (3 each)

  size_t num_vertices() const { return xy.size() / 2; }
  size_t num_triangles() const { return tri.size() / 3; }
};

struct Mesh2dOptions {
  int layers = 1;                 // stage 1 layers
  bool split_segments = false;    // allow points on the input's segments
  bool refine = true, optimize = true;
  int anisotropic_cycles = 2;     // more refine + optimize rounds on an anisotropic field
  SizingOptions2 sizing;          // the sizing field (sizing.metric: a user field, kept by the caller)
  OptimizeOptions2 optimize_options;
  // Progress: fraction in [0, 1] and stage name on entering each stage; false cancels.
  std::function<bool(double, const char*)> progress;
};

struct Mesh2dStats {
  StageStats stages;
  SizingStats2 sizing;
  RefineStats2 refine;
  OptimizeStats2 optimize;
  double in_range = 0;   // share of edges of metric length in [1/sqrt2, sqrt2]
  double seconds = 0;
  std::vector<std::pair<std::string, double>> stage_seconds;
  // The stage an error came from ("validate": the input is invalid; "sizing": the options).
  std::string failed_stage;
};

// Meshes the PSLG (already in a planar frame). Errors: the input's (naming elements, see
// check_pslg and analyse_domain), InvalidArgument for bad options, Cancelled, RecoveryFailed.
Result<TriMesh2> mesh_pslg(const Pslg& pslg, const Mesh2dOptions& options, Mesh2dStats* stats = nullptr);

}  // namespace anitet::mesh2d
