// anitet-mpi's .pvtu output: every rank writes its piece, rank 0 the index; nothing gathered.
#pragma once
#include <string>

#include "core/surface_mesh.hpp"
#include "distributed/rank_mesh.hpp"

namespace anitet::mpi {

// Collective. `output` ends in .pvtu; the pieces are OUTPUT_STEM_<rank>.vtu beside it. The
// boundary triangles are the surface's (its vertex v is the coarse mesh's vertex v, gid v), each
// written by the rank owning the tet it bounds. A failure on any rank fails all of them.
Status write_pieces(const distributed::RankMesh& rm, const SurfaceMesh& surface, const std::string& output,
                    distributed::Comm& comm);

}  // namespace anitet::mpi
