#include "layers/slide_patches.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <string>
#include <unordered_map>

#include "core/bvh.hpp"
#include "core/tet_mesh.hpp"
#include "layers/geometry.hpp"
#include "layers/layer_builder.hpp"
#include "layers/planar_cdt.hpp"
#include "predicates/predicates.hpp"

namespace anitet {

namespace {

using layers::point_text;
constexpr uint32_t kNone = TetMesh::kNone;
enum Kind : uint8_t { kOther = 0, kWall = 1, kSlide = 2 };

double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double dist3(const double* a, const double* b) {
  const double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  return std::sqrt(dot3(e, e));
}
uint64_t edge_key(uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | b; }

// A planar face of a slide patch: its triangles are coplanar and connected across their edges.
// axis0, axis1: the coordinates that show its triangles counter-clockwise; flat_axis: the axis
// its plane is normal to when every vertex has the same coordinate flat_value there (-1: none).
struct Piece {
  int32_t label = 0;
  double m[3] = {0, 0, 0};
  int axis0 = 0, axis1 = 1, flat_axis = -1;
  double flat_value = 0.0;
  std::vector<uint32_t> triangles;
};

// A junction vertex's column: direction, the factor on h0 r^i (lowered where needed), the
// vertex of the crease edge it runs along (kNone: it slides in one plane), its points.
struct Column {
  uint32_t root = 0;
  double d[3] = {0, 0, 0};
  double factor = 1.0;  // 1 / (d . wall normal), capped: the layers' normal heights kept
  double scale = 1.0;   // the reduction
  uint32_t along = kNone;
  uint32_t first_point = 0;  // id of A_1 in the new surface (A_i = first_point + i - 1)
};

struct BandTriangle {
  uint32_t v[3];
  uint32_t piece;
};

// An edge where a wall meets a slide patch: a -> b as in the slide triangle (the patch on its left).
struct JunctionEdge {
  uint32_t a, b, piece;
};

class SlideBuilder {
 public:
  SlideBuilder(const SurfaceMesh& s, const BoundaryLayerOptions& bl)
      : s_(s), bl_(bl), n_(boundary_layer_count(bl)) {}

  Result<SlideSurface> run() {
    if (Status st = classify(); !st.ok()) return st;
    out_.surface = s_;
    out_.surface.line.clear();
    out_.column_next.assign(s_.num_vertices(), kNone);
    if (columns_.empty()) return std::move(out_);
    find_pieces();
    if (Status st = plan_columns(); !st.ok()) return st;
    grade_columns();
    place_points();
    if (Status st = band_triangles(); !st.ok()) return st;
    affected_.assign(s_.num_triangles(), 0);
    std::vector<uint32_t> new_tri;
    std::vector<int32_t> new_label;
    for (uint32_t p = 0; p < pieces_.size(); ++p)
      if (has_band_[p])
        if (Status st = retriangulate(p, new_tri, new_label); !st.ok()) return st;
    assemble(new_tri, new_label);
    return std::move(out_);
  }

