// The faces of a tetrahedral mesh matched by their three vertices: which are boundary faces (one
// tet), which are shared by more than two tets, and, when boundary triangles are given, whether
// each is a face of the tets and whether together they cover the boundary once. The quality
// report measures meshes with it; every volume writer checks its boundary elements with it
// before writing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace anitet {

struct FaceCensus {
  // Faces of exactly one tet, as sorted vertex triples (3 values per face), ordered by smallest
  // vertex, then by the first tet that has them: the same list on any number of threads.
  std::vector<uint32_t> boundary;
  size_t shared_by_more_than_two = 0;  // faces of three or more tets
  // Only with boundary triangles (the `tri` of census_faces):
  std::vector<uint8_t> tets_of_triangle;  // per triangle: tets that have it as a face (capped at 255)
  std::vector<uint32_t> repeated;         // triangles whose face an earlier triangle already gave
  std::vector<uint32_t> uncovered;        // boundary faces (sorted triples) no triangle gives
};

// `tet`: 4 vertex ids per tet, each < num_vertices; `tri`: 3 per triangle (may be null with
// num_triangles 0: then only `boundary` and `shared_by_more_than_two` are filled). A counting
// sort of the faces by their smallest vertex, then each vertex's few faces (about 23 on a mesh of
// the usual shape) matched in a small open-addressing table; on every core when `parallel`.
FaceCensus census_faces(const uint32_t* tet, size_t num_tets, size_t num_vertices, bool parallel,
                        const uint32_t* tri = nullptr, size_t num_triangles = 0);

}  // namespace anitet
