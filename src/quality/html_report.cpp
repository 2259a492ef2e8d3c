// The HTML quality report (html_report.hpp): one pass over the tets bins the quality measures and
// every dihedral angle, one pass over the unique edges bins their lengths, and one pass collects
// the cross-sections of the tets crossed by the three cut planes. The page is plain HTML with
// inline CSS and SVG; the element classes (hist/bar-all/bar-bnd, cut/polygon) are what
// tests/e2e/report_check.py counts.
#include "quality/html_report.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <tbb/parallel_for.h>

#include "core/buckets.hpp"
#include "core/metric_measures.hpp"
#include "quality/parallel_for.hpp"
#include "quality/report_detail.hpp"
#include "quality/tet_measures.hpp"

namespace anitet {

namespace {

using quality_detail::TetData;

constexpr int kClasses = 10;  // colour classes of the radius ratio in the cut views
const char* const kClassColour[kClasses] = {"#7f0000", "#b30000", "#e34a33", "#fc8d59", "#fdbb84",
                                            "#fee08b", "#d9ef8b", "#a6d96a", "#66bd63", "#1a9850"};

// f(block, begin, end) over [0, n) in a fixed number of blocks (deterministic merging).
template <class F>
size_t for_blocks(size_t n, bool parallel, F&& f) {
  const size_t blocks = std::clamp<size_t>(n / 16384, 1, 64);
  if (!parallel || blocks == 1) {
    for (size_t b = 0; b < blocks; ++b) f(b, n * b / blocks, n * (b + 1) / blocks);
  } else {
    tbb::parallel_for(size_t(0), blocks, [&](size_t b) { f(b, n * b / blocks, n * (b + 1) / blocks); });
  }
  return blocks;
}

// Bin of x in [lo, hi] split in `bins` equal bins: a value on an edge goes up, hi in the last.
size_t bin_of(double x, double lo, double hi, int bins) {
  const double nb = double(bins);
  const double t = hi > lo ? std::clamp((x - lo) / (hi - lo), 0.0, 1.0) : 0.0;
  long b = static_cast<long>(t * nb);
  if (b > 0 && t < double(b) / nb) --b;
  if (b + 1 < bins && t >= double(b + 1) / nb) ++b;
  return size_t(std::clamp<long>(b, 0, bins - 1));
}

std::string num(const char* format, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, x);
  return buf;
}

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string percent(size_t part, size_t whole) {
  return whole == 0 ? std::string("-") : num("%.2f%%", 100.0 * double(part) / double(whole));
}

// Histogram pair: all items and the ones touching the boundary.
struct Hist {
  std::vector<size_t> all, bnd;
  explicit Hist(int bins = 1) : all(size_t(bins), 0), bnd(size_t(bins), 0) {}
  void add(const Hist& o) {
    for (size_t i = 0; i < all.size(); ++i) {
      all[i] += o.all[i];
      bnd[i] += o.bnd[i];
    }
  }
};

// Per-block tallies of the tet pass.
struct TetTally {
  Hist rr, mr, dihedral;
  size_t boundary_tets = 0;
  double max_dihedral_key[2] = {0.0, 0.0};  // interior, boundary (tet_measures_keyed's keys)
  size_t lt5[2] = {0, 0}, lt10[2] = {0, 0};
};

// A cross-section of a tet by a cut plane, in the plane's 2D coordinates.
struct Poly {
  float u[4], v[4];
  uint8_t n = 0;
  uint8_t cls = 0;
};

struct Bbox {
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
};

// The SVG bar chart of a histogram pair over [lo, hi].
std::string hist_svg(const std::string& name, const std::string& title, const std::string& xlabel,
                     const Hist& h, double lo, double hi, const char* tick_format, int tick_every) {
  const int bins = int(h.all.size());
  const double W = 540, H = 270, ml = 62, mr = 22, mt = 28, mb = 44;
  const double pw = W - ml - mr, ph = H - mt - mb, bw = pw / bins;
  size_t top = 1, total = 0, total_bnd = 0;
  for (int i = 0; i < bins; ++i) {
    top = std::max(top, h.all[size_t(i)]);
    total += h.all[size_t(i)];
    total_bnd += h.bnd[size_t(i)];
  }
  std::ostringstream s;
  s << "<svg class=\"hist\" data-name=\"" << name << "\" data-bins=\"" << bins << "\" data-total=\"" << total
    << "\" data-total-boundary=\"" << total_bnd << "\" width=\"" << W << "\" height=\"" << H
    << "\" viewBox=\"0 0 " << W << " " << H << "\" xmlns=\"http://www.w3.org/2000/svg\">\n";
  s << "<text x=\"" << W / 2 << "\" y=\"17\" class=\"title\">" << escape(title) << "</text>\n";
  // Axes and ticks.
  s << "<line class=\"axis\" x1=\"" << ml << "\" y1=\"" << mt + ph << "\" x2=\"" << ml + pw << "\" y2=\""
    << mt + ph << "\"/><line class=\"axis\" x1=\"" << ml << "\" y1=\"" << mt << "\" x2=\"" << ml
    << "\" y2=\"" << mt + ph << "\"/>\n";
  for (int k = 0; k <= 4; ++k) {
    const double y = mt + ph - ph * k / 4.0;
    s << "<line class=\"grid\" x1=\"" << ml << "\" y1=\"" << y << "\" x2=\"" << ml + pw << "\" y2=\"" << y
      << "\"/><text class=\"ytick\" x=\"" << ml - 4 << "\" y=\"" << y + 4 << "\">"
      << size_t(std::llround(double(top) * k / 4.0)) << "</text>\n";
  }
  for (int i = 0; i <= bins; i += tick_every) {
    const double x = ml + bw * i;
    s << "<text class=\"xtick\" x=\"" << num("%.1f", x) << "\" y=\"" << mt + ph + 15 << "\">"
      << num(tick_format, lo + (hi - lo) * i / bins) << "</text>\n";
  }
  s << "<text class=\"xlabel\" x=\"" << ml + pw / 2 << "\" y=\"" << H - 6 << "\">" << escape(xlabel)
    << "</text>\n";
  // Bars: every bin has its two bars (height 0 when empty), so the counts are fixed.
  for (int i = 0; i < bins; ++i) {
    const double x = ml + bw * i;
    const double ha = ph * double(h.all[size_t(i)]) / double(top);
    const double hb = ph * double(h.bnd[size_t(i)]) / double(top);
    s << "<rect class=\"bar-all\" data-count=\"" << h.all[size_t(i)] << "\" x=\"" << num("%.2f", x + 0.5)
      << "\" y=\"" << num("%.2f", mt + ph - ha) << "\" width=\"" << num("%.2f", std::max(bw - 1.0, 0.5))
      << "\" height=\"" << num("%.2f", ha) << "\"><title>[" << num(tick_format, lo + (hi - lo) * i / bins)
      << ", " << num(tick_format, lo + (hi - lo) * (i + 1) / bins) << "): " << h.all[size_t(i)]
      << " all, " << h.bnd[size_t(i)] << " touching the boundary</title></rect>\n";
    s << "<rect class=\"bar-bnd\" data-count=\"" << h.bnd[size_t(i)] << "\" x=\""
      << num("%.2f", x + 0.2 * bw) << "\" y=\"" << num("%.2f", mt + ph - hb) << "\" width=\""
      << num("%.2f", std::max(0.6 * bw - 0.5, 0.5)) << "\" height=\"" << num("%.2f", hb) << "\"/>\n";
  }
  s << "</svg>\n";
  return s.str();
}

// The SVG of one cut view.
std::string cut_svg(int axis, double position, const std::vector<Poly>& polys, size_t total) {
  static const char* const kAxis = "xyz";
  static const int kU[3] = {1, 0, 0}, kV[3] = {2, 2, 1};
  double ulo = 0, uhi = 1, vlo = 0, vhi = 1;
  if (!polys.empty()) {
    ulo = vlo = HUGE_VAL;
    uhi = vhi = -HUGE_VAL;
    for (const Poly& p : polys) {
      for (int k = 0; k < p.n; ++k) {
        ulo = std::min(ulo, double(p.u[k]));
        uhi = std::max(uhi, double(p.u[k]));
        vlo = std::min(vlo, double(p.v[k]));
        vhi = std::max(vhi, double(p.v[k]));
      }
    }
  }
  const double du = std::max(uhi - ulo, 1e-300), dv = std::max(vhi - vlo, 1e-300);
  const double box = 420.0, pad = 6.0;
  const double scale = box / std::max(du, dv);
  const double w = du * scale + 2 * pad, h = dv * scale + 2 * pad;
  std::ostringstream s;
  s << "<svg class=\"cut\" data-axis=\"" << kAxis[axis] << "\" data-polygons=\"" << polys.size()
    << "\" data-crossed=\"" << total << "\" width=\"" << num("%.0f", w) << "\" height=\""
    << num("%.0f", h) << "\" viewBox=\"0 0 " << num("%.1f", w) << " " << num("%.1f", h)
    << "\" xmlns=\"http://www.w3.org/2000/svg\">\n";
  // Thinner strokes when the polygons are small on screen.
  const double mean_size = polys.empty() ? 1.0 : box / std::sqrt(double(polys.size()));
  s << "<g stroke-width=\"" << num("%.2f", std::clamp(mean_size / 12.0, 0.05, 0.8)) << "\">\n";
  char buf[48];
  for (const Poly& p : polys) {
    s << "<polygon class=\"q" << int(p.cls) << "\" points=\"";
    for (int k = 0; k < p.n; ++k) {
      std::snprintf(buf, sizeof buf, "%s%.1f,%.1f", k ? " " : "", pad + (double(p.u[k]) - ulo) * scale,
                    pad + (vhi - double(p.v[k])) * scale);
      s << buf;
    }
    s << "\"/>\n";
  }
  s << "</g></svg>\n";
  std::ostringstream cap;
  cap << "<figcaption>Plane " << kAxis[axis] << " = " << num("%.6g", position) << " (horizontal "
      << kAxis[kU[axis]] << ", vertical " << kAxis[kV[axis]] << "): " << total << " tets crossed";
  if (polys.size() < total) {
    cap << "; drawing the " << polys.size() << " nearest the centre of the cut";
  }
  cap << ".</figcaption>\n";
  return "<figure class=\"cutview\">\n" + s.str() + cap.str() + "</figure>\n";
}

// Cross-section of the tet p[0..3] by the plane x[axis] = c, when the plane separates two of its
// vertices (a point or an edge touching the plane gives nothing).
bool cross_section(const double* const p[4], int axis, double c, Poly& out) {
  static const int kU[3] = {1, 0, 0}, kV[3] = {2, 2, 1};
  double s[4];
  bool below = false, above = false;
  for (int i = 0; i < 4; ++i) {
    s[i] = p[i][axis] - c;
    below |= s[i] < 0.0;
    above |= s[i] > 0.0;
  }
  if (!below || !above) return false;
  double pu[4], pv[4];
  int n = 0;
  for (int i = 0; i < 4 && n < 4; ++i) {
    if (s[i] == 0.0) {
      pu[n] = p[i][kU[axis]];
      pv[n++] = p[i][kV[axis]];
    }
  }
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4 && n < 4; ++j) {
      if ((s[i] < 0.0 && s[j] > 0.0) || (s[i] > 0.0 && s[j] < 0.0)) {
        const double t = s[i] / (s[i] - s[j]);
        pu[n] = p[i][kU[axis]] + t * (p[j][kU[axis]] - p[i][kU[axis]]);
        pv[n++] = p[i][kV[axis]] + t * (p[j][kV[axis]] - p[i][kV[axis]]);
      }
    }
  }
  if (n < 3) return false;
  // Convex polygon: order the points by angle around their centroid.
  double cu = 0, cv = 0;
  for (int k = 0; k < n; ++k) {
    cu += pu[k];
    cv += pv[k];
  }
  cu /= n;
  cv /= n;
  int order[4] = {0, 1, 2, 3};
  double ang[4];
  for (int k = 0; k < n; ++k) ang[k] = std::atan2(pv[k] - cv, pu[k] - cu);
  for (int i = 1; i < n; ++i) {  // insertion sort of at most 4 by angle
    for (int j = i; j > 0 && ang[order[j]] < ang[order[j - 1]]; --j) std::swap(order[j], order[j - 1]);
  }
  out.n = uint8_t(n);
  for (int k = 0; k < n; ++k) {
    out.u[k] = float(pu[order[k]]);
    out.v[k] = float(pv[order[k]]);
  }
  return true;
}