 private:
  // ---- the input's topology, the triangles' kinds, the junction vertices ----
  Status classify() {
    for (int32_t w : bl_.wall_patches)
      if (std::find(bl_.slide_patches.begin(), bl_.slide_patches.end(), w) != bl_.slide_patches.end())
        return Status(Error::InvalidArgument, "boundary layer: patch " + std::to_string(w) +
                                                  " is given both as a wall and as a slide patch");
    const size_t nv = s_.num_vertices(), nt = s_.num_triangles();
    kind_.assign(nt, kOther);
    auto listed = [](const std::vector<int32_t>& v, int32_t x) { return std::find(v.begin(), v.end(), x) != v.end(); };
    for (size_t t = 0; t < nt; ++t)
      kind_[t] = listed(bl_.wall_patches, s_.patch[t]) ? kWall : listed(bl_.slide_patches, s_.patch[t]) ? kSlide : kOther;
    star_start_.assign(nv + 1, 0);
    for (uint32_t v : s_.tri) ++star_start_[v + 1];
    std::partial_sum(star_start_.begin(), star_start_.end(), star_start_.begin());
    star_.resize(s_.tri.size());
    std::vector<uint32_t> fill(star_start_.begin(), star_start_.end() - 1);
    for (uint32_t t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = s_.tri[3 * t + k];
        star_[fill[v]++] = t;
        directed_[edge_key(v, s_.tri[3 * t + (k + 1) % 3])] = t;
      }
    column_of_.assign(nv, kNone);
    for (uint32_t v = 0; v < nv; ++v) {
      bool wall = false, slide = false;
      int32_t other = 0;
      bool has_other = false;
      for (uint32_t i = star_start_[v]; i < star_start_[v + 1]; ++i) {
        const uint32_t t = star_[i];
        wall |= kind_[t] == kWall;
        slide |= kind_[t] == kSlide;
        if (kind_[t] == kOther && !has_other) {
          has_other = true;
          other = s_.patch[t];
        }
      }
      if (wall && has_other)
        return Status(Error::InvalidArgument,
                      "boundary layer: vertex " + std::to_string(v) + " at " + point_text(s_.point(v)) +
                          " is on a wall patch and on patch " + std::to_string(other) +
                          ", which is neither a wall nor a slide patch: the layers can slide along it if it is "
                          "one (slide patches, --bl-slide-patches " + std::to_string(other) + ")");
      if (wall && slide) {
        column_of_[v] = uint32_t(columns_.size());
        columns_.push_back(Column{});
        columns_.back().root = v;
      }
    }
    return Status::success();
  }

  uint32_t twin(uint32_t a, uint32_t b) const {
    auto it = directed_.find(edge_key(b, a));
    return it == directed_.end() ? kNone : it->second;
  }
  void normal_of(uint32_t t, double n[3]) const {
    layers::unit_normal(s_.point(s_.tri[3 * t]), s_.point(s_.tri[3 * t + 1]), s_.point(s_.tri[3 * t + 2]), n);
  }

  // ---- planar faces of the slide patches ----
  uint32_t find(uint32_t t) {
    while (parent_[t] != t) t = parent_[t] = parent_[parent_[t]];
    return t;
  }
  bool coplanar(uint32_t t, uint32_t u) const {
    double nt[3], nu[3];
    normal_of(t, nt);
    normal_of(u, nu);
    if (dot3(nt, nu) < 1.0 - 1e-10) return false;
    double len = 0.0;
    for (uint32_t x : {t, u})
      for (int k = 0; k < 3; ++k)
        len = std::max(len, dist3(s_.point(s_.tri[3 * x + k]), s_.point(s_.tri[3 * x + (k + 1) % 3])));
    const double* a = s_.point(s_.tri[3 * t]);
    for (int k = 0; k < 3; ++k) {
      const double* q = s_.point(s_.tri[3 * u + k]);
      const double e[3] = {q[0] - a[0], q[1] - a[1], q[2] - a[2]};
      if (std::abs(dot3(e, nt)) > 1e-9 * len) return false;
    }
    return true;
  }
  void find_pieces() {
    const size_t nt = s_.num_triangles();
    parent_.resize(nt);
    std::iota(parent_.begin(), parent_.end(), 0u);
    for (uint32_t t = 0; t < nt; ++t) {
      if (kind_[t] != kSlide) continue;
      for (int k = 0; k < 3; ++k) {
        const uint32_t u = twin(s_.tri[3 * t + k], s_.tri[3 * t + (k + 1) % 3]);
        if (u == kNone || u < t || kind_[u] != kSlide || s_.patch[u] != s_.patch[t] || !coplanar(t, u)) continue;
        parent_[find(u)] = find(t);
      }
    }
    piece_.assign(nt, kNone);
    std::vector<uint32_t> index(nt, kNone);
    for (uint32_t t = 0; t < nt; ++t) {
      if (kind_[t] != kSlide) continue;
      const uint32_t r = find(t);
      if (index[r] == kNone) {
        index[r] = uint32_t(pieces_.size());
        pieces_.emplace_back();
        pieces_.back().label = s_.patch[t];
      }
      piece_[t] = index[r];
      Piece& p = pieces_[index[r]];
      p.triangles.push_back(t);
      double n[3];
      const double area = layers::unit_normal(s_.point(s_.tri[3 * t]), s_.point(s_.tri[3 * t + 1]),
                                              s_.point(s_.tri[3 * t + 2]), n);
      for (int k = 0; k < 3; ++k) p.m[k] += area * n[k];
    }
    for (Piece& p : pieces_) {
      const double len = std::sqrt(dot3(p.m, p.m));
      for (double& x : p.m) x /= len;
      int k = 0;
      for (int j = 1; j < 3; ++j)
        if (std::abs(p.m[j]) > std::abs(p.m[k])) k = j;
      p.axis0 = p.m[k] > 0 ? (k + 1) % 3 : (k + 2) % 3;
      p.axis1 = p.m[k] > 0 ? (k + 2) % 3 : (k + 1) % 3;
      const double value = s_.point(s_.tri[3 * p.triangles[0]])[k];
      bool flat = true;
      for (uint32_t t : p.triangles)
        for (int j = 0; j < 3; ++j) flat = flat && s_.point(s_.tri[3 * t + j])[k] == value;
      if (flat) {
        p.flat_axis = k;
        p.flat_value = value;
      }
    }
    has_band_.assign(pieces_.size(), 0);
  }

