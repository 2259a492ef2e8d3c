/* The example surface of examples/c, shared with the C ABI tests: a sphere of radius 1 made of
 * SPHERE_NLAT-1 rings of SPHERE_NLON points and the two poles, 0-based, counter-clockwise seen from outside,
 * patches 1 (south cap), 2 (bands), 3 (north cap). Points come from a diamond (|r| + |z| = 1,
 * |x| + |y| = 1) pushed onto the sphere with sqrt and divisions only, so that C, Fortran and
 * Python compute the same doubles bit for bit (examples/fortran and examples/python repeat it). */
#ifndef ANITET_EXAMPLE_SPHERE_SURFACE_H
#define ANITET_EXAMPLE_SPHERE_SURFACE_H

#include <math.h>
#include <stdint.h>

enum { SPHERE_NLAT = 8, SPHERE_NLON = 16, SPHERE_NPOINTS = 2 + (SPHERE_NLAT - 1) * SPHERE_NLON, SPHERE_NTRI = 2 * SPHERE_NLON * (SPHERE_NLAT - 1) };

static int32_t sphere_ring_point(int k, int j) { return 1 + (k - 1) * SPHERE_NLON + j % SPHERE_NLON; }

static void sphere_build(double* xyz, int32_t* tri, int32_t* patch) {
  const int q = SPHERE_NLON / 4;
  int k, j, t = 0;
  xyz[0] = 0.0, xyz[1] = 0.0, xyz[2] = -1.0;
  for (k = 1; k < SPHERE_NLAT; ++k) {
    const double zd = (double)(2 * k - SPHERE_NLAT) / (double)SPHERE_NLAT;
    const double rd = 1.0 - fabs(zd);
    const double h = sqrt(rd * rd + zd * zd);
    const double r = rd / h, z = zd / h;
    for (j = 0; j < SPHERE_NLON; ++j) {
      const double u = (double)(j % q) / (double)q;
      double xd, yd, g;
      switch (j / q) {
        case 0: xd = 1.0 - u, yd = u; break;
        case 1: xd = -u, yd = 1.0 - u; break;
        case 2: xd = -(1.0 - u), yd = -u; break;
        default: xd = u, yd = -(1.0 - u); break;
      }
      g = sqrt(xd * xd + yd * yd);
      xyz[3 * sphere_ring_point(k, j)] = r * (xd / g);
      xyz[3 * sphere_ring_point(k, j) + 1] = r * (yd / g);
      xyz[3 * sphere_ring_point(k, j) + 2] = z;
    }
  }
  xyz[3 * (SPHERE_NPOINTS - 1)] = 0.0, xyz[3 * (SPHERE_NPOINTS - 1) + 1] = 0.0, xyz[3 * (SPHERE_NPOINTS - 1) + 2] = 1.0;
  for (j = 0; j < SPHERE_NLON; ++j, ++t) {
    tri[3 * t] = 0, tri[3 * t + 1] = sphere_ring_point(1, j + 1), tri[3 * t + 2] = sphere_ring_point(1, j);
    patch[t] = 1;
  }
  for (k = 1; k < SPHERE_NLAT - 1; ++k) {
    for (j = 0; j < SPHERE_NLON; ++j) {
      const int32_t a = sphere_ring_point(k, j), b = sphere_ring_point(k, j + 1);
      const int32_t c = sphere_ring_point(k + 1, j + 1), d = sphere_ring_point(k + 1, j);
      tri[3 * t] = a, tri[3 * t + 1] = b, tri[3 * t + 2] = c, patch[t++] = 2;
      tri[3 * t] = a, tri[3 * t + 1] = c, tri[3 * t + 2] = d, patch[t++] = 2;
    }
  }
  for (j = 0; j < SPHERE_NLON; ++j, ++t) {
    tri[3 * t] = sphere_ring_point(SPHERE_NLAT - 1, j), tri[3 * t + 1] = sphere_ring_point(SPHERE_NLAT - 1, j + 1);
    tri[3 * t + 2] = SPHERE_NPOINTS - 1;
    patch[t] = 3;
  }
}

#endif