// The edge's length: in the vertex metric by the UGAWG rule (core/metric_measures.hpp) when
// there is one (metric_kind 1: sizes, 6: tensors), else Euclidean.
double edge_length(const VolumeMesh& mesh, uint32_t a, uint32_t b, int metric_kind) {
  const double *p = mesh.point(a), *q = mesh.point(b);
  const double e[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
  const double l2 = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
  if (metric_kind == 1) {
    const double l = std::sqrt(l2);
    return combine_lengths(l / mesh.vertex_metric[a], l / mesh.vertex_metric[b]);
  }
  if (metric_kind == 6)
    return ugawg_edge_length(p, q, &mesh.vertex_metric[6 * size_t(a)], &mesh.vertex_metric[6 * size_t(b)]);
  return std::sqrt(l2);
}

// InvalidArgument for a cut fraction outside [0, 1], a bin count < 1, or a vertex metric that is
// not usable (1 or 6 values per vertex; sizes > 0, finite tensors).
Status check_options(const VolumeMesh& mesh, const HtmlReportOptions& opt) {
  for (int axis = 0; axis < 3; ++axis) {
    if (!(opt.cut[size_t(axis)] >= 0.0 && opt.cut[size_t(axis)] <= 1.0)) {
      return Status(Error::InvalidArgument, "cut plane positions must be fractions in [0, 1] of the bounding box");
    }
  }
  if (opt.quality_bins < 1 || opt.dihedral_bins < 1 || opt.edge_bins < 1) {
    return Status(Error::InvalidArgument, "histogram bin counts must be >= 1");
  }
  const size_t nv = mesh.num_vertices();
  const std::vector<double>& m = mesh.vertex_metric;
  if (!m.empty() && m.size() != nv && m.size() != 6 * nv) {
    return Status(Error::InvalidArgument, "the vertex metric has " + std::to_string(m.size()) + " values for " +
                                              std::to_string(nv) + " vertices (1 or 6 per vertex expected)");
  }
  for (size_t i = 0; i < m.size(); ++i) {
    if (!std::isfinite(m[i]) || (m.size() == nv && !(m[i] > 0.0))) {
      return Status(Error::InvalidArgument, "the vertex metric value " + std::to_string(i) + " (" +
                                                std::to_string(m[i]) + ") is not a usable size or tensor entry");
    }
  }
  return Status::success();
}

// The bounding box of the vertices used by a tet.
Bbox used_vertex_box(const VolumeMesh& mesh) {
  const size_t nv = mesh.num_vertices();
  Bbox box;
  bool first = true;
  std::vector<uint8_t> used(nv, 0);
  for (uint32_t v : mesh.tet) used[v] = 1;
  for (size_t v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    for (int k = 0; k < 3; ++k) {
      const double x = mesh.point(v)[k];
      box.lo[k] = first ? x : std::min(box.lo[k], x);
      box.hi[k] = first ? x : std::max(box.hi[k], x);
    }
    first = false;
  }
  return box;
}

// A dihedral angle's bin from its cosine, without acos. The angle is in bin i (of [0, 180]) when
// cos(edge i+1) < cos(angle) <= cos(edge i); cos_edges_ holds the inner edges' cosines, so the bin
// is how many of them are >= cos(angle). A table on the cosine gives it within one, the cosines
// of the bin edges (decreasing) settle it.
class DihedralBins {
 public:
  explicit DihedralBins(int bins) : bins_(bins), cos_edges_(size_t(bins - 1)), cos_table_(size_t(kCosTable)) {
    for (int i = 1; i < bins; ++i) {
      cos_edges_[size_t(i - 1)] = std::cos(3.14159265358979323846 * double(i) / double(bins));
    }
    for (size_t k = 0; k < cos_table_.size(); ++k) {
      const double c = 2.0 * double(k) / kCosTable - 1.0;
      cos_table_[k] = long(std::partition_point(cos_edges_.begin(), cos_edges_.end(),
                                                [c](double edge) { return c <= edge; }) -
                           cos_edges_.begin());
    }
  }

  size_t bin(double c) const {
    long db = cos_table_[size_t(std::clamp((c + 1.0) * 0.5 * kCosTable, 0.0, kCosTable - 1.0))];
    while (db + 1 < bins_ && c <= cos_edges_[size_t(db)]) ++db;
    while (db > 0 && c > cos_edges_[size_t(db - 1)]) --db;
    return size_t(db);
  }

 private:
  static constexpr double kCosTable = 4096.0;
  int bins_;
  std::vector<double> cos_edges_;
  std::vector<long> cos_table_;
};

// Bins the six dihedral angles of the tet p[0..3] (in h.bnd too when bnd): 180 degrees minus the
// angle between the inward face normals.
void add_dihedrals(const double* const p[4], const DihedralBins& bins, bool bnd, Hist& h) {
  double e[6][3];
  static const int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (int k = 0; k < 6; ++k) {
    for (int c = 0; c < 3; ++c) e[k][c] = p[kEdge[k][1]][c] - p[kEdge[k][0]][c];
  }
  auto cross = [](const double* x, const double* y, double* r) {
    r[0] = x[1] * y[2] - x[2] * y[1];
    r[1] = x[2] * y[0] - x[0] * y[2];
    r[2] = x[0] * y[1] - x[1] * y[0];
  };
  double n[4][3];
  cross(e[4], e[3], n[0]);  // facet 0 (b d c): bd x bc
  cross(e[1], e[2], n[1]);  // facet 1 (a c d): ac x ad
  cross(e[2], e[0], n[2]);  // facet 2 (a d b): ad x ab
  cross(e[0], e[1], n[3]);  // facet 3 (a b c): ab x ac
  double len[4];
  for (int k = 0; k < 4; ++k) len[k] = std::sqrt(n[k][0] * n[k][0] + n[k][1] * n[k][1] + n[k][2] * n[k][2]);
  for (int k = 0; k < 4; ++k) {
    for (int j = k + 1; j < 4; ++j) {
      // A degenerate face (zero normal) makes its three angles 0.
      const double c = len[k] == 0.0 || len[j] == 0.0
                           ? 1.0
                           : -(n[k][0] * n[j][0] + n[k][1] * n[j][1] + n[k][2] * n[j][2]) / (len[k] * len[j]);
      const size_t db = bins.bin(c);
      h.all[db] += 1;
      if (bnd) h.bnd[db] += 1;
    }
  }
}

// What the pass over the tets gives: per tet its boundary flag, per block of tets its tallies and
// its cross-sections by each plane (merged in block order: the same on any number of threads).
struct TetPass {
  std::vector<uint8_t> tet_bnd;  // 1: the tet touches the boundary
  std::vector<TetTally> tallies;
  std::vector<std::array<std::vector<Poly>, 3>> cuts;
  size_t blocks = 0;
};

// One pass over the tets: flags, histograms, per-group extremes, cross-sections.
TetPass tet_pass(const VolumeMesh& mesh, const TetData& data, const std::vector<uint8_t>& on_boundary,
                 const double plane[3], const HtmlReportOptions& opt, bool parallel) {
  const size_t nt = mesh.num_tets();
  const DihedralBins dihedral_bins(opt.dihedral_bins);
  TetPass pass;
  pass.tet_bnd.assign(nt, 0);
  pass.tallies.resize(64);
  pass.cuts.resize(64);
  pass.blocks = for_blocks(nt, parallel, [&](size_t b, size_t begin, size_t end) {
    TetTally tally;  // local: the blocks' tallies side by side would share cache lines
    tally.rr = Hist(opt.quality_bins);
    tally.mr = Hist(opt.quality_bins);
    tally.dihedral = Hist(opt.dihedral_bins);
    std::array<std::vector<Poly>, 3> block_cuts;
    for (size_t t = begin; t < end; ++t) {
      const uint32_t* v = &mesh.tet[4 * t];
      const bool bnd = on_boundary[v[0]] || on_boundary[v[1]] || on_boundary[v[2]] || on_boundary[v[3]];
      pass.tet_bnd[t] = bnd ? 1 : 0;
      tally.boundary_tets += bnd;
      const size_t rb = bin_of(data.radius_ratio[t], 0.0, 1.0, opt.quality_bins);
      const size_t mb = bin_of(data.mean_ratio[t], 0.0, 1.0, opt.quality_bins);
      tally.rr.all[rb] += 1;
      tally.mr.all[mb] += 1;
      if (bnd) {
        tally.rr.bnd[rb] += 1;
        tally.mr.bnd[mb] += 1;
      }
      const int g = bnd ? 1 : 0;
      tally.max_dihedral_key[g] = std::max(tally.max_dihedral_key[g], data.max_dihedral_key[t]);
      tally.lt5[g] += data.min_dihedral[t] < 5.0;
      tally.lt10[g] += data.min_dihedral[t] < 10.0;
      const double* p[4] = {mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2]), mesh.point(v[3])};
      add_dihedrals(p, dihedral_bins, bnd, tally.dihedral);
      for (int axis = 0; axis < 3; ++axis) {
        Poly poly;
        if (cross_section(p, axis, plane[axis], poly)) {
          poly.cls = uint8_t(std::min(kClasses - 1, std::max(0, int(data.radius_ratio[t] * kClasses))));
          block_cuts[size_t(axis)].push_back(poly);
        }
      }
    }
    pass.tallies[b] = std::move(tally);
    pass.cuts[b] = std::move(block_cuts);
  });
  return pass;
}

