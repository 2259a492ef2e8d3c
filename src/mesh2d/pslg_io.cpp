#include "mesh2d/pslg_io.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <nlohmann/json.hpp>

#include "io/file_bytes.hpp"
#include "io/reader_util.hpp"
#include "io/text_scanner.hpp"

namespace anitet::mesh2d {

namespace {

constexpr uint64_t kMaxCount = 0xfffffff0u;

// The points of a .poly or .node: header "<#points> <dim> <#attributes> <#markers>" (already
// read when `count` is given) and one line per point.
Status read_poly_points(TextScanner& in, Pslg& p, bool header_read, uint64_t count, int64_t dim, uint64_t attributes,
                        uint64_t markers) {
  if (!header_read) {
    int64_t d = 0;
    if (!in.read_count(kMaxCount, count)) return in.expected("the number of points");
    if (!in.read_int(d)) return in.expected("the dimension");
    dim = d;
    if (!in.read_count(1u << 20, attributes)) return in.expected("the number of point attributes");
    if (!in.read_count(1, markers)) return in.expected("the number of point markers (0 or 1)");
  }
  if (dim != 2) return in.error(Error::UnsupportedFormat, "dimension " + std::to_string(dim) + ": only 2 is supported");
  if (!fits(count, 6, in.remaining() + 1)) return in.error(Error::Parse, std::to_string(count) + " points do not fit in the file");
  p.xy.resize(2 * count);
  p.point_origin.resize(count);
  for (uint64_t i = 0; i < count; ++i) {
    int64_t id = 0;
    in.skip_space();
    const uint32_t line = uint32_t(in.line());
    if (!in.read_int(id)) return in.expected("the number of point " + std::to_string(i + 1));
    if (i == 0) {
      if (id != 0 && id != 1) return in.error(Error::Parse, "the first point is numbered " + std::to_string(id) + ", not 0 or 1");
      p.first_index = int(id);
    } else if (id != int64_t(i) + p.first_index) {
      return in.error(Error::Parse, "point " + std::to_string(id) + " out of order: expected " +
                                        std::to_string(int64_t(i) + p.first_index));
    }
    p.point_origin[i].line = line;
    if (!in.read_double(p.xy[2 * i]) || !in.read_double(p.xy[2 * i + 1]))
      return in.expected("the coordinates of point " + std::to_string(id));
    double ignored;
    for (uint64_t k = 0; k < attributes + markers; ++k)
      if (!in.read_double(ignored)) return in.expected("an attribute or marker of point " + std::to_string(id));
  }
  return Status::success();
}

}  // namespace

Result<Pslg> parse_poly(std::string_view data, const std::string& name, std::string_view node_data,
                        const std::string& node_name) {
  return catch_bad_alloc(name, [&]() -> Result<Pslg> {
    Pslg p;
    p.name = name;
    TextScanner in(data, name);
    uint64_t count = 0, attributes = 0, markers = 0;
    int64_t dim = 0;
    if (!in.read_count(kMaxCount, count)) return in.expected("the number of points");
    if (!in.read_int(dim)) return in.expected("the dimension");
    if (!in.read_count(1u << 20, attributes)) return in.expected("the number of point attributes");
    if (!in.read_count(1, markers)) return in.expected("the number of point markers (0 or 1)");
    if (count > 0) {
      if (Status s = read_poly_points(in, p, true, count, dim, attributes, markers); !s.ok()) return s;
    } else {
      if (node_data.empty())
        return in.error(Error::Parse, "0 points: they must be in the .node file of the same name, which is missing or empty");
      TextScanner node(node_data, node_name);
      if (Status s = read_poly_points(node, p, false, 0, 0, 0, 0); !s.ok()) return s;
    }
    const uint64_t n = p.num_points();
    uint64_t nseg = 0, seg_markers = 0;
    if (!in.read_count(kMaxCount, nseg)) return in.expected("the number of segments");
    if (!in.read_count(1, seg_markers)) return in.expected("the number of segment markers (0 or 1)");
    if (!fits(nseg, 6, in.remaining() + 1)) return in.error(Error::Parse, std::to_string(nseg) + " segments do not fit in the file");
    p.seg.resize(2 * nseg);
    p.label.assign(nseg, 0);
    p.seg_origin.resize(nseg);
    for (uint64_t i = 0; i < nseg; ++i) {
      int64_t id = 0, a = 0, b = 0;
      in.skip_space();
      p.seg_origin[i].line = uint32_t(in.line());
      if (!in.read_int(id)) return in.expected("the number of segment " + std::to_string(i + 1));
      if (!in.read_int(a) || !in.read_int(b)) return in.expected("the points of segment " + std::to_string(id));
      for (int64_t v : {a, b})
        if (v < p.first_index || v >= int64_t(n) + p.first_index)
          return in.error(Error::BadIndex, "segment " + std::to_string(id) + " refers to point " + std::to_string(v) +
                                               ", but the points are numbered " + std::to_string(p.first_index) + " to " +
                                               std::to_string(int64_t(n) - 1 + p.first_index));
      p.seg[2 * i] = uint32_t(a - p.first_index);
      p.seg[2 * i + 1] = uint32_t(b - p.first_index);
      if (seg_markers) {
        int64_t mark = 0;
        if (!in.read_int(mark) || mark < INT32_MIN || mark > INT32_MAX)
          return in.expected("the marker of segment " + std::to_string(id));
        p.label[i] = int32_t(mark);
      }
    }
    uint64_t nholes = 0;
    if (!in.read_count(kMaxCount, nholes)) return in.expected("the number of holes");
    if (!fits(nholes, 6, in.remaining() + 1)) return in.error(Error::Parse, std::to_string(nholes) + " holes do not fit in the file");
    p.holes.resize(2 * nholes);
    p.hole_origin.resize(nholes);
    for (uint64_t i = 0; i < nholes; ++i) {
      int64_t id = 0;
      in.skip_space();
      p.hole_origin[i].line = uint32_t(in.line());
      if (!in.read_int(id) || !in.read_double(p.holes[2 * i]) || !in.read_double(p.holes[2 * i + 1]))
        return in.expected("hole " + std::to_string(i + 1) + ": its number and coordinates");
    }
    if (!in.skip_space()) return p;
    uint64_t nregions = 0;
    if (!in.read_count(kMaxCount, nregions)) return in.expected("the number of regions");
    for (uint64_t i = 0; i < nregions; ++i) {
      int64_t id = 0;
      Region r;
      in.skip_space();
      Origin o;
      o.line = uint32_t(in.line());
      if (!in.read_int(id) || !in.read_double(r.x) || !in.read_double(r.y))
        return in.expected("region " + std::to_string(i + 1) + ": its number and coordinates");
      if (!in.read_double_in_line(r.attribute)) return in.expected("the attribute of region " + std::to_string(i + 1));
      if (in.skip_space_in_line() && !in.read_double_in_line(r.max_area))
        return in.expected("the area bound of region " + std::to_string(i + 1));
      p.regions.push_back(r);
      p.region_origin.push_back(o);
    }
    return p;
  });
}

// ---- Medit 2D ---------------------------------------------------------------------------------

namespace {

bool starts_number(std::string_view t) {
  return !t.empty() && (std::isdigit(static_cast<unsigned char>(t[0])) || t[0] == '-' || t[0] == '+' || t[0] == '.');
}

Status read_medit_elements(TextScanner& in, const char* what, int per, uint64_t nv, std::vector<uint32_t>& idx,
                           std::vector<int32_t>& ref, std::vector<uint32_t>* lines) {
  uint64_t count = 0;
  if (!in.read_count(kMaxCount, count)) return in.expected(std::string("the number of ") + what);
  if (!fits(count, 2 * uint64_t(per + 1), in.remaining() + 1))
    return in.error(Error::Parse, std::to_string(count) + " " + what + " do not fit in the file");
  const size_t base = ref.size();
  idx.resize(idx.size() + size_t(per) * count);
  ref.resize(base + count);
  for (uint64_t e = 0; e < count; ++e) {
    in.skip_space();
    if (lines) lines->push_back(uint32_t(in.line()));
    for (int k = 0; k < per; ++k) {
      int64_t v = 0;
      if (!in.read_int(v)) return in.expected(std::string("a vertex of ") + what + " " + std::to_string(e + 1));
      if (v < 1 || uint64_t(v) > nv)
        return in.error(Error::BadIndex, std::string(what) + " " + std::to_string(e + 1) + " refers to vertex " +
                                             std::to_string(v) + ", but there are " + std::to_string(nv) +
                                             " vertices (numbered from 1)");
      idx[(base + e) * size_t(per) + size_t(k)] = uint32_t(v - 1);
    }
    int64_t r = 0;
    if (!in.read_int(r) || r < INT32_MIN || r > INT32_MAX)
      return in.expected(std::string("the reference of ") + what + " " + std::to_string(e + 1));
    ref[base + e] = int32_t(r);
  }
  return Status::success();
}

}  // namespace

Result<Medit2d> parse_medit2d(std::string_view data, const std::string& name) {
  return catch_bad_alloc(name, [&]() -> Result<Medit2d> {
    if (data.size() >= 4 && data.substr(0, 4).find('\0') != std::string_view::npos)
      return Status(Error::UnsupportedFormat, name + ": binary Medit files (.meshb) are not supported");
    Medit2d out;
    TextScanner in(data, name);
    int64_t dim = 0;
    bool have_vertices = false;
    for (;;) {
      const std::string_view key = in.next_token();
      if (key.empty() || iequals(key, "End")) break;
      Status status;
      if (iequals(key, "MeshVersionFormatted")) {
        int64_t version = 0;
        if (!in.read_int(version)) return in.expected("the mesh version");
      } else if (iequals(key, "Dimension")) {
        if (!in.read_int(dim)) return in.expected("the dimension");
        if (dim != 2 && dim != 3) return in.error(Error::UnsupportedFormat, "Dimension " + std::to_string(dim) + ": 2 expected");
      } else if (iequals(key, "Vertices")) {
        if (dim == 0) return in.error(Error::Parse, "Vertices before Dimension");
        if (have_vertices) return in.error(Error::Parse, "a second Vertices section");
        have_vertices = true;
        uint64_t count = 0;
        if (!in.read_count(kMaxCount, count)) return in.expected("the number of vertices");
        if (!fits(count, 6, in.remaining() + 1)) return in.error(Error::Parse, std::to_string(count) + " vertices do not fit in the file");
        out.xy.resize(2 * count);
        out.vertex_line.resize(count);
        for (uint64_t v = 0; v < count; ++v) {
          in.skip_space();
          out.vertex_line[v] = uint32_t(in.line());
          double z = 0;
          if (!in.read_double(out.xy[2 * v]) || !in.read_double(out.xy[2 * v + 1]) || (dim == 3 && !in.read_double(z)))
            return in.expected("a coordinate of vertex " + std::to_string(v + 1));
          if (z != 0) return in.error(Error::UnsupportedFormat, "vertex " + std::to_string(v + 1) + " has z = " +
                                                                   std::to_string(z) + ": a 2D mesh needs every z to be 0");
          int64_t ref = 0;
          if (!in.read_int(ref)) return in.expected("the reference of vertex " + std::to_string(v + 1));
        }
      } else if (iequals(key, "Edges")) {
        status = read_medit_elements(in, "edges", 2, out.xy.size() / 2, out.edges, out.edge_ref, &out.edge_line);
      } else if (iequals(key, "Triangles")) {
        status = read_medit_elements(in, "triangles", 3, out.xy.size() / 2, out.tri, out.tri_ref, nullptr);
      } else if (starts_number(key)) {
        return in.error(Error::Parse, "expected a keyword, found '" + quote_token(key) + "'");
      } else {
        while (starts_number(in.peek_token())) in.next_token();  // a section of no use here
      }
      if (!status.ok()) return status;
    }
    if (dim == 0) return Status(Error::Parse, name + ": no Dimension");
    return out;
  });
}

Result<Pslg> parse_medit2d_pslg(std::string_view data, const std::string& name) {
  Result<Medit2d> mesh = parse_medit2d(data, name);
  if (!mesh.ok()) return mesh.status();
  Pslg p;
  p.name = name;
  p.xy = std::move(mesh->xy);
  p.seg = std::move(mesh->edges);
  p.label = std::move(mesh->edge_ref);
  for (uint32_t line : mesh->vertex_line) p.point_origin.push_back(Origin{line});
  for (uint32_t line : mesh->edge_line) p.seg_origin.push_back(Origin{line});
  if (p.seg.empty()) return Status(Error::EmptyInput, name + ": no Edges section: the domain's boundary must be given as edges");
  return p;
}

// ---- GeoJSON ------------------------------------------------------------------------------------

namespace {

using nlohmann::json;

// An object's "type" member, "" when it has none or it is no string (json::value would throw).
std::string type_of(const json& o) {
  const auto it = o.find("type");
  return it != o.end() && it->is_string() ? it->get<std::string>() : std::string();
}

// Whether the properties hold a "label" that is an integer of 32 bits.
bool is_label(const json& props) {
  const auto it = props.find("label");
  if (it == props.end() || !it->is_number_integer()) return false;
  const double v = it->get<double>();
  return v >= -2147483648.0 && v <= 2147483647.0;
}

class GeoJsonBuilder {
 public:
  explicit GeoJsonBuilder(const std::string& name) { p_.name = name; }

