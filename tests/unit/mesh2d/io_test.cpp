// The 2D readers and writers: .poly (both numberings, .node, holes, regions, markers), 2D .mesh,
// GeoJSON (rings, holes, shared edges, labelling lines), their errors naming line and element,
// and the writers read back.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "mesh2d/mesh2d_io.hpp"
#include "mesh2d/mesher2.hpp"
#include "mesh2d/pslg_io.hpp"

namespace anitet::mesh2d {
namespace {

const char* kPoly =
    "# a square with a hole and a region\n"
    "4 2 1 1\n"
    "0 0 0 7.5 1\n"
    "1 1 0 7.5 1\n"
    "2 1 1 7.5 1\n"
    "3 0 1 7.5 1\n"
    "4 1\n"
    "0 0 1 5\n"
    "1 1 2 6\n"
    "2 2 3 7\n"
    "3 3 0 8\n"
    "1\n"
    "0 -1 -1\n"
    "1\n"
    "0 0.5 0.5 3 0.01\n";

TEST(Mesh2dIo, PolyZeroBasedWithMarkersHolesAndRegions) {
  Result<Pslg> p = parse_poly(kPoly, "sq.poly");
  ASSERT_TRUE(p.ok()) << p.status().message();
  EXPECT_EQ(p->first_index, 0);
  EXPECT_EQ(p->num_points(), 4u);
  EXPECT_EQ(p->seg, (std::vector<uint32_t>{0, 1, 1, 2, 2, 3, 3, 0}));
  EXPECT_EQ(p->label, (std::vector<int32_t>{5, 6, 7, 8}));
  EXPECT_EQ(p->holes, (std::vector<double>{-1, -1}));
  ASSERT_EQ(p->regions.size(), 1u);
  EXPECT_EQ(p->regions[0].attribute, 3.0);
  EXPECT_EQ(p->regions[0].max_area, 0.01);
  EXPECT_EQ(describe_segment(p.value(), 2), "segment 2 (line 10)");
}

TEST(Mesh2dIo, PolyErrorsNameTheLine) {
  auto code = [](const std::string& text) { return parse_poly(text, "t.poly").status(); };
  Status s = code("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n3 0\n1 1 2\n2 2 7\n3 3 1\n0\n");
  EXPECT_EQ(s.code(), Error::BadIndex);
  EXPECT_NE(s.message().find("t.poly:7: segment 2 refers to point 7"), std::string::npos) << s.message();
  s = code("3 3 0 0\n");
  EXPECT_EQ(s.code(), Error::UnsupportedFormat);
  s = code("3 2 0 0\n1 0 0\n3 1 0\n");
  EXPECT_EQ(s.code(), Error::Parse);
  EXPECT_NE(s.message().find(":3:"), std::string::npos) << s.message();
  s = code("0 2 0 0\n3 0\n");
  EXPECT_EQ(s.code(), Error::Parse);  // no .node given
  // With the .node.
  Result<Pslg> p = parse_poly("0 2 0 0\n3 0\n1 1 2\n2 2 3\n3 3 1\n0\n", "t.poly", "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n", "t.node");
  ASSERT_TRUE(p.ok()) << p.status().message();
  EXPECT_EQ(p->num_points(), 3u);
}

TEST(Mesh2dIo, Medit2dEdgesAndErrors) {
  Result<Pslg> p = parse_medit2d_pslg(
      "MeshVersionFormatted 2\nDimension 2\nVertices\n3\n0 0 0\n1 0 0\n0 1 0\nEdges\n3\n1 2 4\n2 3 4\n3 1 9\nEnd\n", "t.mesh");
  ASSERT_TRUE(p.ok()) << p.status().message();
  EXPECT_EQ(p->label, (std::vector<int32_t>{4, 4, 9}));
  EXPECT_EQ(describe_point(p.value(), 1), "point 2 (line 6)");
  EXPECT_EQ(parse_medit2d_pslg("Dimension 2\nVertices\n1\n0 0 0\nEnd\n", "t.mesh").status().code(), Error::EmptyInput);
  const Status bad = parse_medit2d_pslg("Dimension 2\nVertices\n2\n0 0 0\n1 0 0\nEdges\n1\n1 3 0\n", "t.mesh").status();
  EXPECT_EQ(bad.code(), Error::BadIndex);
  EXPECT_NE(bad.message().find("edges 1 refers to vertex 3"), std::string::npos) << bad.message();
  EXPECT_EQ(parse_medit2d_pslg("Dimension 3\nVertices\n1\n0 0 1 0\n", "t.mesh").status().code(), Error::UnsupportedFormat);
}

TEST(Mesh2dIo, GeoJsonPolygonsHolesSharedEdgesAndLabels) {
  // Two unit squares side by side (a shared edge: one interface segment), the first with a hole;
  // a line labels the right square's right side.
  const char* text = R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {"region": 7}, "geometry": {"type": "Polygon", "coordinates": [
      [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]], [[0.25, 0.25], [0.25, 0.75], [0.75, 0.75], [0.75, 0.25], [0.25, 0.25]]]}},
    {"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": [
      [[1, 0], [2, 0], [2, 1], [1, 1], [1, 0]]]}},
    {"type": "Feature", "properties": {"label": 3}, "geometry": {"type": "LineString", "coordinates": [[2, 0], [2, 1]]}}]})";
  Result<Pslg> p = parse_geojson(text, "t.geojson");
  ASSERT_TRUE(p.ok()) << p.status().message();
  EXPECT_EQ(p->num_points(), 10u);
  EXPECT_EQ(p->num_segments(), 11u);  // 4 + 4 + 4 - 1 shared
  ASSERT_EQ(p->polygons.size(), 2u);
  EXPECT_EQ(p->polygons[0].attribute, 7.0);
  EXPECT_EQ(p->polygons[1].attribute, 2.0);
  int threes = 0, twos = 0;
  for (int32_t l : p->label) threes += l == 3, twos += l == 2;
  EXPECT_EQ(threes, 1);
  EXPECT_EQ(twos, 4);  // the hole's ring
  // Meshed: the hole empty, two regions, the interface kept.
  Mesh2dOptions o;
  o.sizing.hsize = 0.2;
  Result<TriMesh2> m = mesh_pslg(p.value(), o);
  ASSERT_TRUE(m.ok()) << m.status().message();
  double area7 = 0, area2 = 0;
  for (size_t t = 0; t < m->num_triangles(); ++t) {
    const double* a = &m->xy[2 * size_t(m->tri[3 * t])];
    const double* b = &m->xy[2 * size_t(m->tri[3 * t + 1])];
    const double* c = &m->xy[2 * size_t(m->tri[3 * t + 2])];
    const double ar = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    (m->attribute[t] == 7.0 ? area7 : area2) += ar;
  }
  EXPECT_NEAR(area7, 0.75, 1e-12);
  EXPECT_NEAR(area2, 1.0, 1e-12);
}

