// geo: geodetic <-> ENU / UTM round trips on Lake Superior's shoreline points (superior.poly,
// x and y taken as longitude and latitude), plus known values and the error paths.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "geo/geodetic.hpp"

namespace anitet {
namespace geo {
namespace {

// The vertices of a Triangle .poly file as (x, y, 0) triples: header "n dim attrs markers",
// then "id x y [attrs] [marker]" lines; '#' starts a comment.
std::vector<double> read_poly_points(const std::string& path) {
  std::ifstream in(path);
  std::vector<double> xyz;
  std::string line;
  long n = -1;
  while (std::getline(in, line)) {
    line = line.substr(0, line.find('#'));
    std::istringstream ls(line);
    if (n < 0) {
      if (ls >> n) continue;
      n = -1;
      continue;
    }
    long id;
    double x, y;
    if (!(ls >> id >> x >> y)) continue;
    xyz.insert(xyz.end(), {x, y, 0.0});
    if (long(xyz.size() / 3) == n) break;
  }
  return xyz;
}

std::vector<double> superior() {
  return read_poly_points(std::string(ANITET_SURFACES_DIR) + "/superior.poly");
}

struct Errors {
  double deg = 0.0, metres = 0.0;
};

// Largest |difference| of longitude/latitude (degrees, longitude modulo 360) and height.
Errors compare(const std::vector<double>& a, const std::vector<double>& b) {
  Errors e;
  for (size_t i = 0; i < a.size(); i += 3) {
    e.deg = std::max(e.deg, std::fabs(std::remainder(a[i] - b[i], 360.0)));
    e.deg = std::max(e.deg, std::fabs(a[i + 1] - b[i + 1]));
    e.metres = std::max(e.metres, std::fabs(a[i + 2] - b[i + 2]));
  }
  return e;
}

// Round trip of pts through the frame, with a check that the local points moved.
Errors round_trip(const GeoFrame& frame, const std::vector<double>& pts) {
  std::vector<double> xyz = pts;
  EXPECT_TRUE(to_local(frame, xyz).ok());
  EXPECT_GT(compare(pts, xyz).deg, 1.0);  // metres now, not degrees
  EXPECT_TRUE(to_geodetic(frame, xyz).ok());
  return compare(pts, xyz);
}

TEST(Geodetic, SuperiorPolyHas518Points) {
  EXPECT_EQ(superior().size(), 3u * 518u);
}

TEST(Geodetic, EnuRoundTripAtDataCentreOnSuperior) {
  std::vector<double> pts = superior();
  ASSERT_EQ(pts.size(), 3u * 518u);
  Result<GeoFrame> frame = centred_frame(FrameKind::Enu, pts);
  ASSERT_TRUE(frame.ok()) << frame.status().message();
  const Errors e = round_trip(frame.value(), pts);
  std::printf("ENU at centre (%.6f, %.6f): max error %.3g deg, %.3g m\n", frame->origin_lat,
              frame->origin_lon, e.deg, e.metres);
  EXPECT_LE(e.deg, 1e-9);
  EXPECT_LE(e.metres, 1e-6);
}

TEST(Geodetic, EnuRoundTripWithHeightsAndGivenOrigin) {
  // The same outline moved onto Lake Superior itself, heights 0 .. 5 km, origin given.
  std::vector<double> pts = superior();
  ASSERT_FALSE(pts.empty());
  for (size_t i = 0; i < pts.size(); i += 3) {
    pts[i] = pts[i] * 10.0 - 87.5;
    pts[i + 1] = pts[i + 1] * 5.0 + 47.5;
    pts[i + 2] = 10.0 * double(i % 500);
  }
  Result<GeoFrame> frame = make_frame(FrameKind::Enu, 47.7, -87.6, 183.0);
  ASSERT_TRUE(frame.ok());
  const Errors e = round_trip(frame.value(), pts);
  EXPECT_LE(e.deg, 1e-9);
  EXPECT_LE(e.metres, 1e-6);
}

TEST(Geodetic, UtmRoundTripOnSuperior) {
  std::vector<double> pts = superior();
  ASSERT_FALSE(pts.empty());
  for (size_t i = 0; i < pts.size(); i += 3) pts[i + 2] = 1.5 * double(i % 100);
  Result<GeoFrame> frame = centred_frame(FrameKind::Utm, pts);
  ASSERT_TRUE(frame.ok()) << frame.status().message();
  EXPECT_EQ(frame->zone, 31);  // longitudes 0 .. 6 east
  const Errors e = round_trip(frame.value(), pts);
  std::printf("UTM zone %d: max error %.3g deg, %.3g m\n", frame->zone, e.deg, e.metres);
  EXPECT_LE(e.deg, 1e-9);
  EXPECT_LE(e.metres, 1e-6);
}

TEST(Geodetic, EnuKnownValues) {
  Result<GeoFrame> frame = make_frame(FrameKind::Enu, 0.0, 0.0, 0.0);
  ASSERT_TRUE(frame.ok());
  // The origin, 0.001 deg north (meridian arc 110574.4 m/deg at the equator), 0.001 deg east
  // (equatorial radius 6378137 m), and 100 m up.
  std::vector<double> xyz = {0.0, 0.0, 0.0, 0.0, 0.001, 0.0, 0.001, 0.0, 0.0, 0.0, 0.0, 100.0};
  ASSERT_TRUE(to_local(frame.value(), xyz).ok());
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(xyz[k], 0.0, 1e-9);
  EXPECT_NEAR(xyz[3], 0.0, 1e-9);
  EXPECT_NEAR(xyz[4], 110.574, 1e-3);
  EXPECT_NEAR(xyz[6], 6378137.0 * 3.14159265358979323846 / 180.0 * 0.001, 1e-3);
  EXPECT_NEAR(xyz[7], 0.0, 1e-9);
  EXPECT_NEAR(xyz[11], 100.0, 1e-9);
}

TEST(Geodetic, UtmKnownValues) {
  // On the equator at a central meridian: easting 500 km, northing 0 (north) or 10000 km (south).
  Result<GeoFrame> north = make_frame(FrameKind::Utm, 10.0, 3.0);
  ASSERT_TRUE(north.ok());
  EXPECT_EQ(north->zone, 31);
  EXPECT_TRUE(north->north);
  std::vector<double> xyz = {3.0, 0.0, 7.0};
  ASSERT_TRUE(to_local(north.value(), xyz).ok());
  EXPECT_NEAR(xyz[0], 500000.0, 1e-6);
  EXPECT_NEAR(xyz[1], 0.0, 1e-6);
  EXPECT_EQ(xyz[2], 7.0);
  Result<GeoFrame> south = make_frame(FrameKind::Utm, -33.9, 151.2);  // Sydney: zone 56 south
  ASSERT_TRUE(south.ok());
  EXPECT_EQ(south->zone, 56);
  EXPECT_FALSE(south->north);
  xyz = {153.0, 0.0, 0.0};
  ASSERT_TRUE(to_local(south.value(), xyz).ok());
  EXPECT_NEAR(xyz[0], 500000.0, 1e-6);
  EXPECT_NEAR(xyz[1], 10000000.0, 1e-6);
}

TEST(Geodetic, CentreAcrossTheAntimeridian) {
  const std::vector<double> pts = {179.9, 10.0, 0.0, -179.9, 10.2, 0.0};
  Result<GeoFrame> frame = centred_frame(FrameKind::Enu, pts);
  ASSERT_TRUE(frame.ok());
  EXPECT_NEAR(std::fabs(frame->origin_lon), 180.0, 1e-9);
  EXPECT_NEAR(frame->origin_lat, 10.1, 1e-12);
  std::vector<double> xyz = pts;
  ASSERT_TRUE(to_local(frame.value(), xyz).ok());
  EXPECT_LT(std::fabs(xyz[0]), 12000.0);  // ~11 km either side, not half the Earth
  EXPECT_LT(std::fabs(xyz[3]), 12000.0);
  ASSERT_TRUE(to_geodetic(frame.value(), xyz).ok());
  const Errors e = compare(pts, xyz);
  EXPECT_LE(e.deg, 1e-9);
  EXPECT_LE(e.metres, 1e-6);
}

TEST(Geodetic, BadInputsAreRejectedAndLeaveTheDataAlone) {
  EXPECT_EQ(make_frame(FrameKind::Enu, 91.0, 0.0).status().code(), Error::InvalidArgument);
  EXPECT_EQ(make_frame(FrameKind::Enu, 0.0, NAN).status().code(), Error::InvalidArgument);
  EXPECT_EQ(make_frame(FrameKind::Utm, 88.0, 0.0).status().code(), Error::InvalidArgument);
  EXPECT_EQ(centred_frame(FrameKind::Enu, {}).status().code(), Error::EmptyInput);
  Result<GeoFrame> frame = make_frame(FrameKind::Enu, 0.0, 0.0);
  ASSERT_TRUE(frame.ok());
  std::vector<double> xyz = {1.0, 2.0, 3.0, 4.0, 95.0, 0.0};
  const std::vector<double> before = xyz;
  const Status st = to_local(frame.value(), xyz);
  EXPECT_EQ(st.code(), Error::InvalidArgument);
  EXPECT_NE(st.message().find("point 1"), std::string::npos) << st.message();
  EXPECT_EQ(xyz, before);
  Result<GeoFrame> utm = make_frame(FrameKind::Utm, 0.0, 3.0);
  ASSERT_TRUE(utm.ok());
  xyz = {100.0, 0.0, 0.0};  // 97 degrees from zone 31's meridian
  EXPECT_EQ(to_local(utm.value(), xyz).code(), Error::InvalidArgument);
}

}  // namespace
}  // namespace geo
}  // namespace anitet