  Status feature(const json& f, uint32_t number) {
    if (!f.is_object()) return fail(number, "is not an object");
    const std::string type = type_of(f);
    if (type == "Feature") {
      const json& props = f.contains("properties") && f["properties"].is_object() ? f["properties"] : json::object();
      return geometry(f.contains("geometry") ? f["geometry"] : json(), props, number);
    }
    return geometry(f, json::object(), number);
  }

  Result<Pslg> finish() {
    for (const Relabel& r : relabels_) {
      const auto it = seg_of_.find(key(r.a, r.b));
      if (it == seg_of_.end())
        return Status(Error::InvalidArgument, p_.name + ": feature " + std::to_string(r.feature) + ": its edge " +
                                                  std::to_string(r.edge) + " is no polygon's edge (labels run along polygon edges)");
      p_.label[it->second] = r.label;
    }
    if (p_.polygons.empty()) return Status(Error::EmptyInput, p_.name + ": no Polygon or MultiPolygon geometry");
    return std::move(p_);
  }

 private:
  struct Relabel {
    uint32_t a, b;
    int32_t label;
    uint32_t feature, edge;
  };
  static uint64_t key(uint32_t a, uint32_t b) { return (uint64_t(std::min(a, b)) << 32) | std::max(a, b); }

  Status fail(uint32_t feature, const std::string& what) const {
    return Status(Error::Parse, p_.name + ": feature " + std::to_string(feature) + " " + what);
  }