// The blocks' tallies added up in block order.
TetTally merge_tallies(const TetPass& pass, const HtmlReportOptions& opt) {
  TetTally total;
  total.rr = Hist(opt.quality_bins);
  total.mr = Hist(opt.quality_bins);
  total.dihedral = Hist(opt.dihedral_bins);
  for (size_t b = 0; b < pass.blocks; ++b) {
    const TetTally& t = pass.tallies[b];
    total.rr.add(t.rr);
    total.mr.add(t.mr);
    total.dihedral.add(t.dihedral);
    total.boundary_tets += t.boundary_tets;
    for (int g = 0; g < 2; ++g) {
      total.max_dihedral_key[g] = std::max(total.max_dihedral_key[g], t.max_dihedral_key[g]);
      total.lt5[g] += t.lt5[g];
      total.lt10[g] += t.lt10[g];
    }
  }
  return total;
}

// One cut view's cross-sections: the blocks' in block order (freeing them on the way), and beyond
// `cap` the ones nearest the centre of the cut, in the same order. `total` gets the count before
// the cap.
std::vector<Poly> cut_view_polys(TetPass& pass, int axis, const Bbox& box, size_t cap, size_t& total) {
  std::vector<Poly> all;
  for (size_t b = 0; b < pass.blocks; ++b) {
    all.insert(all.end(), pass.cuts[b][size_t(axis)].begin(), pass.cuts[b][size_t(axis)].end());
    std::vector<Poly>().swap(pass.cuts[b][size_t(axis)]);
  }
  total = all.size();
  if (all.size() > cap) {
    static const int kU[3] = {1, 0, 0}, kV[3] = {2, 2, 1};
    const int u = kU[axis], w = kV[axis];
    const double cu = 0.5 * (box.lo[u] + box.hi[u]), cv = 0.5 * (box.lo[w] + box.hi[w]);
    const double su = std::max(box.hi[u] - box.lo[u], 1e-300), sv = std::max(box.hi[w] - box.lo[w], 1e-300);
    auto key = [&](const Poly& p) {
      double mu = 0, mv = 0;
      for (int k = 0; k < p.n; ++k) {
        mu += p.u[k];
        mv += p.v[k];
      }
      return std::max(std::fabs(mu / p.n - cu) / su, std::fabs(mv / p.n - cv) / sv);
    };
    std::vector<std::pair<double, size_t>> keyed(all.size());
    for (size_t i = 0; i < all.size(); ++i) keyed[i] = {key(all[i]), i};
    std::nth_element(keyed.begin(), keyed.begin() + long(cap), keyed.end());
    keyed.resize(cap);
    std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
    std::vector<Poly> kept;
    kept.reserve(keyed.size());
    for (const auto& k : keyed) kept.push_back(all[k.second]);
    all.swap(kept);
  }
  return all;
}

