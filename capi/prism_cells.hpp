// Boundary-layer prism cells of a mesh handle (options->bl_cells ANITET_BL_CELLS_PRISMS).
#pragma once

#include "core/status.hpp"
#include "core/volume_mesh.hpp"
#include "handles.hpp"

namespace anitet::capi {

// Merges the BL tets of mesh.mesh (made by anitet_mesher_run: mesh.run holds the layers'
// vertex origins) into mesh.prism, prism_region and tet_prism; mesh.mesh keeps its tets.
Status make_prism_cells(anitet_mesh& mesh);

// The mesh as anitet_mesh_write writes it: the prisms in place of their tets.
VolumeMesh written_cells(const anitet_mesh& mesh);

}  // namespace anitet::capi