  Status position(const json& pos, uint32_t feature, double& x, double& y) const {
    if (!pos.is_array() || pos.size() < 2 || !pos[0].is_number() || !pos[1].is_number())
      return fail(feature, "has a position that is not [longitude, latitude]");
    x = pos[0].get<double>();
    y = pos[1].get<double>();
    return Status::success();
  }

  uint32_t point(double x, double y, const Origin& o) {
    const auto [it, added] = point_of_.emplace(std::make_pair(x, y), uint32_t(p_.num_points()));
    if (added) {
      p_.xy.push_back(x);
      p_.xy.push_back(y);
      p_.point_origin.push_back(o);
    }
    return it->second;
  }

  // A ring as a closed list of points (the closing position, when repeated, dropped).
  Status ring(const json& r, Origin o, int32_t label, std::vector<uint32_t>& out) {
    if (!r.is_array()) return fail(o.feature, "has a ring that is not an array");
    out.clear();
    for (size_t i = 0; i < r.size(); ++i) {
      double x = 0, y = 0;
      if (Status s = position(r[i], o.feature, x, y); !s.ok()) return s;
      o.vertex = uint32_t(i + 1);
      const uint32_t v = point(x, y, o);
      if (!out.empty() && out.back() == v) continue;  // a repeated position
      out.push_back(v);
    }
    if (out.size() > 1 && out.front() == out.back()) out.pop_back();
    if (out.size() < 3)
      return Status(Error::InvalidArgument, p_.name + ": feature " + std::to_string(o.feature) + ", polygon " +
                                                std::to_string(o.polygon) + ", ring " + std::to_string(o.ring) +
                                                " has fewer than 3 distinct positions");
    for (size_t i = 0; i < out.size(); ++i) {
      const uint32_t a = out[i], b = out[(i + 1) % out.size()];
      o.vertex = uint32_t(i + 1);
      if (seg_of_.emplace(key(a, b), uint32_t(p_.num_segments())).second) {
        p_.seg.push_back(a);
        p_.seg.push_back(b);
        p_.label.push_back(label);
        p_.seg_origin.push_back(o);
      }
    }
    return Status::success();
  }