// The unique edges of the tets, by smaller vertex then larger: their lengths (in the vertex
// metric when metric_kind is 1 or 6, see edge_length) and whether they touch the boundary.
struct EdgeLengths {
  std::vector<double> lengths;
  std::vector<uint8_t> boundary;
};

// The tets' edges bucketed by their smaller vertex, each bucket sorted and made unique.
EdgeLengths unique_edge_lengths(const VolumeMesh& mesh, const std::vector<uint8_t>& on_boundary, int metric_kind,
                                bool parallel) {
  const size_t nv = mesh.num_vertices(), nt = mesh.num_tets();
  std::vector<size_t> start;
  std::vector<uint32_t> other;  // the larger end, bucketed by the smaller
  {
    std::vector<size_t> fill;
    auto emit_edges = [&](size_t first, size_t last, auto&& emit) {
      static const int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
      for (size_t t = first; t < last; ++t) {
        const uint32_t* v = &mesh.tet[4 * t];
        for (const auto& e : kEdge) {
          const uint32_t a = v[e[0]], b = v[e[1]];
          emit(std::min(a, b), std::max(a, b));
        }
      }
    };
    if (parallel) parallel_bucket_by_key(nv, nt, emit_edges, start, other, fill);
    else bucket_by_key(nv, [&](auto&& emit) { emit_edges(0, nt, emit); }, start, other, fill);
  }
  std::vector<size_t> unique_count(nv, 0);
  quality_detail::for_chunks(nv, parallel, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      auto first = other.begin() + long(start[v]), last = other.begin() + long(start[v + 1]);
      std::sort(first, last);
      unique_count[v] = size_t(std::unique(first, last) - first);
    }
  });
  std::vector<size_t> offset(nv + 1, 0);
  for (size_t v = 0; v < nv; ++v) offset[v + 1] = offset[v] + unique_count[v];
  EdgeLengths edges;
  edges.lengths.resize(offset[nv]);
  edges.boundary.resize(offset[nv]);
  quality_detail::for_chunks(nv, parallel, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      for (size_t k = 0; k < unique_count[v]; ++k) {
        const uint32_t w = other[start[v] + k];
        edges.lengths[offset[v] + k] = edge_length(mesh, uint32_t(v), w, metric_kind);
        edges.boundary[offset[v] + k] = on_boundary[v] || on_boundary[w];
      }
    }
  });
  return edges;
}