  // ---- the columns: direction, length, reductions ----
  Status plan_columns() {
    bvh_.build(s_.xyz.data(), s_.tri.data(), s_.num_triangles());
    double total = 0.0;
    for (int i = 0; i < n_; ++i) total += bl_.first_height * std::pow(bl_.growth, i);
    for (Column& c : columns_) {
      const uint32_t a = c.root;
      double wall_n[3] = {0, 0, 0};
      std::vector<uint32_t> pieces, creases;
      for (uint32_t i = star_start_[a]; i < star_start_[a + 1]; ++i) {
        const uint32_t t = star_[i];
        int k = 0;
        while (s_.tri[3 * t + k] != a) ++k;
        const uint32_t b = s_.tri[3 * t + (k + 1) % 3], e = s_.tri[3 * t + (k + 2) % 3];
        if (kind_[t] == kWall) {
          double n[3];
          normal_of(t, n);
          const double angle = layers::corner_angle(s_.point(a), s_.point(b), s_.point(e));
          for (int j = 0; j < 3; ++j) wall_n[j] -= angle * n[j];  // into the domain
          continue;
        }
        pieces.push_back(piece_[t]);
        for (uint32_t x : {b, e}) {  // the triangles across t's edges at a
          const uint32_t u = x == b ? twin(a, b) : twin(e, a);
          if (u != kNone && kind_[u] == kSlide && piece_[u] != piece_[t]) creases.push_back(x);
        }
      }
      std::sort(pieces.begin(), pieces.end());
      pieces.erase(std::unique(pieces.begin(), pieces.end()), pieces.end());
      std::sort(creases.begin(), creases.end());
      creases.erase(std::unique(creases.begin(), creases.end()), creases.end());
      const double len = std::sqrt(dot3(wall_n, wall_n));
      for (double& x : wall_n) x /= len;
      const std::string where = "vertex " + std::to_string(a) + " at " + point_text(s_.point(a));
      if (creases.size() > 1 || (creases.empty() && pieces.size() > 1))
        return Status(Error::NotImplemented,
                      "boundary layer: the column of " + where + " would slide on " + std::to_string(pieces.size()) +
                          " faces of slide patches that do not meet along one edge there (a slide patch must be planar "
                          "where the layers slide on it, or planar faces meeting at edges)");
      if (creases.empty()) {
        const double* m = pieces_[pieces[0]].m;
        const double along = dot3(wall_n, m);
        for (int j = 0; j < 3; ++j) c.d[j] = wall_n[j] - along * m[j];
      } else {
        c.along = creases[0];
        for (int j = 0; j < 3; ++j) c.d[j] = s_.point(c.along)[j] - s_.point(a)[j];
      }
      const double dl = std::sqrt(dot3(c.d, c.d));
      for (double& x : c.d) x /= dl;
      const double cosine = dot3(c.d, wall_n);
      if (!(cosine >= 0.3))
        return Status(Error::NotImplemented, "boundary layer: at " + where +
                                                 " the wall meets slide patch " + std::to_string(pieces_[pieces[0]].label) +
                                                 " at a grazing angle: its column cannot slide there");
      c.factor = 1.0 / std::max(cosine, 0.5);
      const double length = total * c.factor;
      const double free = clearance(a, c.d, length / bl_.gap_share);
      c.scale = std::min(1.0, bl_.gap_share * free / length);
      if (c.along != kNone) c.scale = std::min(c.scale, 0.5 * dist3(s_.point(a), s_.point(c.along)) / length);
      for (uint32_t p : pieces) has_band_[p] = 1;
    }
    return Status::success();
  }

