// Closed shells as solids: exact inside/outside tests, nesting, orientation.
#pragma once

#include <cstdint>
#include <vector>

#include "core/bvh.hpp"
#include "core/surface_mesh.hpp"
#include "validate/topology.hpp"

namespace anitet::shells {

// Does the ray from p towards +x cross triangle abc? Exact, with a symbolic perturbation of p
// (p + (delta, eps, eps^2), delta >> eps > 0 infinitesimal) so that a ray through an edge, a
// vertex or along a plane is decided consistently: across a closed surface, the number of
// crossings is odd exactly when p is inside (p itself must not lie on the surface).
bool ray_crosses(const double* p, const double* a, const double* b, const double* c);

// Exact sign of the signed volume of the triangles `tris` (a closed shell): positive when they
// face outward. *volume gets the floating-point value.
int volume_sign(const SurfaceMesh& s, const std::vector<uint32_t>& tris, double* volume);

struct Nesting {
  std::vector<int32_t> parent;  // per shell: innermost closed shell containing it, or -1
  std::vector<int32_t> depth;   // per shell: closed shells containing it (0 for open shells)
  std::vector<int32_t> region;  // per shell: region id (-1 for open shells)
  int32_t num_regions = 0;
};

// Nesting of the closed shells. Each closed shell is tested with one of its vertices that no
// other shell uses; the result is meaningless for shells that intersect each other.
Nesting nest_shells(const SurfaceMesh& s, const TriangleBVH& bvh, const topology::Topology& topo,
                    const std::vector<std::vector<uint32_t>>& shell_tris);

}  // namespace anitet::shells