// The edge lengths' extremes, mean and histogram over [0, longest] (zeros when there is none).
struct EdgeSummary {
  double min = 0, max = 0, mean = 0;
  Hist hist;
};

EdgeSummary summarize_edges(const EdgeLengths& edges, int bins) {
  const std::vector<double>& lengths = edges.lengths;
  EdgeSummary s;
  s.hist = Hist(bins);
  if (!lengths.empty()) {
    s.min = *std::min_element(lengths.begin(), lengths.end());
    s.max = *std::max_element(lengths.begin(), lengths.end());
    double sum = 0;
    for (double l : lengths) sum += l;
    s.mean = sum / double(lengths.size());
    for (size_t i = 0; i < lengths.size(); ++i) {
      const size_t b = bin_of(lengths[i], 0.0, s.max, bins);
      s.hist.all[b] += 1;
      if (edges.boundary[i]) s.hist.bnd[b] += 1;
    }
  }
  return s;
}

// What the page draws besides the report and HtmlReport's counts.
struct PageData {
  Bbox box;                                    // of the used vertices
  double plane[3] = {0, 0, 0};                 // the cut planes' positions along x, y, z
  TetTally tally;                              // all blocks' added up
  std::array<std::vector<Poly>, 3> cut_polys;  // drawn per plane
  EdgeSummary edges;
  QualitySplit split_bnd, split_int;  // tets touching the boundary, the others
};