  Status polygon(const json& coords, const json& props, uint32_t feature, uint32_t number) {
    if (!coords.is_array() || coords.empty()) return fail(feature, "has a polygon without rings");
    PolygonRings poly;
    const bool has_region = props.contains("region");
    if (has_region && !props["region"].is_number()) return fail(feature, "has a \"region\" that is not a number");
    poly.attribute = has_region ? props["region"].get<double>() : double(p_.polygons.size() + 1);
    const bool has_label = props.contains("label");
    if (has_label && !is_label(props)) return fail(feature, "has a \"label\" that is not an integer of 32 bits");
    for (size_t r = 0; r < coords.size(); ++r) {
      Origin o;
      o.feature = feature;
      o.polygon = number;
      o.ring = uint32_t(r + 1);
      const int32_t label = has_label ? props["label"].get<int32_t>() : (r == 0 ? 1 : 2);
      std::vector<uint32_t> ring_points;
      if (Status s = ring(coords[r], o, label, ring_points); !s.ok()) return s;
      poly.rings.push_back(std::move(ring_points));
    }
    p_.polygons.push_back(std::move(poly));
    return Status::success();
  }

  Status lines(const json& coords, const json& props, uint32_t feature) {
    if (!is_label(props))
      return fail(feature, "is a line without an integer \"label\" property (lines only label polygon edges)");
    const int32_t label = props["label"].get<int32_t>();
    uint32_t edge = 0;
    for (const json& line : coords) {
      if (!line.is_array()) return fail(feature, "has a line that is not an array");
      for (size_t i = 0; i + 1 < line.size(); ++i) {
        double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
        if (Status s = position(line[i], feature, x0, y0); !s.ok()) return s;
        if (Status s = position(line[i + 1], feature, x1, y1); !s.ok()) return s;
        const auto a = point_of_.find({x0, y0}), b = point_of_.find({x1, y1});
        ++edge;
        relabels_.push_back({a == point_of_.end() ? 0xffffffffu : a->second, b == point_of_.end() ? 0xfffffffeu : b->second,
                             label, feature, edge});
      }
    }
    return Status::success();
  }

