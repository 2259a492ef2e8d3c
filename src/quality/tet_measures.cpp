#include "quality/tet_measures.hpp"

#include <algorithm>
#include <cmath>

namespace anitet {

namespace {

struct V3 {
  double x, y, z;
};
inline V3 sub(const double* p, const double* q) { return {p[0] - q[0], p[1] - q[1], p[2] - q[2]}; }
inline V3 cross(const V3& u, const V3& v) {
  return {u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
}
inline double dot(const V3& u, const V3& v) { return u.x * v.x + u.y * v.y + u.z * v.z; }
inline double norm(const V3& u) { return std::sqrt(dot(u, u)); }

constexpr double kRadToDeg = 57.295779513082320876798154814105;

// 16 * (area of a triangle with sides x, y, z)^2, with x >= y >= z, in Kahan's cancellation-free
// arrangement of Heron's formula. For a tet, with x, y, z the products of opposite edge lengths,
// this is (24 V R)^2 (the circumradius identity), and the arrangement keeps slivers accurate.
inline double heron16(double x, double y, double z) {
  if (x < y) std::swap(x, y);
  if (y < z) std::swap(y, z);
  if (x < y) std::swap(x, y);
  const double s = (x + (y + z)) * (z - (x - y)) * (z + (x - y)) * (x + (y - z));
  return s > 0.0 ? s : 0.0;
}

}  // namespace

double tet_signed_volume(const double* a, const double* b, const double* c, const double* d) {
  return dot(cross(sub(b, a), sub(c, a)), sub(d, a)) / 6.0;
}

namespace {

// The measures, with the largest dihedral as the key of max_dihedral_key (its angle only when
// `angle` is set: an atan2 per tet the report does without).
TetMeasures measure(const double* a, const double* b, const double* c, const double* d, bool angle,
                    double& max_key) {
  TetMeasures m;
  const V3 ab = sub(b, a), ac = sub(c, a), ad = sub(d, a);
  const V3 bc = sub(c, b), bd = sub(d, b), cd = sub(d, c);
  // Face normals in the local numbering of tet_mesh.hpp (facet i opposite vertex i, wound so
  // that the normal points into a positive tet): all inward, or all outward for an inverted tet;
  // either way the angle between two of them is 180 degrees minus the dihedral.
  const V3 n[4] = {cross(bd, bc),   // facet 0: (b d c)
                   cross(ac, ad),   // facet 1: (a c d)
                   cross(ad, ab),   // facet 2: (a d b)
                   cross(ab, ac)};  // facet 3: (a b c)
  m.volume = dot(n[3], ad) / 6.0;
  const double av = std::fabs(m.volume);

  const double l2[6] = {dot(ab, ab), dot(ac, ac), dot(ad, ad), dot(bc, bc), dot(bd, bd), dot(cd, cd)};
  const double l2sum = l2[0] + l2[1] + l2[2] + l2[3] + l2[4] + l2[5];
  if (l2sum > 0.0) {
    const double c3 = std::cbrt(3.0 * av);
    m.mean_ratio = 12.0 * c3 * c3 / l2sum;
  }
  double len[6];
  for (int k = 0; k < 6; ++k) len[k] = std::sqrt(l2[k]);

  if (av > 0.0) {
    const double area2 = norm(n[0]) + norm(n[1]) + norm(n[2]) + norm(n[3]);  // twice the total area
    const double r_in = 3.0 * av / (0.5 * area2);
    const double s = heron16(len[0] * len[5], len[1] * len[4], len[2] * len[3]);
    if (s > 0.0) {
      const double circum = std::sqrt(s) / (24.0 * av);
      // The circumsphere holds every edge (R >= l_max / 2), so 3 r / R <= 6 r / l_max <= 1. For
      // a nearly flat tet, V and s are both rounding noise and their ratio may break the bound
      // (values above 1 were seen); r alone is as accurate as V.
      const double l_max = std::max({len[0], len[1], len[2], len[3], len[4], len[5]});
      m.radius_ratio = std::min({3.0 * r_in / circum, 6.0 * r_in / l_max, 1.0});
    }
  }

  // Each dihedral is the angle of the vector (cos, sin) = (-n_k.n_j, |n_k x n_j|) in the upper
  // half plane, where |n_k x n_j| = 6 |V| |e| for the edge e the two facets share (the volume
  // as the facets' areas, the angle between them and that edge give it). Angles compare by the
  // sign of a 2D cross product (opposite vectors, 0 against 180 degrees, by their cosines), so
  // only the smallest and the largest need atan2, which unlike acos is accurate near 0 and 180.
  static constexpr int kSharedEdge[4][4] = {{-1, 5, 4, 3}, {5, -1, 2, 1}, {4, 2, -1, 0}, {3, 1, 0, -1}};
  auto smaller = [](double c1, double s1, double c2, double s2) {
    const double turn = c1 * s2 - s1 * c2;
    return turn > 0.0 || (turn == 0.0 && c1 * c2 + s1 * s2 < 0.0 && c1 > c2);
  };
  const double v6 = 6.0 * av;
  double lo_c = 0.0, lo_s = 0.0, hi_c = 0.0, hi_s = 0.0;
  bool first = true;
  for (int k = 0; k < 4; ++k) {
    for (int j = k + 1; j < 4; ++j) {
      const double cs = -dot(n[k], n[j]), sn = v6 * len[kSharedEdge[k][j]];
      if (first || smaller(cs, sn, lo_c, lo_s)) {
        lo_c = cs;
        lo_s = sn;
      }
      if (first || smaller(hi_c, hi_s, cs, sn)) {
        hi_c = cs;
        hi_s = sn;
      }
      first = false;
    }
  }
  m.min_dihedral_deg = std::atan2(lo_s, lo_c) * kRadToDeg;
  if (angle) {
    m.max_dihedral_deg = std::atan2(hi_s, hi_c) * kRadToDeg;
  } else {
    // The direction's position on the path (1, 0) -> (0, 1) -> (-1, 0): 0 to 2 as the angle
    // goes from 0 to 180 degrees.
    const double t = std::fabs(hi_c) + hi_s;
    max_key = t > 0.0 ? (hi_c >= 0.0 ? hi_s / t : 2.0 - hi_s / t) : 0.0;
  }
  return m;
}

}  // namespace

TetMeasures tet_measures(const double* a, const double* b, const double* c, const double* d) {
  double unused = 0.0;
  return measure(a, b, c, d, true, unused);
}

TetMeasures tet_measures_keyed(const double* a, const double* b, const double* c, const double* d,
                               double& max_dihedral_key) {
  return measure(a, b, c, d, false, max_dihedral_key);
}

double max_dihedral_from_key(double key) {
  return std::atan2(key <= 1.0 ? key : 2.0 - key, 1.0 - key) * kRadToDeg;
}

}  // namespace anitet
