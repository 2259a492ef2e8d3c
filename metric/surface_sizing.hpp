// The paper's default sizing grid (section 5.3): voxels the input surface passes through take the
// local triangle size and stay pinned; every other voxel starts at the mean of the pinned values
// and is smoothed (Laplacian or Gaussian), the pinned voxels being reset after each pass, until the
// largest change of a free voxel falls below tolerance * mean.
//
// Which voxels the surface passes through (Pinning): by default those whose centre lies within
// half a voxel of the surface. That band has the same width whatever the surface's orientation,
// so a rotated surface pins as many voxels per unit area; the paper's literal test (the surface
// cuts the voxel's cube) pins up to sqrt(3) times more where faces lie oblique to the lattice's
// axes, and a rotated CAD part then got noticeably fewer tets. The band still stops
// the outside flood fill: a lattice step of length h that crosses the surface has an end within
// h/2 of it. A surface whose band holds no node at all (tiny against a voxel that max_voxels
// grew) is pinned by the cube test instead; a small separate shell whose band holds no node
// while others' do is not pinned (the grid around it takes its neighbours' sizes).
//
// The smoothing runs on a dense lattice whose node count is bounded by max_voxels (the voxel size
// grows until it fits). Voxels outside the surface are dropped (drop_outside), and
// MetricField::from_lattice stores the rest sparsely in OpenVDB, leaves where the size hardly
// varies collapsing into tiles.
#pragma once

#include <cstddef>

#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "lattice.hpp"
#include "metric_field.hpp"

namespace anitet {
namespace metric {

enum class TriangleSize { Shortest, Mean };  // the edge length a pinned voxel takes
enum class Smoothing { Laplacian, Gaussian };
// A voxel is pinned when its centre lies within half a voxel of a triangle (HalfVoxelBand), or
// when a triangle cuts its cube (CutCube, the paper's wording; depends on the orientation).
enum class Pinning { HalfVoxelBand, CutCube };

struct SurfaceSizingOptions {
  TriangleSize triangle_size = TriangleSize::Shortest;
  Pinning pinning = Pinning::HalfVoxelBand;
  Smoothing smoothing = Smoothing::Laplacian;
  // 0: the surface's mean edge length, at most twice its median one (grown to fit max_voxels)
  double voxel_size = 0.0;
  int padding = 2;          // voxels added around the surface's bounding box on each side
  double tolerance = 1e-3;  // stop when max |change| < tolerance * mean pinned size
  int max_iterations = 20000;
  // Laplacian passes are Gauss-Seidel with this over-relaxation factor (1 = plain averaging).
  double relaxation = 1.8;
  size_t max_voxels = size_t(1) << 22;  // ~4M nodes: 9 bytes each while smoothing
  // Storing in OpenVDB: a leaf (8^3 voxels) whose sizes vary by less than this fraction of their
  // mean becomes one tile.
  double prune_tolerance = 1e-2;
  // Drop the voxels outside the surface (a 6-connected flood fill from the lattice's faces that
  // pinned voxels stop), except a one-voxel shell around the pinned ones, so that interpolation inside
  // the domain never reads a dropped voxel. Dropped voxels are neither smoothed nor stored; a
  // query far outside reads the largest size. Off: the whole box is smoothed and stored.
  bool drop_outside = true;
};

struct SurfaceSizingStats {
  int iterations = 0;
  bool converged = false;
  double last_change = 0.0;  // max |change| of the last pass, relative to the mean
  size_t voxels = 0;
  size_t pinned = 0;
  size_t dropped = 0;  // outside voxels left out (drop_outside)
  bool cube_fallback = false;  // the half-voxel band held no node: pinned by the cube test
  double voxel_size = 0.0;
  double mean_size = 0.0;
  size_t working_bytes = 0;  // dense working memory (values + pinned flags)
};

// A size lattice (components == 1) for the surface. Error::EmptyInput without triangles,
// Error::InvalidArgument for non-finite coordinates or bad options.
Result<Lattice> surface_sizing(const SurfaceMesh& surface, const SurfaceSizingOptions& options = {},
                               SurfaceSizingStats* stats = nullptr);

// The default sizing field: surface_sizing stored sparsely (prune_tolerance) in a MetricField.
Result<MetricField> surface_sizing_field(const SurfaceMesh& surface,
                                         const SurfaceSizingOptions& options = {},
                                         SurfaceSizingStats* stats = nullptr);

// Which nodes' voxels (axis-aligned cubes of side `spacing` centred on the nodes) intersect the
// triangle abc. Exact separating-axis test in floating point (Akenine-Möller's 13 axes), with the
// box grown by a relative 1e-9 so that touching counts as cutting.
bool triangle_cuts_box(const double a[3], const double b[3], const double c[3],
                       const double centre[3], double half);

}  // namespace metric
}  // namespace anitet