  // The distance from vertex a along d to the surface (triangles touching a's neighbours skipped),
  // looked for up to max_dist; +inf when free.
  double clearance(uint32_t a, const double d[3], double max_dist) const {
    std::vector<uint32_t> ring;
    for (uint32_t i = star_start_[a]; i < star_start_[a + 1]; ++i)
      ring.insert(ring.end(), &s_.tri[3 * star_[i]], &s_.tri[3 * star_[i]] + 3);
    std::sort(ring.begin(), ring.end());
    const double* p = s_.point(a);
    Box3 box;
    for (int k = 0; k < 3; ++k) {
      box.lo[k] = std::min(p[k], p[k] + max_dist * d[k]);
      box.hi[k] = std::max(p[k], p[k] + max_dist * d[k]);
    }
    double best = HUGE_VAL;
    bvh_.query(box, [&](size_t t) {
      const uint32_t* v = &s_.tri[3 * t];
      for (int k = 0; k < 3; ++k)
        if (std::binary_search(ring.begin(), ring.end(), v[k])) return true;
      best = std::min(best, layers::ray_triangle(p, d, s_.point(v[0]), s_.point(v[1]), s_.point(v[2])));
      return true;
    });
    return best;
  }

  void grade_columns() {
    // Neighbouring columns' reductions differ by at most the gradation factor (only lowered).
    std::vector<std::pair<uint32_t, uint32_t>> edges;
    for (uint32_t t = 0; t < s_.num_triangles(); ++t)
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = s_.tri[3 * t + k], b = s_.tri[3 * t + (k + 1) % 3];
        if (a < b && column_of_[a] != kNone && column_of_[b] != kNone) edges.emplace_back(column_of_[a], column_of_[b]);
      }
    const double g = std::max(bl_.gradation, 1.0);
    for (int pass = 0; pass < 100; ++pass) {
      bool changed = false;
      for (const auto& [u, v] : edges) {
        const double su = columns_[u].scale, sv = columns_[v].scale;
        if (su > g * sv) columns_[u].scale = g * sv, changed = true;
        if (sv > g * su) columns_[v].scale = g * su, changed = true;
      }
      if (!changed) break;
    }
    for (const Column& c : columns_) out_.reduced_columns += c.scale < 0.9 ? 1 : 0;
    out_.junction_vertices = columns_.size();
  }

