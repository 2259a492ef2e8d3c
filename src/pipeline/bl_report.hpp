// The boundary layer's columns measured on a mesh: what the run built against what was asked.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/surface_mesh.hpp"
#include "core/tet_mesh.hpp"
#include "layers/layers.hpp"

namespace anitet {

// Boundary-layer figures (MesherOptions::layers.boundary_layer), measured on the final mesh, or on
// T1 when stage 1 runs alone. A column is a wall vertex followed up the BL layers (each pushed
// vertex to the one pushed from it); the height of layer i is the length of its step (after
// refinement and optimization, on the final mesh), against the requested h0 r^i.
struct BoundaryLayerReport {
  int layers = 0;              // BL layers built (n)
  size_t wall_vertices = 0;    // input vertices on the wall patches
  size_t tets = 0;             // BL tets in the output (regions bodies .. 2 bodies - 1)
  size_t vertices = 0;         // BL vertices (wall vertices included), frozen for stages 3b/3c
  size_t full_columns = 0;     // wall vertices whose column reaches all n layers
  std::vector<size_t> columns_reaching;  // [i]: wall vertices whose column reaches i layers (0..n)
  size_t nominal_columns = 0;  // full columns with every height within 10% of h0 r^i
  size_t reduced_vertices = 0; // wall vertices with a reduced layer (stage 1's count)
  double first_height_min = 0.0, first_height_mean = 0.0, first_height_max = 0.0;  // full columns
  double max_height_error = 0.0;  // max |h / (h0 r^i) - 1| over the nominal columns
  double growth_mean = 0.0;       // mean of (h_(n-1) / h_0)^(1 / (n-1)) over full columns
  double max_displacement = 0.0;  // largest move of a BL vertex after stage 1 (0: kept)
  // Per layer i (0..n-1), over the columns that reach it: the heights' min, mean and max.
  std::vector<double> layer_height_min, layer_height_mean, layer_height_max;
  double max_neighbour_growth = 0.0;  // max h_(i+1) / h_i within a column (1/that if larger)
  // OpenFOAM checkMesh's measures of the dual mesh on the faces two tets share, one of them a BL
  // tet (cell centres: the tets' centroids): non-orthogonality, the angle between the face's
  // normal and the line joining the centres (degrees); skewness, the distance from the face's
  // centroid to where that line crosses the face's plane over the distance to the face's edge in
  // that direction (at least 0.2 of the centres' distance). checkMesh flags > 70 deg and > 4.
  size_t dual_faces = 0;
  double non_orthogonality_max = 0.0, non_orthogonality_mean = 0.0;
  double skewness_max = 0.0;
  size_t non_orthogonal_faces = 0;  // above 70 deg
  size_t skew_faces = 0;            // above 4
  // The transition to the interior, on the faces between a BL tet and a non-BL tet (the layers'
  // top, and the side of a column that stopped): each tet's height over the face (the distance
  // from its opposite vertex to the face's plane), the interior one's over the BL one's. 1 is a
  // seamless transition; the isotropic interior over thin layers gives the wall size over the top
  // layer's height. Also the interior tet's mean edge length over the BL tet's height.
  size_t transition_faces = 0;
  double transition_ratio_mean = 0.0, transition_ratio_median = 0.0, transition_ratio_p90 = 0.0;
  size_t transition_within_1_5 = 0;  // faces with the ratio in [1/1.5, 1.5]
  double transition_edge_ratio_mean = 0.0;
  // Per wall vertex, in the surface's order: its point (x y z), the layers its column reaches, its
  // first and total height (0 when it reaches none), and its normal share: the least cosine
  // between the column (wall vertex to top) and the fluid-side normals of its wall triangles (1
  // on a flat wall; about 0.71 along a right-angled edge or corner, where the layers are that
  // much thinner across each wall than along the column). For the columns at given places (a
  // trailing edge, a wing's tip or root): --bl-columns writes them.
  std::vector<double> column_xyz, column_first, column_total, column_normal_share;
  std::vector<int> column_layers;
};

// The BL columns of `surface`'s wall vertices measured on `mesh` (stage 1's T1, or the final
// mesh, whose vertex ids T1's are). vertex_origin and t1_xyz: stage 1's, for the T1 vertices;
// max_displacement is measured on the vertices flagged vflag::kBoundaryLayer (none in T1: 0).
// A column's step counts as a BL layer only up to a vertex of a BL tet (region >=
// first_bl_region): a vertex that stopped in the top BL layers is pushed by the ordinary layers
// after them, which are no BL layer.
void measure_boundary_layer(const SurfaceMesh& surface, const BoundaryLayerOptions& bl, int layers,
                            const std::vector<uint32_t>& vertex_origin, const std::vector<double>& t1_xyz,
                            const TetMesh& mesh, int32_t first_bl_region, BoundaryLayerReport& r);

// The dual-mesh figures above (dual_faces .. skew_faces) on the tets of regions >= first_bl_region
// (the final mesh's BL regions, or T1's BoundaryLayerOptions::region).
void measure_boundary_layer_cells(const TetMesh& mesh, int32_t first_bl_region, BoundaryLayerReport& r);

// The columns of `r` as CSV text (`anitet mesh --bl-columns`, anitet_mesh_write_bl_columns): a
// header line, then one line per wall vertex (a vertex of `surface`, the surface that was meshed,
// on a triangle whose patch is in `walls`), in the surface's order as measure_boundary_layer
// measured them: its point, the layers its column reaches, its first and total height, its
// normal share, and the labels of the patches it is on, ascending and space-separated (a wall's
// junction with a slide patch, a wing's root on the floor).
std::string bl_columns_csv(const BoundaryLayerReport& r, const SurfaceMesh& surface, const std::vector<int32_t>& walls);

}  // namespace anitet
