// Local re-triangulations (flips) used by boundary recovery before it falls back to Steiner
// points: on CAD surfaces with sliver triangles most missing edges and faces are one flip away
// (the Delaunay triangulation chose the other diagonal of a nearly flat quad), and a flip adds no
// point, where conforming splits would need hundreds.
//
// Every flip is checked with the exact orient3d (all new tets positive) and refuses to remove a
// protected facet or a constrained edge, so the mesh stays valid; it is then in general no longer
// Delaunay, which the modified kernel (PointInserter) accepts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/tet_mesh.hpp"

namespace anitet {

class DegeneracyOracle;  // delaunay/delaunay.hpp: with one, no flip makes a tet it calls flat

// The tets around edge (p q), starting at tet t which has it: tets[i] holds p, q, link[i] and
// link[i+1 mod n], and orient3d(p, q, link[i], link[i+1]) > 0. False when a ghost tet, a protected
// facet or a facet without neighbour is met (a hull or boundary edge) or the ring is longer than
// max_size. (meshops::edge_ring, oriented.) The flips below replace tets with
// meshops::replace_tets, which keeps every constrained edge.
struct EdgeRing {
  uint32_t p = TetMesh::kNone, q = TetMesh::kNone;
  std::vector<uint32_t> link;
  std::vector<uint32_t> tets;
};
bool edge_ring(const TetMesh& mesh, uint32_t t, uint32_t p, uint32_t q, EdgeRing& ring,
               size_t max_size = 12);

// 2-3 flip across facet i of t: t and its neighbour become three tets around the edge joining
// their apexes. False when that edge does not cross the facet's interior, the facet is protected,
// or a tet is a ghost.
bool flip23(TetMesh& mesh, uint32_t t, int facet, std::vector<uint32_t>* created = nullptr,
            const DegeneracyOracle* oracle = nullptr);

// Edge removal: the ring's tets are replaced by a triangulation of the link polygon coned to p and
// to q (the 3-2 flip is the case of a link of 3). With want_n == 2 the triangulation must have the
// edge (want[0] want[1]) (both link vertices), with want_n == 3 the triangle want[0..2]; with
// want_n == 0 any valid one. False when edge pq is constrained, a facet around it is protected,
// or no triangulation gives positive tets.
bool remove_edge(TetMesh& mesh, const EdgeRing& ring, const uint32_t* want, int want_n,
                 std::vector<uint32_t>* created = nullptr, const DegeneracyOracle* oracle = nullptr);

// Makes (u w) an edge by one flip, when one does: a 2-3 flip of the facet opposite u in a tet
// whose neighbour there has apex w, or the removal of an edge of such a facet whose ring holds w.
// `ball` holds the tets around u. On success `created` lists the new tets.
bool flip_in_edge(TetMesh& mesh, uint32_t u, uint32_t w, const std::vector<uint32_t>& ball,
                  std::vector<uint32_t>& created, const DegeneracyOracle* oracle = nullptr);

// Makes triangle (a b c), whose edges are present, a facet by removing one edge whose ring holds
// all three (the 3-2 flip when the ring is just a b c). `ball` holds the tets around a.
bool flip_in_face(TetMesh& mesh, uint32_t a, uint32_t b, uint32_t c, const std::vector<uint32_t>& ball,
                  std::vector<uint32_t>& created, const DegeneracyOracle* oracle = nullptr);

}  // namespace anitet