  void place_points() {
    // Column-major, in the junction vertices' order: at every layer the column pushed first
    // (the smaller root id) has the smaller vertex id, as stage 1's junction pushes go.
    SurfaceMesh& s = out_.surface;
    for (Column& c : columns_) {
      c.first_point = uint32_t(s.num_vertices());
      const double* a = s_.point(c.root);
      std::vector<int> flat_axes;
      std::vector<double> flat_values;
      for (uint32_t i = star_start_[c.root]; i < star_start_[c.root + 1]; ++i) {
        const uint32_t t = star_[i];
        if (kind_[t] != kSlide || pieces_[piece_[t]].flat_axis < 0) continue;
        flat_axes.push_back(pieces_[piece_[t]].flat_axis);
        flat_values.push_back(pieces_[piece_[t]].flat_value);
      }
      double up = 0.0;
      for (int i = 0; i < n_; ++i) {
        up += bl_.first_height * std::pow(bl_.growth, i) * c.factor * c.scale;
        double p[3];
        for (int k = 0; k < 3; ++k) p[k] = a[k] + up * c.d[k];
        for (size_t j = 0; j < flat_axes.size(); ++j) p[flat_axes[j]] = flat_values[j];  // exactly in the plane
        s.add_vertex(p[0], p[1], p[2]);
      }
      uint32_t prev = c.root;
      for (int i = 0; i < n_; ++i) {
        out_.column_next.push_back(kNone);
        out_.column_next[prev] = c.first_point + uint32_t(i);
        prev = c.first_point + uint32_t(i);
      }
    }
  }

  // Column point i (0: the junction vertex itself) of junction vertex v.
  uint32_t level(uint32_t v, int i) const {
    return i == 0 ? v : columns_[column_of_[v]].first_point + uint32_t(i - 1);
  }
  const double* point(uint32_t v) const { return out_.surface.point(v); }
  int orient(const Piece& p, uint32_t a, uint32_t b, uint32_t c) const {
    const double pa[2] = {point(a)[p.axis0], point(a)[p.axis1]}, pb[2] = {point(b)[p.axis0], point(b)[p.axis1]},
                 pc[2] = {point(c)[p.axis0], point(c)[p.axis1]};
    return predicates::orient2d(pa, pb, pc);
  }

  // ---- the prisms' side faces ----
  Status band_triangles() {
    for (uint32_t w = 0; w < s_.num_triangles(); ++w) {
      if (kind_[w] != kWall) continue;
      for (int k = 0; k < 3; ++k) {
        const uint32_t u = twin(s_.tri[3 * w + k], s_.tri[3 * w + (k + 1) % 3]);
        if (u == kNone || kind_[u] != kSlide) continue;
        // In the slide triangle the edge runs a -> b, the patch on its left.
        const uint32_t a = s_.tri[3 * w + (k + 1) % 3], b = s_.tri[3 * w + k];
        const uint32_t p = piece_[u];
        junction_edges_.push_back({a, b, p});
        for (int i = 0; i < n_; ++i) {
          const uint32_t a0 = level(a, i), b0 = level(b, i), a1 = level(a, i + 1), b1 = level(b, i + 1);
          // The diagonal from the top of the column pushed first (smaller id) to the other's foot.
          band_.push_back(a < b ? BandTriangle{{a0, b0, a1}, p} : BandTriangle{{a0, b0, b1}, p});
          band_.push_back(a < b ? BandTriangle{{a1, b0, b1}, p} : BandTriangle{{a0, b1, a1}, p});
        }
      }
    }
    for (const BandTriangle& b : band_)
      if (orient(pieces_[b.piece], b.v[0], b.v[1], b.v[2]) <= 0)
        return Status(Error::NotImplemented, "boundary layer: the layers' columns fold on slide patch " +
                                                 std::to_string(pieces_[b.piece].label) + " near " +
                                                 point_text(point(b.v[0])) + " (the junction turns too sharply there)");
    return Status::success();
  }

  Status retriangulate(uint32_t p, std::vector<uint32_t>& new_tri, std::vector<int32_t>& new_label);
  bool covered_by_band(const Piece& piece, uint32_t p, const std::vector<BandTriangle>& quads,
                       const std::vector<std::pair<uint32_t, uint32_t>>& tops, bool* inside) const;
  void assemble(const std::vector<uint32_t>& new_tri, const std::vector<int32_t>& new_label);