  Status geometry(const json& g, const json& props, uint32_t feature) {
    if (!g.is_object()) return g.is_null() ? Status::success() : fail(feature, "has a geometry that is not an object");
    const std::string type = type_of(g);
    const json coords = g.contains("coordinates") ? g["coordinates"] : json();
    if (type == "Polygon") return polygon(coords, props, feature, ++polygons_in_feature_[feature]);
    if (type == "MultiPolygon") {
      if (!coords.is_array()) return fail(feature, "has MultiPolygon coordinates that are not an array");
      for (const json& c : coords)
        if (Status s = polygon(c, props, feature, ++polygons_in_feature_[feature]); !s.ok()) return s;
      return Status::success();
    }
    if (type == "LineString" || type == "MultiLineString") {
      pending_lines_.push_back({type == "LineString" ? json::array({coords}) : coords, props, feature});
      return Status::success();
    }
    if (type == "GeometryCollection" && g.contains("geometries") && g["geometries"].is_array()) {
      for (const json& c : g["geometries"])
        if (Status s = geometry(c, props, feature); !s.ok()) return s;
      return Status::success();
    }
    return Status(Error::UnsupportedFormat, p_.name + ": feature " + std::to_string(feature) + ": geometry type '" + type +
                                                "' is not supported (Polygon, MultiPolygon; LineString to label edges)");
  }

