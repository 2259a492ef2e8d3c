// Small floating-point geometry for stage 1: normals, the push direction of a vertex, and tet
// quality measured in a metric. Only constructions live here; every decision about validity is
// taken by the exact tests in tet_fit.hpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace anitet::layers {

// Unit right-hand normal of the triangle abc (zero vector for a degenerate one); returns the
// triangle's doubled area.
double unit_normal(const double* a, const double* b, const double* c, double n[3]);

// The interior angle of the triangle at corner a.
double corner_angle(const double* a, const double* b, const double* c);

// A unit direction d that sees every triangle of a vertex's star from the region side:
// d . n_i > 0 for each unit normal n_i pointing INTO the region (3 per triangle in `normals`).
// Starts from the angle-weighted mean normal (`weights`, 1 per triangle) and, when that does not
// see every triangle with a margin, takes the direction that maximizes the smallest d . n_i
// (exact enumeration for small stars, an ascent for large ones). Returns that smallest d . n_i
// (<= 0: no direction sees the whole star).
double visible_direction(const std::vector<double>& normals, const std::vector<double>& weights,
                         double d[3], bool* improved);

// min_i d . n_i over the star's unit normals (3 per triangle).
double star_margin(const std::vector<double>& normals, const double d[3]);

// Distance t > 0 along the unit direction d from o to the triangle abc (Moller-Trumbore, in
// floating point: a heuristic for choosing heights, never for validity), or +infinity.
double ray_triangle(const double o[3], const double d[3], const double* a, const double* b,
                    const double* c);

// Cholesky factor of the metric m (xx xy yy xz yz zz): upper-triangular U with M = U^T U, so that
// |U x| is the metric length of x. Falls back to the identity for a non-SPD input.
void metric_factor(const double m[6], double u[9]);
void apply_factor(const double u[9], const double x[3], double y[3]);
// The inverse: y with U y = x (back substitution; U upper triangular with a positive diagonal).
void solve_factor(const double u[9], const double x[3], double y[3]);

// Radius ratio 3 r / R of the tet abcd (1 regular, 0 flat), in Euclidean space.
double radius_ratio(const double* a, const double* b, const double* c, const double* d);
// The same after mapping the points by the metric factor u (quality in that metric).
double radius_ratio_in(const double u[9], const double* a, const double* b, const double* c,
                       const double* d);

}  // namespace anitet::layers