  const SurfaceMesh& s_;
  const BoundaryLayerOptions& bl_;
  const int n_;
  SlideSurface out_;
  std::vector<uint8_t> kind_;
  std::vector<uint32_t> star_start_, star_;
  std::unordered_map<uint64_t, uint32_t> directed_;
  std::vector<uint32_t> parent_, piece_;
  std::vector<Piece> pieces_;
  std::vector<uint8_t> has_band_;
  std::vector<Column> columns_;
  std::vector<uint32_t> column_of_;
  TriangleBVH bvh_;
  std::vector<BandTriangle> band_;
  std::vector<JunctionEdge> junction_edges_;
  std::vector<uint8_t> affected_;      // 1 per input triangle: replaced
  std::map<int32_t, size_t> dropped_;  // per slide patch: vertices left out
};

// Whether vertex p of the piece lies in the closed band (`quads`: the band's outline per
// junction edge, as triangles) or near its top (closer to a top edge than 0.35 of its length).
bool SlideBuilder::covered_by_band(const Piece& piece, uint32_t p, const std::vector<BandTriangle>& quads,
                                   const std::vector<std::pair<uint32_t, uint32_t>>& tops, bool* inside) const {
  *inside = false;
  for (const BandTriangle& q : quads)
    if (orient(piece, q.v[0], q.v[1], p) >= 0 && orient(piece, q.v[1], q.v[2], p) >= 0 &&
        orient(piece, q.v[2], q.v[0], p) >= 0) {
      *inside = true;
      return true;
    }
  const double* x = point(p);
  for (const auto& [a, b] : tops) {
    const double *pa = point(a), *pb = point(b);
    const double e[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
    const double w[3] = {x[0] - pa[0], x[1] - pa[1], x[2] - pa[2]};
    const double len2 = dot3(e, e);
    const double t = std::clamp(len2 > 0 ? dot3(w, e) / len2 : 0.0, 0.0, 1.0);
    const double r[3] = {w[0] - t * e[0], w[1] - t * e[1], w[2] - t * e[2]};
    if (dot3(r, r) < 0.35 * 0.35 * len2) return true;
  }
  return false;
}

Status SlideBuilder::retriangulate(uint32_t p, std::vector<uint32_t>& new_tri, std::vector<int32_t>& new_label) {
  const Piece& piece = pieces_[p];
  // The band's outline per junction edge a -> b: the quad a_0 b_0 b_n a_n (columns are straight),
  // as the four triangles of both its diagonals (covers it even when it is not convex); its tops.
  std::vector<BandTriangle> quads;
  std::vector<std::pair<uint32_t, uint32_t>> tops;
  for (const JunctionEdge& e : junction_edges_) {
    if (e.piece != p) continue;
    const uint32_t a = e.a, b = e.b, an = level(a, n_), bn = level(b, n_);
    quads.push_back({{a, b, bn}, p});
    quads.push_back({{a, bn, an}, p});
    quads.push_back({{a, b, an}, p});
    quads.push_back({{b, bn, an}, p});
    tops.emplace_back(an, bn);
  }
  auto in_piece = [&](uint32_t t) { return t != kNone && kind_[t] == kSlide && piece_[t] == p; };
  auto free_vertex = [&](uint32_t v) {  // inside the piece: every triangle around it in it
    if (column_of_[v] != kNone) return false;
    for (uint32_t i = star_start_[v]; i < star_start_[v + 1]; ++i)
      if (!in_piece(star_[i])) return false;
    return true;
  };
  // Affected: the piece's triangles at a junction vertex, those the band overlaps, and the
  // triangles around a vertex the band covers or nearly touches (that vertex is left out).
  std::vector<uint32_t> work;
  auto affect = [&](uint32_t t) {
    if (affected_[t]) return;
    affected_[t] = 1;
    work.push_back(t);
  };
  for (uint32_t t : piece.triangles) {
    bool hit = false;
    for (int k = 0; k < 3 && !hit; ++k) hit = column_of_[s_.tri[3 * t + k]] != kNone;
    for (size_t q = 0; q < quads.size() && !hit; q += 2) {
      // Separating edges, exact: some edge of one triangle has the other on or past its far side.
      auto apart = [&](const uint32_t* x, const uint32_t* y) {
        for (int k = 0; k < 3; ++k) {
          const int inner = orient(piece, x[k], x[(k + 1) % 3], x[(k + 2) % 3]);
          bool all = true;
          for (int j = 0; j < 3 && all; ++j) all = orient(piece, x[k], x[(k + 1) % 3], y[j]) * inner <= 0;
          if (all) return true;
        }
        return false;
      };
      for (size_t h = q; h < q + 2 && !hit; ++h)
        hit = !apart(&s_.tri[3 * t], quads[h].v) && !apart(quads[h].v, &s_.tri[3 * t]);
    }
    if (hit) affect(t);
  }
  std::vector<uint8_t> seen(s_.num_vertices(), 0), dropped(s_.num_vertices(), 0);
  for (size_t w = 0; w < work.size(); ++w) {
    const uint32_t t = work[w];
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = s_.tri[3 * t + k];
      if (seen[v]) continue;
      seen[v] = 1;
      if (column_of_[v] != kNone) continue;
      bool inside = false;
      if (!covered_by_band(piece, v, quads, tops, &inside)) continue;
      if (!free_vertex(v)) {
        if (!inside) continue;  // near the band: kept, its triangles poorer
        return Status(Error::NotImplemented,
                      "boundary layer: the layers sliding on patch " + std::to_string(piece.label) + " cover its vertex " +
                          std::to_string(v) + " at " + point_text(s_.point(v)) +
                          ", on its edge with another patch or face: fewer or thinner layers, or finer triangles there");
      }
      dropped[v] = 1;
      for (uint32_t i = star_start_[v]; i < star_start_[v + 1]; ++i) affect(star_[i]);
    }
  }
  // The region left: the affected triangles' outline (junction edges aside; an edge along which
  // a column runs starts at the column's top) and the band's tops.
  std::vector<std::pair<uint32_t, uint32_t>> segments;
  double area_before = 0.0, area_after = 0.0;
  auto area = [&](uint32_t a, uint32_t b, uint32_t c) {
    double n[3];
    return 0.5 * layers::unit_normal(point(a), point(b), point(c), n);
  };
  for (uint32_t t : work) {
    area_before += area(s_.tri[3 * t], s_.tri[3 * t + 1], s_.tri[3 * t + 2]);
    for (int k = 0; k < 3; ++k) {
      uint32_t a = s_.tri[3 * t + k], b = s_.tri[3 * t + (k + 1) % 3];
      const uint32_t u = twin(a, b);
      if ((u != kNone && affected_[u] && piece_[u] == p) || (u != kNone && kind_[u] == kWall)) continue;
      if (column_of_[a] != kNone && columns_[column_of_[a]].along == b) a = level(a, n_);
      if (column_of_[b] != kNone && columns_[column_of_[b]].along == a) b = level(b, n_);
      segments.emplace_back(a, b);
    }
  }
  segments.insert(segments.end(), tops.begin(), tops.end());
  std::vector<uint32_t> ids;
  for (const auto& [a, b] : segments) ids.insert(ids.end(), {a, b});
  for (uint32_t t : work)
    for (int k = 0; k < 3; ++k)
      if (!dropped[s_.tri[3 * t + k]] && column_of_[s_.tri[3 * t + k]] == kNone) ids.push_back(s_.tri[3 * t + k]);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  auto local = [&](uint32_t v) { return uint32_t(std::lower_bound(ids.begin(), ids.end(), v) - ids.begin()); };
  std::vector<double> xy;
  for (uint32_t v : ids) xy.insert(xy.end(), {point(v)[piece.axis0], point(v)[piece.axis1]});
  std::vector<std::pair<uint32_t, uint32_t>> local_segments;
  for (const auto& [a, b] : segments) local_segments.emplace_back(local(a), local(b));
  Result<std::vector<uint32_t>> tri = layers::triangulate_region(xy, local_segments);
  if (!tri.ok())
    return Status(Error::Internal, "boundary layer: slide patch " + std::to_string(piece.label) +
                                       ": re-triangulating it around the layers near " +
                                       point_text(point(segments[0].first)) + " failed: " + tri.status().message());
  const std::vector<uint32_t>& local_tri = tri.value();
  for (size_t i = 0; i < local_tri.size(); i += 3) {
    const uint32_t a = ids[local_tri[i]], b = ids[local_tri[i + 1]], c = ids[local_tri[i + 2]];
    new_tri.insert(new_tri.end(), {a, b, c});
    new_label.push_back(piece.label);
    area_after += area(a, b, c);
  }
  for (const BandTriangle& b : band_)
    if (b.piece == p) area_after += area(b.v[0], b.v[1], b.v[2]);
  if (!(std::abs(area_after - area_before) <= 1e-9 * area_before))
    return Status(Error::Internal, "boundary layer: slide patch " + std::to_string(piece.label) +
                                       ": its new triangles' area differs from the old ones' (" +
                                       std::to_string(area_after) + " against " + std::to_string(area_before) + ")");
  dropped_[piece.label] += size_t(std::count(dropped.begin(), dropped.end(), 1));
  return Status::success();
}

void SlideBuilder::assemble(const std::vector<uint32_t>& new_tri, const std::vector<int32_t>& new_label) {
  SurfaceMesh& s = out_.surface;  // (its vertices: the input's, then the columns' points)
  s.tri.clear();
  s.patch.clear();
  std::map<int32_t, SlidePatchChange> changes;
  for (const Piece& p : pieces_)
    if (has_band_[&p - pieces_.data()]) changes[p.label].label = p.label;
  for (uint32_t t = 0; t < s_.num_triangles(); ++t) {
    if (changes.count(s_.patch[t])) ++changes[s_.patch[t]].triangles_before;
    if (!affected_[t]) s.add_triangle(s_.tri[3 * t], s_.tri[3 * t + 1], s_.tri[3 * t + 2], s_.patch[t]);
  }
  for (const BandTriangle& b : band_) {
    s.add_triangle(b.v[0], b.v[1], b.v[2], pieces_[b.piece].label);
    ++changes[pieces_[b.piece].label].band_triangles;
  }
  for (size_t i = 0; i < new_label.size(); ++i) s.add_triangle(new_tri[3 * i], new_tri[3 * i + 1], new_tri[3 * i + 2], new_label[i]);
  for (int32_t label : s.patch)
    if (changes.count(label)) ++changes[label].triangles_after;
  for (auto& [label, c] : changes) {
    c.dropped_vertices = dropped_[label];
    out_.changes.push_back(c);
  }
}

}  // namespace

Result<SlideSurface> slide_boundary_layer(const SurfaceMesh& surface, const BoundaryLayerOptions& bl) {
  if (!(bl.first_height > 0.0) || !(bl.growth >= 1.0) || !(bl.gap_share > 0.0 && bl.gap_share < 0.5) ||
      boundary_layer_count(bl) < 1)
    return Status(Error::InvalidArgument, "boundary layer: first_height > 0, growth >= 1, gap_share in (0, 0.5) and "
                                          "at least one layer are needed to slide the layers along patches");
  return SlideBuilder(surface, bl).run();
}

SlideReport slide_report(SlideSurface&& slid) {
  return SlideReport{std::move(slid.surface), std::move(slid.changes), slid.junction_vertices, slid.reduced_columns};
}

}  // namespace anitet
