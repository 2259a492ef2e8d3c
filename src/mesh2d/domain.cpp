#include "mesh2d/domain.hpp"

#include <algorithm>
#include <numeric>
#include <string>

#include "mesh2d/conforming.hpp"
#include "predicates/predicates.hpp"

namespace anitet::mesh2d {

namespace {

std::string prefix(const Pslg& p) { return p.name.empty() ? std::string() : p.name + ": "; }

// Even-odd test of q against a polygon's rings (q on no ring's edge); exact crossings of the
// horizontal ray to the right.
bool inside_polygon(const Pslg& p, const PolygonRings& poly, const double q[2]) {
  bool inside = false;
  for (const std::vector<uint32_t>& ring : poly.rings)
    for (size_t i = 0; i < ring.size(); ++i) {
      const double* a = p.point(ring[i]);
      const double* b = p.point(ring[(i + 1) % ring.size()]);
      if ((a[1] > q[1]) == (b[1] > q[1])) continue;
      // The edge crosses the line y = q.y; to the right of q when q is left of the edge going up.
      const int o = a[1] < b[1] ? predicates::orient2d(a, b, q) : predicates::orient2d(b, a, q);
      if (o > 0) inside = !inside;
    }
  return inside;
}

}  // namespace

uint32_t Domain::face_at(const double p[2], uint32_t& hint) const {
  if (hint == kNone || hint >= mesh.num_slots() || !mesh.alive(hint)) {
    hint = 0;
    while (hint < mesh.num_slots() && !mesh.alive(hint)) ++hint;
  }
  Kernel kernel(const_cast<Triangulation&>(mesh));  // locate only reads
  const Location loc = kernel.locate(p, hint);
  if (loc.t == kNone) return kNone;
  if (loc.kind == Location::Outside) return outer_face;
  hint = loc.t;
  if (loc.kind == Location::OnVertex) return kNone;
  if (loc.kind == Location::OnEdge && mesh.constrained(loc.t, loc.k)) return kNone;
  return face[loc.t];
}

Result<Domain> analyse_domain(const Pslg& p) {
  if (Status s = check_pslg(p); !s.ok()) return s;
  Domain d;
  std::vector<uint32_t> all(p.num_points());
  std::iota(all.begin(), all.end(), 0u);
  uint32_t corner = 0;
  Result<Triangulation> dt = delaunay_in_box(p.xy, all, &corner);
  if (!dt.ok()) return Status(dt.status().code(), prefix(p) + dt.status().message());
  d.mesh = std::move(dt.value());
  std::vector<int32_t> tags(p.num_segments());
  std::iota(tags.begin(), tags.end(), 0);
  if (Status s = recover_segments(d.mesh, p.seg, tags); !s.ok()) return Status(s.code(), prefix(p) + s.message());
  const uint32_t faces = label_faces(d.mesh, d.face);
  d.face_inside.assign(faces, 1);
  d.face_attribute.assign(faces, 0.0);
  d.face_max_area.assign(faces, -1.0);
  const uint32_t outer = d.outer_face = d.face[d.mesh.vtri[corner]];
  d.face_inside[outer] = 0;
  uint32_t hint = kNone;
  if (!p.polygons.empty()) {
    // GeoJSON: a face is inside when a point inside one of its triangles is in some polygon.
    std::vector<uint8_t> done(faces, 0);
    done[outer] = 1;
    for (uint32_t t = 0; t < d.mesh.num_slots(); ++t) {
      if (!d.mesh.alive(t) || done[d.face[t]]) continue;
      const uint32_t f = d.face[t];
      done[f] = 1;
      const double* a = d.mesh.point(d.mesh.v(t, 0));
      const double* b = d.mesh.point(d.mesh.v(t, 1));
      const double* c = d.mesh.point(d.mesh.v(t, 2));
      const double q[2] = {(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0};
      d.face_inside[f] = 0;
      for (const PolygonRings& poly : p.polygons)
        if (inside_polygon(p, poly, q)) {
          d.face_inside[f] = 1;
          d.face_attribute[f] = poly.attribute;
          break;
        }
    }
  } else {
    for (size_t h = 0; h < p.num_holes(); ++h) {
      const uint32_t f = d.face_at(&p.holes[2 * h], hint);
      if (f == kNone)
        return Status(Error::InvalidArgument, prefix(p) + describe_hole(p, h) + " lies on a segment or a point");
      if (f == outer)
        return Status(Error::InvalidArgument, prefix(p) + describe_hole(p, h) + " lies outside the domain (beyond its outer boundary)");
      d.face_inside[f] = 0;
    }
    std::vector<int64_t> region_of(faces, -1);
    for (size_t r = 0; r < p.regions.size(); ++r) {
      const double q[2] = {p.regions[r].x, p.regions[r].y};
      const uint32_t f = d.face_at(q, hint);
      if (f == kNone) return Status(Error::InvalidArgument, prefix(p) + describe_region(p, r) + " lies on a segment or a point");
      if (!d.face_inside[f])
        return Status(Error::InvalidArgument, prefix(p) + describe_region(p, r) + " lies outside the domain (or in a hole)");
      if (region_of[f] >= 0 && (p.regions[size_t(region_of[f])].attribute != p.regions[r].attribute ||
                                p.regions[size_t(region_of[f])].max_area != p.regions[r].max_area))
        return Status(Error::InvalidArgument, prefix(p) + describe_region(p, size_t(region_of[f])) + " and " +
                                                  describe_region(p, r) + " lie in the same face with different values");
      region_of[f] = int64_t(r);
      d.face_attribute[f] = p.regions[r].attribute;
      d.face_max_area[f] = p.regions[r].max_area;
    }
  }
  if (std::find(d.face_inside.begin(), d.face_inside.end(), uint8_t(1)) == d.face_inside.end())
    return Status(Error::EmptyInput, prefix(p) + "no domain is left: every face of the segments is a hole or outside");
  // Each segment's faces on its left and right (from seg[2i] to seg[2i+1]). A segment with one
  // face on both sides is on no closed loop: a dangling chain.
  std::vector<uint32_t> side_face(2 * p.num_segments(), kNone);
  for (uint32_t t = 0; t < d.mesh.num_slots(); ++t) {
    if (!d.mesh.alive(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const int32_t s = d.mesh.edge_tag(t, k);
      if (s < 0) continue;
      // t lies left of its edge (a, b): on the segment's left when the piece runs the same way
      // (pieces are collinear with the segment: the sign of the dot product is robust).
      const double* pa = d.mesh.point(d.mesh.edge_a(t, k));
      const double* pb = d.mesh.point(d.mesh.edge_b(t, k));
      const double* qa = p.point(p.seg[2 * size_t(s)]);
      const double* qb = p.point(p.seg[2 * size_t(s) + 1]);
      const double along = (pb[0] - pa[0]) * (qb[0] - qa[0]) + (pb[1] - pa[1]) * (qb[1] - qa[1]);
      side_face[2 * size_t(s) + (along > 0 ? 0 : 1)] = d.face[t];
    }
  }
  d.sides.assign(p.num_segments(), 0);
  for (size_t s = 0; s < p.num_segments(); ++s) {
    if (side_face[2 * s] == side_face[2 * s + 1])
      return Status(Error::OpenBoundary, prefix(p) + "open loop: " + describe_segment(p, s) +
                                             " has the same face on both sides: it closes no loop");
    if (side_face[2 * s] != kNone && d.face_inside[side_face[2 * s]]) d.sides[s] |= 1;
    if (side_face[2 * s + 1] != kNone && d.face_inside[side_face[2 * s + 1]]) d.sides[s] |= 2;
  }
  for (size_t s = 0; s < p.num_segments(); ++s)
    if (!d.sides[s])
      return Status(Error::InvalidArgument, prefix(p) + describe_segment(p, s) +
                                                " has no domain on either side (it lies in a hole or outside the outer boundary)");
  std::vector<uint8_t> on_segment(p.num_points(), 0);
  for (uint32_t v : p.seg) on_segment[v] = 1;
  for (uint32_t v = 0; v < p.num_points(); ++v) {
    if (on_segment[v]) continue;
    const uint32_t t = d.mesh.vtri[v];
    if (t == kNone || !d.face_inside[d.face[t]])
      return Status(Error::InvalidArgument, prefix(p) + describe_point(p, v) + " is on no segment and lies outside the domain");
    d.free_points.push_back(v);
  }
  return d;
}

}  // namespace anitet::mesh2d