// The page up to the end of its introduction: the style, the body's data attributes (which
// tests/e2e/report_check.py reads), the title.
void write_head(std::ostringstream& h, const HtmlReport& out, const PageData& page, const HtmlReportOptions& opt) {
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << escape(opt.title)
    << "</title>\n<style>\n"
       "body{font-family:sans-serif;margin:16px 24px;color:#222;background:#fff}\n"
       "h1{font-size:22px;margin:0 0 4px}h2{font-size:18px;margin:22px 0 8px;border-bottom:1px solid #ccc}\n"
       "table{border-collapse:collapse;margin:6px 16px 6px 0;font-size:13px;display:inline-table;vertical-align:top}\n"
       "td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}th{background:#eef}td.k{text-align:left}\n"
       ".ok{color:#070;font-weight:bold}.bad{color:#b00;font-weight:bold}\n"
       ".hists{display:flex;flex-wrap:wrap;gap:10px}.cuts{display:flex;flex-wrap:wrap;gap:14px}\n"
       "svg.hist{border:1px solid #ddd;background:#fff}\n"
       "svg.hist text{font-size:11px;fill:#333}svg.hist text.title{font-size:13px;text-anchor:middle;font-weight:bold}\n"
       "svg.hist text.ytick{text-anchor:end}svg.hist text.xtick,svg.hist text.xlabel{text-anchor:middle}\n"
       "svg.hist .axis{stroke:#333;stroke-width:1}svg.hist .grid{stroke:#e4e4e4;stroke-width:1}\n"
       "rect.bar-all{fill:#4c78a8}rect.bar-bnd{fill:#f58518}\n"
       "svg.cut{border:1px solid #ddd;background:#f7f7f7}svg.cut g{stroke:#222;stroke-opacity:.55}\n"
       "figure{margin:0}figcaption{font-size:12px;max-width:440px}\n"
       ".legend span{display:inline-block;padding:2px 6px;font-size:11px;margin-right:1px}\n";
  for (int c = 0; c < kClasses; ++c) {
    h << "polygon.q" << c << "{fill:" << kClassColour[c] << "}.legend .q" << c << "{background:"
      << kClassColour[c] << (c <= 2 ? ";color:#fff" : "") << "}\n";
  }
  h << "</style>\n</head>\n<body data-tets=\"" << out.report.tets << "\" data-boundary-tets=\"" << out.boundary_tets
    << "\" data-edges=\"" << out.edges << "\" data-edge-metric=\"" << (out.metric_edge_lengths ? 1 : 0)
    << "\" data-edge-mean=\"" << num("%.6g", page.edges.mean) << "\">\n";
  h << "<h1>" << escape(opt.title) << "</h1>\n<p>Quality report written by anitet";
  if (!opt.mesh_name.empty()) h << " for <code>" << escape(opt.mesh_name) << "</code>";
  if (!opt.surface_name.empty()) h << " against the input surface <code>" << escape(opt.surface_name) << "</code>";
  h << ". Radius ratio = 3 &times; inradius / circumradius, mean ratio = 12 (3|V|)<sup>2/3</sup> / &Sigma; l<sup>2</sup> "
       "(both 1 for the regular tet). <i>Touching the boundary</i>: tets with a vertex on a boundary face "
       "of the mesh.</p>\n";
}

// A row of a two-column table (k and v are HTML already).
void table_row(std::ostringstream& h, const std::string& k, const std::string& v) {
  h << "<tr><td class=\"k\">" << k << "</td><td>" << v << "</td></tr>\n";
}

// The summary's first table: the mesh's counts, box, validity and edge lengths. The page's own
// time is a marker, filled in when the page is done.
void write_mesh_table(std::ostringstream& h, const HtmlReport& out, const PageData& page) {
  const QualityReport& r = out.report;
  const Bbox& box = page.box;
  h << "<h2>Summary</h2>\n<table><tr><th colspan=\"2\">Mesh</th></tr>\n";
  auto row = [&](const std::string& k, const std::string& v) { table_row(h, k, v); };
  row("vertices", std::to_string(r.vertices));
  row("tets", std::to_string(r.tets));
  row("unused vertices", std::to_string(r.unused_vertices));
  row("edges", std::to_string(out.edges));
  row("boundary faces", std::to_string(r.boundary_faces));
  row("tets touching the boundary", std::to_string(out.boundary_tets) + " (" + percent(out.boundary_tets, r.tets) + ")");
  row("volume", num("%.9g", r.volume));
  row("bounding box", "[" + num("%.4g", box.lo[0]) + ", " + num("%.4g", box.hi[0]) + "] &times; [" +
                          num("%.4g", box.lo[1]) + ", " + num("%.4g", box.hi[1]) + "] &times; [" +
                          num("%.4g", box.lo[2]) + ", " + num("%.4g", box.hi[2]) + "]");
  row("valid", r.valid ? "<span class=\"ok\">yes</span>" : "<span class=\"bad\">no</span>");
  row("non-positive tets (inverted, flat)",
      std::to_string(r.nonpositive_tets) + " (" + std::to_string(r.inverted_tets) + ", " + std::to_string(r.flat_tets) + ")");
  row("valid tets flat to double rounding", std::to_string(r.rounding_flat_tets));
  row("faces shared by &gt; 2 tets", std::to_string(r.faces_shared_by_more_than_two));
  row(out.metric_edge_lengths ? "edge length in the metric: min / mean / max" : "edge length: min / mean / max",
      num("%.4g", page.edges.min) + " / " + num("%.4g", page.edges.mean) + " / " + num("%.4g", page.edges.max));
  row("report time (measures / page)", num("%.3f s", out.seconds_quality) + " / " + "<!--html-seconds-->");
  h << "</table>\n";
}

