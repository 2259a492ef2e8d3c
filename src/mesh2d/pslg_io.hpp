// Readers of the 2D mesher's inputs: Triangle's .poly (and .node), Medit's 2D .mesh, GeoJSON.
// Errors name the file, the line (text formats) or the feature/polygon/ring (GeoJSON) and the
// element, 1-based (or as the file numbers them).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/status.hpp"
#include "mesh2d/pslg.hpp"

namespace anitet::mesh2d {

// Triangle's .poly: "<#points> 2 <#attributes> <#markers>", points "<i> <x> <y> [attributes]
// [marker]", "<#segments> <#markers>", segments "<i> <a> <b> [marker]" (the marker is the
// segment's label, 0 without), "<#holes>", holes "<i> <x> <y>", optionally "<#regions>",
// regions "<i> <x> <y> <attribute> [max area]". Numbering from 0 or 1 (the first point's).
// With 0 points the points are in `node_data` (the .node file of the same name).
Result<Pslg> parse_poly(std::string_view data, const std::string& name, std::string_view node_data = {},
                        const std::string& node_name = {});

// A 2D Medit mesh: "Dimension 2" (or 3 with every z zero), Vertices "x y ref", Edges "a b ref",
// Triangles "a b c ref" (1-based); other sections skipped.
struct Medit2d {
  std::vector<double> xy;
  std::vector<uint32_t> edges, tri;     // 0-based
  std::vector<int32_t> edge_ref, tri_ref;
  std::vector<uint32_t> vertex_line, edge_line;  // the line each element starts on
};
Result<Medit2d> parse_medit2d(std::string_view data, const std::string& name);
// Its vertices and edges (labels: the edges' references) as a PSLG.
Result<Pslg> parse_medit2d_pslg(std::string_view data, const std::string& name);

// GeoJSON (RFC 7946): a FeatureCollection, Feature or geometry whose Polygon and MultiPolygon
// geometries make the domain (their union); positions are [longitude, latitude] (a third value
// is ignored). Equal positions become one point and shared edges one segment (an interface).
// Labels: a feature's numeric "label" property, else 1 on outer rings and 2 on inner ones.
// LineString and MultiLineString features with a "label" relabel the polygon edges they run
// along (each of their edges must be one). A polygon's attribute: its feature's numeric
// "region" property, else its 1-based number (in feature order).
Result<Pslg> parse_geojson(std::string_view data, const std::string& name);

// By extension: .poly, .mesh, .geojson or .json. Error::UnsupportedFormat for others.
Result<Pslg> read_pslg(const std::string& path);

}  // namespace anitet::mesh2d
