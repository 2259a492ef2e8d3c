#include "validate/shells.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "predicates/predicates.hpp"

namespace anitet::shells {

namespace {

// Sign of orient2d(a, b, p + (eps, eps^2)) for 2D points (first coordinates of the pointers).
int perturbed_orient2d(const double* a, const double* b, const double* p) {
  const int o = predicates::orient2d(a, b, p);
  if (o != 0) return o;
  // d/d(p0) = a1 - b1, d/d(p1) = b0 - a0.
  if (a[1] != b[1]) return a[1] > b[1] ? 1 : -1;
  if (a[0] != b[0]) return b[0] > a[0] ? 1 : -1;
  return 0;
}

}  // namespace

bool ray_crosses(const double* p, const double* a, const double* b, const double* c) {
  // In the (y, z) projection: is the perturbed p strictly inside the projected triangle?
  const int s1 = perturbed_orient2d(a + 1, b + 1, p + 1);
  const int s2 = perturbed_orient2d(b + 1, c + 1, p + 1);
  const int s3 = perturbed_orient2d(c + 1, a + 1, p + 1);
  if (s1 == 0 || s1 != s2 || s1 != s3) return false;
  // Then the projected triangle has orientation s1 = sign(n_x), n the normal (b-a)x(c-a), and
  // the line meets the plane at x_hit with (x_hit - p_x) * n_x = -orient3d(a, b, c, p).
  int o = predicates::orient3d(a, b, c, p);
  if (o == 0) o = s1;  // p on the plane: the delta shift along +x decides
  return o != s1;
}

int volume_sign(const SurfaceMesh& s, const std::vector<uint32_t>& tris, double* volume) {
  if (tris.empty()) {
    *volume = 0.0;
    return 0;
  }
  const double* o = s.point(s.tri[3 * size_t(tris[0])]);
  double sum = 0.0, permanent = 0.0;
  for (uint32_t t : tris) {
    const double* a = s.point(s.tri[3 * size_t(t)]);
    const double* b = s.point(s.tri[3 * size_t(t) + 1]);
    const double* c = s.point(s.tri[3 * size_t(t) + 2]);
    const double ax = a[0] - o[0], ay = a[1] - o[1], az = a[2] - o[2];
    const double bx = b[0] - o[0], by = b[1] - o[1], bz = b[2] - o[2];
    const double cx = c[0] - o[0], cy = c[1] - o[1], cz = c[2] - o[2];
    sum += ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx);
    permanent += std::fabs(ax) * (std::fabs(by * cz) + std::fabs(bz * cy)) +
                 std::fabs(ay) * (std::fabs(bz * cx) + std::fabs(bx * cz)) +
                 std::fabs(az) * (std::fabs(bx * cy) + std::fabs(by * cx));
  }
  *volume = sum / 6.0;
  // Each term is off by at most ~7u of its permanent, the sum by n*u more (u = 2^-53);
  // the bound below is generous.
  const double u = std::numeric_limits<double>::epsilon();
  const double bound = (double(tris.size()) + 16.0) * u * permanent * 1.5;
  if (sum > bound) return 1;
  if (sum < -bound) return -1;
  mpq_class exact(0);
  const mpq_class ox(o[0]), oy(o[1]), oz(o[2]);
  for (uint32_t t : tris) {
    mpq_class d[3][3];
    for (int k = 0; k < 3; ++k) {
      const double* p = s.point(s.tri[3 * size_t(t) + k]);
      d[k][0] = mpq_class(p[0]) - ox;
      d[k][1] = mpq_class(p[1]) - oy;
      d[k][2] = mpq_class(p[2]) - oz;
    }
    exact += d[0][0] * (d[1][1] * d[2][2] - d[1][2] * d[2][1]) +
             d[0][1] * (d[1][2] * d[2][0] - d[1][0] * d[2][2]) +
             d[0][2] * (d[1][0] * d[2][1] - d[1][1] * d[2][0]);
  }
  return sgn(exact);
}

Nesting nest_shells(const SurfaceMesh& s, const TriangleBVH& bvh, const topology::Topology& topo,
                    const std::vector<std::vector<uint32_t>>& shell_tris) {
  const size_t num_shells = shell_tris.size();
  Nesting nest;
  nest.parent.assign(num_shells, -1);
  nest.depth.assign(num_shells, 0);
  nest.region.assign(num_shells, -1);

  // Which shell uses each vertex (-2: several).
  std::vector<int32_t> vertex_shell(s.num_vertices(), -1);
  for (size_t t = 0; t < s.num_triangles(); ++t) {
    const int32_t sh = topo.shell_of[t];
    if (sh < 0) continue;
    for (int c = 0; c < 3; ++c) {
      int32_t& vs = vertex_shell[s.tri[3 * t + c]];
      vs = (vs == -1 || vs == sh) ? sh : -2;
    }
  }

  // containers[b]: the closed shells that contain shell b.
  std::vector<std::vector<int32_t>> containers(num_shells);
  std::vector<int32_t> crossed;  // shell of each crossed triangle
  for (size_t b = 0; b < num_shells; ++b) {
    if (!topo.shell_closed[b]) continue;
    const double* p = nullptr;
    for (uint32_t t : shell_tris[b]) {
      for (int c = 0; c < 3 && !p; ++c) {
        const uint32_t v = s.tri[3 * size_t(t) + c];
        if (vertex_shell[v] == int32_t(b)) p = s.point(v);
      }
      if (p) break;
    }
    if (!p) p = s.point(s.tri[3 * size_t(shell_tris[b][0])]);
    crossed.clear();
    const double inf = std::numeric_limits<double>::infinity();
    const Box3 ray{{p[0], p[1], p[2]}, {inf, p[1], p[2]}};
    bvh.query(ray, [&](size_t t) {
      const int32_t sh = topo.shell_of[t];
      if (sh < 0 || sh == int32_t(b) || !topo.shell_closed[sh]) return true;
      if (ray_crosses(p, s.point(s.tri[3 * t]), s.point(s.tri[3 * t + 1]),
                      s.point(s.tri[3 * t + 2]))) {
        crossed.push_back(sh);
      }
      return true;
    });
    std::sort(crossed.begin(), crossed.end());
    for (size_t i = 0; i < crossed.size();) {
      size_t j = i;
      while (j < crossed.size() && crossed[j] == crossed[i]) ++j;
      if ((j - i) % 2 == 1) containers[b].push_back(crossed[i]);
      i = j;
    }
    nest.depth[b] = int32_t(containers[b].size());
  }
  for (size_t b = 0; b < num_shells; ++b) {
    for (int32_t a : containers[b]) {
      if (nest.parent[b] < 0 || nest.depth[a] > nest.depth[nest.parent[b]]) nest.parent[b] = a;
    }
  }
  // Regions: one per body (closed shell at even depth); a cavity belongs to its parent's body.
  std::vector<size_t> order;
  for (size_t b = 0; b < num_shells; ++b) {
    if (topo.shell_closed[b]) order.push_back(b);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t x, size_t y) { return nest.depth[x] < nest.depth[y]; });
  for (size_t b : order) {
    if (nest.depth[b] % 2 == 0 || nest.parent[b] < 0) {
      nest.region[b] = nest.num_regions++;
    } else {
      nest.region[b] = nest.region[nest.parent[b]];
    }
  }
  return nest;
}

}  // namespace anitet::shells