 public:
  // Lines label the polygons' edges: read after every polygon.
  Status apply_lines() {
    for (const PendingLines& l : pending_lines_)
      if (Status s = lines(l.coords, l.props, l.feature); !s.ok()) return s;
    return Status::success();
  }

 private:
  struct PendingLines {
    json coords, props;
    uint32_t feature;
  };
  Pslg p_;
  std::map<std::pair<double, double>, uint32_t> point_of_;
  std::map<uint64_t, uint32_t> seg_of_;
  std::map<uint32_t, uint32_t> polygons_in_feature_;
  std::vector<Relabel> relabels_;
  std::vector<PendingLines> pending_lines_;
};

}  // namespace

Result<Pslg> parse_geojson(std::string_view data, const std::string& name) {
  return catch_bad_alloc(name, [&]() -> Result<Pslg> {
    json doc = json::parse(data.begin(), data.end(), nullptr, false);
    if (doc.is_discarded()) {
      // Find the line of the error with a second, throwing parse (only on failure).
      try {
        const json again = json::parse(data.begin(), data.end());
        (void)again;
      } catch (const json::parse_error& e) {
        LineCounter lines(data);
        return Status(Error::Parse, name + ":" + std::to_string(lines.at(std::min(e.byte, data.size()))) +
                                        ": not valid JSON (" + e.what() + ")");
      } catch (const json::exception& e) {  // e.g. out_of_range: a number past a double's range
        return Status(Error::Parse, name + ": not valid JSON (" + e.what() + ")");
      }
      return Status(Error::Parse, name + ": not valid JSON");
    }
    GeoJsonBuilder b(name);
    if (doc.is_object() && type_of(doc) == "FeatureCollection") {
      if (!doc.contains("features") || !doc["features"].is_array())
        return Status(Error::Parse, name + ": a FeatureCollection without a features array");
      uint32_t number = 0;
      for (const json& f : doc["features"])
        if (Status s = b.feature(f, ++number); !s.ok()) return s;
    } else if (Status s = b.feature(doc, 1); !s.ok()) {
      return s;
    }
    if (Status s = b.apply_lines(); !s.ok()) return s;
    return b.finish();
  });
}

Result<Pslg> read_pslg(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext != "poly" && ext != "mesh" && ext != "geojson" && ext != "json")
    return Status(Error::UnsupportedFormat, path + ": unknown input format '." + ext +
                                                "' (2D inputs: .poly, .mesh, .geojson or .json)");
  Result<std::string> bytes = read_file_bytes(path);
  if (!bytes.ok()) return bytes.status();
  if (ext == "mesh") return parse_medit2d_pslg(bytes.value(), path);
  if (ext == "geojson" || ext == "json") return parse_geojson(bytes.value(), path);
  std::string node;
  std::string node_path;
  {
    TextScanner head(bytes.value(), path);
    int64_t count = -1;
    if (head.read_int(count) && count == 0) {
      node_path = path.substr(0, path.size() - 5) + ".node";
      Result<std::string> nb = read_file_bytes(node_path);
      if (!nb.ok()) return Status(nb.status().code(), path + ": 0 points, so they are in " + node_path + ": " + nb.status().message());
      node = std::move(nb.value());
    }
  }
  return parse_poly(bytes.value(), path, node, node_path);
}

}  // namespace anitet::mesh2d
