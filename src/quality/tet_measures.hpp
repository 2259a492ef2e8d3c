// Shape measures of one tetrahedron, in floating point (the sign of the volume that decides
// validity comes from the exact orient3d elsewhere; see quality_report.hpp).
//
// Definitions (the same as /work/shared/tools/meshcheck.py, so that the two agree):
//   volume        = (b-a) x (c-a) . (d-a) / 6   (signed: > 0 for a positively oriented tet)
//   radius ratio  = 3 * inradius / circumradius  (1 for the regular tet, 0 for a flat one)
//   mean ratio    = 12 * (3|V|)^(2/3) / sum of squared edge lengths  (1 regular, 0 flat)
//   dihedral      = interior angle between the two faces at an edge, in degrees
#pragma once

namespace anitet {

struct TetMeasures {
  double volume = 0.0;
  double radius_ratio = 0.0;
  double mean_ratio = 0.0;
  double min_dihedral_deg = 0.0;
  double max_dihedral_deg = 0.0;
};

// Measures of the tet (a, b, c, d). Shape measures use |V|, so an inverted tet gets the same
// shape numbers as its mirror image; a tet whose volume is exactly 0 gets ratios 0.
TetMeasures tet_measures(const double* a, const double* b, const double* c, const double* d);

// The same, except max_dihedral_deg (left 0): instead a key that orders tets' largest dihedrals
// as their angles do (0 to 2), which max_dihedral_from_key turns into the angle. The report
// keeps keys and converts only the largest (an atan2 per tet less).
TetMeasures tet_measures_keyed(const double* a, const double* b, const double* c, const double* d,
                               double& max_dihedral_key);
double max_dihedral_from_key(double key);

// Signed volume only (same formula as TetMeasures::volume).
double tet_signed_volume(const double* a, const double* b, const double* c, const double* d);

}  // namespace anitet
