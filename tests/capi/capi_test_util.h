/* Shared data and helpers of the C ABI tests. */
#ifndef ANITET_CAPI_TEST_UTIL_H
#define ANITET_CAPI_TEST_UTIL_H

#include <stdint.h>

#include "anitet.h"

/* The unit cube: 8 points, 12 triangles counter-clockwise seen from outside, 0-based. */
static const double kCubeXyz[24] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0,
                                    0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
static const int32_t kCubeTri[36] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                     3, 7, 6, 3, 6, 2, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};
static const int32_t kCubePatch[12] = {1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6};

#endif