TEST(Mesh2dIo, GeoJsonErrorsNameTheFeature) {
  Status s = parse_geojson(R"({"type": "Feature", "geometry": {"type": "Point", "coordinates": [0, 0]}})", "t.geojson").status();
  EXPECT_EQ(s.code(), Error::UnsupportedFormat);
  EXPECT_NE(s.message().find("feature 1: geometry type 'Point'"), std::string::npos) << s.message();
  s = parse_geojson("{\n\"type\": \n", "t.geojson").status();
  EXPECT_EQ(s.code(), Error::Parse);
  EXPECT_NE(s.message().find("t.geojson:3:"), std::string::npos) << s.message();
  s = parse_geojson(R"({"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [0, 0]]]})", "t.geojson").status();
  EXPECT_EQ(s.code(), Error::InvalidArgument);
  EXPECT_NE(s.message().find("feature 1, polygon 1, ring 1"), std::string::npos) << s.message();
  // Members of the wrong type: refused by name, never thrown.
  s = parse_geojson(R"({"type": [1], "coordinates": []})", "t.geojson").status();
  EXPECT_EQ(s.code(), Error::UnsupportedFormat) << s.message();
  s = parse_geojson(R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {}, "geometry": null},
    {"type": "Feature", "properties": {"label": "land"}, "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [0, 1], [0, 0]]]}}]})",
                    "t.geojson").status();
  EXPECT_EQ(s.code(), Error::Parse);
  EXPECT_NE(s.message().find("feature 2 has a \"label\" that is not an integer"), std::string::npos) << s.message();
  s = parse_geojson(R"({"type": "Feature", "properties": {"label": 4294967296}, "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [0, 1], [0, 0]]]}})",
                    "t.geojson").status();
  EXPECT_EQ(s.code(), Error::Parse) << s.message();
  // A bow tie: the crossing named by its ring and vertex.
  Result<Pslg> p = parse_geojson(R"({"type": "Polygon", "coordinates": [[[0, 0], [1, 1], [1, 0], [0, 1], [0, 0]]]})", "t.geojson");
  ASSERT_TRUE(p.ok());
  Result<TriMesh2> m = mesh_pslg(p.value(), Mesh2dOptions{});
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.status().code(), Error::SelfIntersection);
  EXPECT_NE(m.status().message().find("(feature 1, polygon 1, ring 1, vertex 1)"), std::string::npos) << m.status().message();
}

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(Mesh2dIo, WritersAndFort14Boundaries) {
  // A square with a square island: the outer loop's bottom side open (label 3).
  Pslg p;
  p.xy = {0, 0, 3, 0, 3, 3, 0, 3, 1, 1, 2, 1, 2, 2, 1, 2};
  p.seg = {0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4};
  p.label = {3, 1, 1, 1, 2, 2, 2, 2};
  p.holes = {1.5, 1.5};
  Mesh2dOptions o;
  o.sizing.hsize = 1.0;
  Result<TriMesh2> m = mesh_pslg(p, o);
  ASSERT_TRUE(m.ok()) << m.status().message();
  const std::string dir = testing::TempDir();
  Fort14Options f;
  f.open_labels = {3};
  ASSERT_TRUE(write_fort14(dir + "/sq.14", m.value(), f).ok());
  const std::string text = slurp(dir + "/sq.14");
  EXPECT_NE(text.find("1 = Number of open boundaries\n2 = Total number of open boundary nodes\n2 0 = Number of nodes for open boundary 1\n1\n2\n"),
            std::string::npos) << text;
  // Land: the rest of the outer loop (4 nodes, mainland 20) first, then the island closed (5, 21).
  EXPECT_NE(text.find("2 = Number of land boundaries\n9 = Total number of land boundary nodes\n4 20 = Number of nodes for land boundary 1\n2\n3\n4\n1\n5 21 ="),
            std::string::npos) << text;
  for (const char* name : {"sq.mesh", "sq.msh", "sq.vtu"}) ASSERT_TRUE(write_mesh2d(dir + "/" + name, m.value()).ok()) << name;
  EXPECT_EQ(write_mesh2d(dir + "/sq.obj", m.value()).code(), Error::UnsupportedFormat);
  // The .mesh read back as a PSLG: its vertices and edges.
  Result<Medit2d> back = parse_medit2d(slurp(dir + "/sq.mesh"), "sq.mesh");
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->xy, m->xy);
  EXPECT_EQ(back->tri, m->tri);
  EXPECT_EQ(back->edge_ref, m->edge_label);
  EXPECT_NE(slurp(dir + "/sq.msh").find("$MeshFormat\n4.1 0 8"), std::string::npos);
}

}  // namespace
}  // namespace anitet::mesh2d