// The quality measures of all tets, of those touching the boundary and of the others.
void write_quality_table(std::ostringstream& h, const QualityReport& r, const PageData& page) {
  const TetTally& total = page.tally;
  h << "<table><tr><th></th><th>all tets</th><th>touching the boundary</th><th>interior</th></tr>\n";
  auto qrow = [&](const std::string& k, const std::string& a, const std::string& b, const std::string& c) {
    h << "<tr><td class=\"k\">" << k << "</td><td>" << a << "</td><td>" << b << "</td><td>" << c << "</td></tr>\n";
  };
  const QualitySplit* groups[2] = {&page.split_bnd, &page.split_int};
  auto grp = [&](auto f) { return std::array<std::string, 2>{f(*groups[0]), f(*groups[1])}; };
  auto g3 = [&](const std::string& k, const std::string& all, const std::array<std::string, 2>& g) {
    qrow(k, all, g[0], g[1]);
  };
  g3("tets", std::to_string(r.tets), grp([](const QualitySplit& q) { return std::to_string(q.tets); }));
  g3("radius ratio min", num("%.4f", r.radius_ratio.min),
     grp([](const QualitySplit& q) { return num("%.4f", q.radius_ratio.min); }));
  g3("radius ratio 1st percentile", num("%.4f", r.radius_ratio.p01),
     grp([](const QualitySplit& q) { return num("%.4f", q.radius_ratio.p01); }));
  g3("radius ratio mean", num("%.4f", r.radius_ratio.mean),
     grp([](const QualitySplit& q) { return num("%.4f", q.radius_ratio.mean); }));
  g3("mean ratio min", num("%.4f", r.mean_ratio.min),
     grp([](const QualitySplit& q) { return num("%.4f", q.mean_ratio.min); }));
  g3("mean ratio mean", num("%.4f", r.mean_ratio.mean),
     grp([](const QualitySplit& q) { return num("%.4f", q.mean_ratio.mean); }));
  g3("min dihedral (deg)", num("%.2f", r.min_dihedral_deg),
     grp([](const QualitySplit& q) { return num("%.2f", q.min_dihedral_deg); }));
  qrow("max dihedral (deg)", num("%.2f", r.max_dihedral_deg), num("%.2f", max_dihedral_from_key(total.max_dihedral_key[1])),
       num("%.2f", max_dihedral_from_key(total.max_dihedral_key[0])));
  qrow("min dihedral &lt; 5&deg;", std::to_string(r.tets_dihedral_lt_5deg), std::to_string(total.lt5[1]),
       std::to_string(total.lt5[0]));
  qrow("min dihedral &lt; 10&deg;", std::to_string(r.tets_dihedral_lt_10deg), std::to_string(total.lt10[1]),
       std::to_string(total.lt10[0]));
  g3("radius ratio &gt; 0.4", num("%.2f%%", 100.0 * r.good_fraction),
     grp([](const QualitySplit& q) { return num("%.2f%%", 100.0 * q.good_fraction); }));
  g3("radius ratio &lt; 0.1", num("%.2f%%", 100.0 * r.bad_fraction),
     grp([](const QualitySplit& q) { return num("%.2f%%", 100.0 * q.bad_fraction); }));
  h << "</table>\n";
}

// The rows of the run that made the mesh (plain text, escaped here).
void write_run_table(std::ostringstream& h, const HtmlReportOptions& opt) {
  h << "<table><tr><th colspan=\"2\">Meshing run</th></tr>\n";
  for (const auto& [name, value] : opt.run_rows) table_row(h, escape(name), escape(value));
  h << "</table>\n";
}

// The UGAWG measures when the mesh carries a metric: edges in range, lengths, mean ratio.
void write_metric_table(std::ostringstream& h, const MetricQuality& m) {
  auto row = [&](const std::string& k, const std::string& v) { table_row(h, k, v); };
  h << "<table><tr><th colspan=\"2\">In the metric (UGAWG measures)</th></tr>\n";
  row("edges with a length in [1/&radic;2, &radic;2]", num("%.2f%%", 100.0 * m.in_range) + " (" +
                                                            num("%.2f%%", 100.0 * m.shorter) + " shorter, " +
                                                            num("%.2f%%", 100.0 * m.longer) + " longer)");
  row("edge length: min / mean / max",
      num("%.4g", m.edge_length.min) + " / " + num("%.4g", m.edge_length.mean) + " / " + num("%.4g", m.edge_length.max));
  row("mean ratio in the metric: min / 1st percentile / mean",
      num("%.4f", m.mean_ratio.min) + " / " + num("%.4f", m.mean_ratio.p01) + " / " + num("%.4f", m.mean_ratio.mean));
  h << "</table>\n";
}

// The mesh against the input surface it was made from.
void write_surface_table(std::ostringstream& h, const SurfaceMatchReport& s) {
  auto row = [&](const std::string& k, const std::string& v) { table_row(h, k, v); };
  h << "<table><tr><th colspan=\"2\">Against the input surface</th></tr>\n";
  row("boundary constrained",
      s.boundary_constrained ? "<span class=\"ok\">yes</span>" : "<span class=\"bad\">no</span>");
  row("input vertices / triangles", std::to_string(s.input_vertices) + " / " + std::to_string(s.input_triangles));
  row("input triangles missing", std::to_string(s.input_triangles_missing));
  row("boundary faces not in the input", std::to_string(s.boundary_faces_not_in_input));
  row("Steiner points on the boundary", std::to_string(s.steiner_points_on_boundary));
  row("other vertices on the surface", std::to_string(s.vertices_on_input_surface));
  row("volume relative error", num("%.3g", s.volume_rel_error));
  row("tets with an input vertex: tets / rr min / rr mean",
      std::to_string(s.touching_surface.tets) + " / " + num("%.4f", s.touching_surface.radius_ratio.min) +
          " / " + num("%.4f", s.touching_surface.radius_ratio.mean));
  row("other tets: tets / rr min / rr mean",
      std::to_string(s.interior.tets) + " / " + num("%.4f", s.interior.radius_ratio.min) + " / " +
          num("%.4f", s.interior.radius_ratio.mean));
  h << "</table>\n";
}

