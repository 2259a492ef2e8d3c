// The one translation unit that includes GeographicLib.
#include "geodetic.hpp"

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>
#include <GeographicLib/TransverseMercator.hpp>
#include <GeographicLib/UTMUPS.hpp>

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>

namespace anitet {
namespace geo {

namespace {

// UTM's false easting and the southern hemisphere's false northing (metres).
constexpr double kFalseEasting = 500000.0;
constexpr double kFalseNorthing = 10000000.0;
// Transverse Mercator (Krüger, 6th order) keeps its 5 nm accuracy within ~3900 km of the
// central meridian; beyond this longitude offset we refuse rather than return a poor point.
constexpr double kMaxZoneOffsetDeg = 35.0;

bool geodetic_ok(double lon, double lat, double h) {
  return std::isfinite(lon) && std::isfinite(lat) && std::isfinite(h) && std::fabs(lat) <= 90.0 &&
         std::fabs(lon) <= 540.0;
}

std::string point_text(size_t i, const double* p) {
  return "point " + std::to_string(i) + " (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) +
         ", " + std::to_string(p[2]) + ")";
}

// lon moved by whole turns to lie within 180 degrees of ref.
double unwrap(double lon, double ref) {
  double d = std::remainder(lon - ref, 360.0);
  return ref + d;
}

double central_meridian(int zone) { return 6.0 * zone - 183.0; }

}  // namespace

Result<GeoFrame> make_frame(FrameKind kind, double lat, double lon, double height) {
  if (!geodetic_ok(lon, lat, height))
    return Status(Error::InvalidArgument,
                  "geodetic origin out of range (latitude in [-90, 90], longitude in [-540, 540], "
                  "finite height): " +
                      std::to_string(lat) + ", " + std::to_string(lon) + ", " +
                      std::to_string(height));
  GeoFrame f;
  f.kind = kind;
  f.origin_lat = lat;
  f.origin_lon = lon;
  f.origin_height = height;
  if (kind == FrameKind::Utm) {
    try {
      f.zone = GeographicLib::UTMUPS::StandardZone(lat, lon);
    } catch (const std::exception& e) {
      return Status(Error::InvalidArgument, std::string("UTM zone: ") + e.what());
    }
    if (f.zone <= 0)
      return Status(Error::InvalidArgument,
                    "no UTM zone at latitude " + std::to_string(lat) + " (polar): use an ENU frame");
    f.north = lat >= 0.0;
  }
  return f;
}

Result<GeoFrame> centred_frame(FrameKind kind, const std::vector<double>& xyz) {
  const size_t n = xyz.size() / 3;
  if (n == 0) return Status(Error::EmptyInput, "no point to centre a geodetic frame on");
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  const double ref = xyz[0];
  for (size_t i = 0; i < n; ++i) {
    const double* p = &xyz[3 * i];
    if (!geodetic_ok(p[0], p[1], p[2]))
      return Status(Error::InvalidArgument, point_text(i, p) + " is not a longitude, latitude, height");
    const double q[3] = {unwrap(p[0], ref), p[1], p[2]};
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], q[k]);
      hi[k] = std::max(hi[k], q[k]);
    }
  }
  double lon = 0.5 * (lo[0] + hi[0]);
  if (lon >= 180.0) lon -= 360.0;
  if (lon < -180.0) lon += 360.0;
  return make_frame(kind, 0.5 * (lo[1] + hi[1]), lon, 0.5 * (lo[2] + hi[2]));
}

namespace {

Status check_zone(const GeoFrame& frame) {
  if (frame.kind != FrameKind::Enu && (frame.zone < 1 || frame.zone > 60))
    return Status(Error::InvalidArgument, "UTM zone must be in 1..60");
  return Status::success();
}

}  // namespace

Status to_local(const GeoFrame& frame, std::vector<double>& xyz) {
  const size_t n = xyz.size() / 3;
  std::vector<double> out(xyz.size());
  if (Status st = check_zone(frame); !st.ok()) return st;
  for (size_t i = 0; i < n; ++i) {
    const double* p = &xyz[3 * i];
    if (!geodetic_ok(p[0], p[1], p[2]))
      return Status(Error::InvalidArgument, point_text(i, p) + " is not a longitude, latitude, height");
  }
  try {
    if (frame.kind == FrameKind::Enu) {
      const GeographicLib::LocalCartesian lc(frame.origin_lat, frame.origin_lon,
                                             frame.origin_height, GeographicLib::Geocentric::WGS84());
      for (size_t i = 0; i < n; ++i) {
        const double* p = &xyz[3 * i];
        lc.Forward(p[1], p[0], p[2], out[3 * i], out[3 * i + 1], out[3 * i + 2]);
      }
    } else {
      const GeographicLib::TransverseMercator& tm = GeographicLib::TransverseMercator::UTM();
      const double lon0 = central_meridian(frame.zone);
      for (size_t i = 0; i < n; ++i) {
        const double* p = &xyz[3 * i];
        if (std::fabs(std::remainder(p[0] - lon0, 360.0)) > kMaxZoneOffsetDeg ||
            std::fabs(p[1]) > 89.0)
          return Status(Error::InvalidArgument, point_text(i, p) + " is too far from UTM zone " +
                                                    std::to_string(frame.zone));
        double x, y;
        tm.Forward(lon0, p[1], p[0], x, y);
        out[3 * i] = x + kFalseEasting;
        out[3 * i + 1] = y + (frame.north ? 0.0 : kFalseNorthing);
        out[3 * i + 2] = p[2];
      }
    }
  } catch (const std::exception& e) {
    return Status(Error::InvalidArgument, std::string("GeographicLib: ") + e.what());
  }
  xyz.swap(out);
  return Status::success();
}

Status to_geodetic(const GeoFrame& frame, std::vector<double>& xyz) {
  const size_t n = xyz.size() / 3;
  std::vector<double> out(xyz.size());
  if (Status st = check_zone(frame); !st.ok()) return st;
  try {
    for (size_t i = 0; i < n; ++i) {
      const double* p = &xyz[3 * i];
      if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])))
        return Status(Error::InvalidArgument, point_text(i, p) + " is not finite");
    }
    double lat, lon, h;
    if (frame.kind == FrameKind::Enu) {
      const GeographicLib::LocalCartesian lc(frame.origin_lat, frame.origin_lon,
                                             frame.origin_height, GeographicLib::Geocentric::WGS84());
      for (size_t i = 0; i < n; ++i) {
        const double* p = &xyz[3 * i];
        lc.Reverse(p[0], p[1], p[2], lat, lon, h);
        out[3 * i] = lon;
        out[3 * i + 1] = lat;
        out[3 * i + 2] = h;
      }
    } else {
      const GeographicLib::TransverseMercator& tm = GeographicLib::TransverseMercator::UTM();
      const double lon0 = central_meridian(frame.zone);
      for (size_t i = 0; i < n; ++i) {
        const double* p = &xyz[3 * i];
        tm.Reverse(lon0, p[0] - kFalseEasting, p[1] - (frame.north ? 0.0 : kFalseNorthing), lat,
                   lon);
        out[3 * i] = lon;
        out[3 * i + 1] = lat;
        out[3 * i + 2] = p[2];
      }
    }
  } catch (const std::exception& e) {
    return Status(Error::InvalidArgument, std::string("GeographicLib: ") + e.what());
  }
  xyz.swap(out);
  return Status::success();
}

}  // namespace geo
}  // namespace anitet
