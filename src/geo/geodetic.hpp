// Geographic inputs: coordinates given as longitude, latitude (degrees) and height (metres) on the
// WGS84 ellipsoid, converted with GeographicLib to a local Cartesian frame in metres and back.
//
// Point layout everywhere here: x = longitude, y = latitude, z = ellipsoidal height (the order of
// lon/lat data files). Two local frames:
//  - Enu: east-north-up tangent frame at an origin (GeographicLib::LocalCartesian, exact: the
//    round trip only loses rounding, no projection error).
//  - Utm: UTM easting/northing in one zone (the zone of the origin, or a given one) with the
//    height kept as z. Transverse Mercator (Krüger series, ~5 nm accuracy in the zone).
// GeographicLib is included by geodetic.cpp alone.
#pragma once

#include <cstddef>
#include <vector>

#include "core/status.hpp"
#include "core/surface_mesh.hpp"

namespace anitet {
namespace geo {

enum class FrameKind { Enu, Utm };

struct GeoFrame {
  FrameKind kind = FrameKind::Enu;
  // Enu: the tangent point. Utm: only picks the zone when zone == 0.
  double origin_lat = 0.0, origin_lon = 0.0, origin_height = 0.0;
  int zone = 0;        // Utm: 1..60 (0: the zone of the origin, fixed by make_frame)
  bool north = true;   // Utm: hemisphere of the northings
};

// The geodetic point (lat, lon, h) as a frame origin: Error::InvalidArgument unless finite,
// |lat| <= 90 and |lon| <= 540 (GeographicLib's range).
Result<GeoFrame> make_frame(FrameKind kind, double lat, double lon, double height = 0.0);

// The frame at the centre of the data's bounding box (longitudes unwrapped around the first
// point's, so data across the antimeridian gets a sensible centre). xyz: lon, lat, h per point.
// Error::EmptyInput without points, Error::InvalidArgument for a point out of range.
Result<GeoFrame> centred_frame(FrameKind kind, const std::vector<double>& xyz);

// In place, 3 doubles per point: (lon, lat, h) -> local (x, y, z) in metres, and back
// (longitudes come back in [-180, 180]).
// Error::InvalidArgument naming the first point out of range (nothing is converted then), e.g. a
// latitude beyond 90 or a UTM point too far from its zone.
Status to_local(const GeoFrame& frame, std::vector<double>& xyz);
Status to_geodetic(const GeoFrame& frame, std::vector<double>& xyz);

// The same on a surface's vertices.
inline Status to_local(const GeoFrame& frame, SurfaceMesh& surface) {
  return to_local(frame, surface.xyz);
}
inline Status to_geodetic(const GeoFrame& frame, SurfaceMesh& surface) {
  return to_geodetic(frame, surface.xyz);
}

}  // namespace geo
}  // namespace anitet