// The four histograms: radius ratio, mean ratio, dihedral angles, edge lengths.
void write_histograms(std::ostringstream& h, const HtmlReport& out, const PageData& page,
                      const HtmlReportOptions& opt) {
  h << "<h2>Histograms</h2>\n<p>Blue: all tets (edges); orange: the ones touching the boundary.</p>\n"
       "<div class=\"hists\">\n";
  const int qt = std::max(1, opt.quality_bins / 5), dt = std::max(1, opt.dihedral_bins / 6),
            et = std::max(1, opt.edge_bins / 5);
  h << hist_svg("radius-ratio", "Radius ratio (per tet)", "radius ratio", page.tally.rr, 0.0, 1.0, "%.1f", qt);
  h << hist_svg("mean-ratio", "Mean ratio (per tet)", "mean ratio", page.tally.mr, 0.0, 1.0, "%.1f", qt);
  h << hist_svg("dihedral", "Dihedral angles (6 per tet)", "degrees", page.tally.dihedral, 0.0, 180.0, "%.0f", dt);
  h << hist_svg("edge-length", out.metric_edge_lengths ? "Edge length in the metric" : "Edge length",
                out.metric_edge_lengths ? "metric length (1 = the prescribed size)"
                                        : "length (no metric in the mesh file: Euclidean)",
                page.edges.hist, 0.0, page.edges.max, "%.3g", et);
  if (out.report.metric.present) {
    Hist metric_mr(int(out.report.metric.mean_ratio_histogram.size()));
    metric_mr.all = out.report.metric.mean_ratio_histogram;
    h << hist_svg("metric-mean-ratio", "Mean ratio in the metric (per tet)", "mean ratio (UGAWG: the finest corner's metric)",
                  metric_mr, 0.0, 1.0, "%.1f", qt);
  }
  h << "</div>\n";
}

// The three cut views with their colour legend, and the end of the page.
void write_cut_views(std::ostringstream& h, const HtmlReport& out, const PageData& page,
                     const HtmlReportOptions& opt) {
  h << "<h2>Cut views</h2>\n<p>Cross-sections of the tets crossed by the planes through x, y, z at "
    << num("%.3g", opt.cut[0]) << ", " << num("%.3g", opt.cut[1]) << ", " << num("%.3g", opt.cut[2])
    << " of the bounding box, coloured by radius ratio:</p>\n<p class=\"legend\">";
  for (int c = 0; c < kClasses; ++c) {
    h << "<span class=\"q" << c << "\">" << num("%.1f", double(c) / kClasses) << "&ndash;"
      << num("%.1f", double(c + 1) / kClasses) << "</span>";
  }
  h << "</p>\n<div class=\"cuts\">\n";
  for (int axis = 0; axis < 3; ++axis) {
    h << cut_svg(axis, page.plane[axis], page.cut_polys[size_t(axis)], out.cut_polygons_total[size_t(axis)]);
  }
  h << "</div>\n</body>\n</html>\n";
}

std::string page_html(const HtmlReport& out, const PageData& page, const HtmlReportOptions& opt) {
  std::ostringstream h;
  write_head(h, out, page, opt);
  write_mesh_table(h, out, page);
  write_quality_table(h, out.report, page);
  if (!opt.run_rows.empty()) write_run_table(h, opt);
  if (out.report.metric.present) write_metric_table(h, out.report.metric);
  if (out.report.surface.present) write_surface_table(h, out.report.surface);
  write_histograms(h, out, page, opt);
  write_cut_views(h, out, page, opt);
  return h.str();
}

}  // namespace

Result<HtmlReport> quality_report_html(const VolumeMesh& mesh, const SurfaceMesh* input_surface,
                                       const QualityOptions& quality_options,
                                       const HtmlReportOptions& opt) {
  if (Status st = check_options(mesh, opt); !st.ok()) return st;
  HtmlReport out;
  TetData data;
  std::vector<uint32_t> boundary;
  {
    Result<QualityReport> r =
        quality_detail::compute_quality_report_keep(mesh, input_surface, quality_options, data, boundary);
    if (!r.ok()) return r.status();
    out.report = std::move(r).value();
  }
  out.seconds_quality = out.report.seconds;
  const auto clock_start = std::chrono::steady_clock::now();
  const bool parallel = quality_options.parallel;
  const size_t nv = mesh.num_vertices();

  // Vertices on the boundary, and the cut planes across the bounding box of the used vertices.
  std::vector<uint8_t> on_boundary(nv, 0);
  for (uint32_t v : boundary) on_boundary[v] = 1;
  PageData page;
  page.box = used_vertex_box(mesh);
  for (int k = 0; k < 3; ++k) page.plane[k] = page.box.lo[k] + opt.cut[size_t(k)] * (page.box.hi[k] - page.box.lo[k]);

  TetPass pass = tet_pass(mesh, data, on_boundary, page.plane, opt, parallel);
  page.tally = merge_tallies(pass, opt);
  out.boundary_tets = page.tally.boundary_tets;
  for (int axis = 0; axis < 3; ++axis) {
    page.cut_polys[size_t(axis)] =
        cut_view_polys(pass, axis, page.box, opt.max_polygons_per_view, out.cut_polygons_total[size_t(axis)]);
    out.cut_polygons_drawn[size_t(axis)] = page.cut_polys[size_t(axis)].size();
  }

  const int metric_kind = nv > 0 && mesh.vertex_metric.size() == nv ? 1
                          : nv > 0 && mesh.vertex_metric.size() == 6 * nv ? 6
                                                                          : 0;
  out.metric_edge_lengths = metric_kind != 0;
  {
    const EdgeLengths edges = unique_edge_lengths(mesh, on_boundary, metric_kind, parallel);
    out.edges = edges.lengths.size();
    page.edges = summarize_edges(edges, opt.edge_bins);
  }

  // The groups' statistics (touching the boundary: 1, interior: 0).
  page.split_bnd = quality_detail::split_quality(data, pass.tet_bnd, 1);
  page.split_int = quality_detail::split_quality(data, pass.tet_bnd, 0);

  out.html = page_html(out, page, opt);
  out.seconds_html = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  const std::string marker = "<!--html-seconds-->";
  const size_t at = out.html.find(marker);
  if (at != std::string::npos) out.html.replace(at, marker.size(), num("%.3f s", out.seconds_html));
  return out;
}

}  // namespace anitet
