#include "mesh2d/sizing2.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

#include "io/file_bytes.hpp"
#include "io/text_scanner.hpp"
#include "mesh2d/pslg_io.hpp"
#include "metric/sol_field.hpp"
#include "metric/spd.hpp"

namespace anitet::mesh2d {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Bilinear weights of p in a lattice of nx x ny nodes: the base node (i, j) and fractions.
void bilinear(const double origin[3], double spacing, int nx, int ny, const double* p, int& i, int& j, double& fx,
              double& fy) {
  const double u = std::clamp((p[0] - origin[0]) / spacing, 0.0, double(nx - 1));
  const double v = std::clamp((p[1] - origin[1]) / spacing, 0.0, double(ny - 1));
  i = std::min(int(u), std::max(nx - 2, 0));
  j = std::min(int(v), std::max(ny - 2, 0));
  fx = nx > 1 ? u - i : 0.0;
  fy = ny > 1 ? v - j : 0.0;
}

double segment_distance(const double* a, const double* b, const double* p) {
  const double ex = b[0] - a[0], ey = b[1] - a[1];
  const double l2 = ex * ex + ey * ey;
  double t = l2 > 0 ? ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / l2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(a[0] + t * ex - p[0], a[1] + t * ey - p[1]);
}

}  // namespace

void LatticeField2::metric(const double p[3], double m[6]) const {
  const metric::Lattice& l = lattice_;
  int i, j;
  double fx, fy;
  bilinear(l.origin, l.spacing, l.dims[0], l.dims[1], p, i, j, fx, fy);
  const int i1 = std::min(i + 1, l.dims[0] - 1), j1 = std::min(j + 1, l.dims[1] - 1);
  const size_t n00 = l.node(i, j, 0), n10 = l.node(i1, j, 0), n01 = l.node(i, j1, 0), n11 = l.node(i1, j1, 0);
  const double w00 = (1 - fx) * (1 - fy), w10 = fx * (1 - fy), w01 = (1 - fx) * fy, w11 = fx * fy;
  if (l.components == 1) {
    const double h = w00 * l.values[n00] + w10 * l.values[n10] + w01 * l.values[n01] + w11 * l.values[n11];
    isotropic_metric(h, m);
    return;
  }
  Metric2 lg;
  auto comp = [&](int c) {
    return w00 * l.values[6 * n00 + size_t(c)] + w10 * l.values[6 * n10 + size_t(c)] +
           w01 * l.values[6 * n01 + size_t(c)] + w11 * l.values[6 * n11 + size_t(c)];
  };
  lg.xx = comp(0), lg.xy = comp(1), lg.yy = comp(2);
  to_metric6(exp2x2(lg), m);
}

// ---- Raster ----------------------------------------------------------------------------------

double Raster::value(double x, double y) const {
  const double u = (x - x0) / dx, v = (y - y0) / dy;
  if (!(u >= 0 && v >= 0 && u <= ncols - 1 && v <= nrows - 1)) return std::numeric_limits<double>::quiet_NaN();
  const int i = std::min(int(u), std::max(ncols - 2, 0)), j = std::min(int(v), std::max(nrows - 2, 0));
  const int i1 = std::min(i + 1, ncols - 1), j1 = std::min(j + 1, nrows - 1);
  const double fx = u - i, fy = v - j;
  auto at = [&](int a, int b) { return values[size_t(b) * size_t(ncols) + size_t(a)]; };
  return (1 - fx) * (1 - fy) * at(i, j) + fx * (1 - fy) * at(i1, j) + (1 - fx) * fy * at(i, j1) + fx * fy * at(i1, j1);
}

Result<Raster> parse_ascii_grid(std::string_view data, const std::string& name) {
  TextScanner in(data, name);
  Raster r;
  double xll = 0, yll = 0, cell = 0, nodata = std::numeric_limits<double>::quiet_NaN();
  bool x_center = false, y_center = false, have_x = false, have_y = false, have_cell = false;
  int64_t ncols = -1, nrows = -1;
  r.dx = r.dy = 0;
  // Header lines: "key value" until the first line starting with a number.
  for (;;) {
    const std::string_view key = in.peek_token();
    if (key.empty()) return in.error(Error::Parse, "the grid ends in its header");
    double probe;
    if (parse_double(key, probe)) break;
    in.next_token();
    double value = 0;
    if (!in.read_double(value)) return in.expected("a number after " + std::string(key));
    if (iequals(key, "ncols")) ncols = int64_t(value);
    else if (iequals(key, "nrows")) nrows = int64_t(value);
    else if (iequals(key, "xllcorner")) xll = value, have_x = true;
    else if (iequals(key, "xllcenter")) xll = value, have_x = x_center = true;
    else if (iequals(key, "yllcorner")) yll = value, have_y = true;
    else if (iequals(key, "yllcenter")) yll = value, have_y = y_center = true;
    else if (iequals(key, "cellsize")) cell = value, have_cell = true;
    else if (iequals(key, "dx")) r.dx = value;
    else if (iequals(key, "dy")) r.dy = value;
    else if (iequals(key, "nodata_value")) nodata = value;
    else return in.error(Error::Parse, "unknown header key '" + quote_token(key) + "'");
  }
  if (have_cell) r.dx = r.dy = cell;
  if (ncols < 2 || nrows < 2 || ncols > 1000000 || nrows > 1000000 || !have_x || !have_y || !(r.dx > 0) || !(r.dy > 0))
    return Status(Error::Parse, name + ": the header needs ncols and nrows (>= 2), xllcorner or xllcenter, yllcorner or "
                                       "yllcenter, and cellsize (or dx and dy) > 0");
  r.ncols = int(ncols);
  r.nrows = int(nrows);
  r.x0 = x_center ? xll : xll + 0.5 * r.dx;
  r.y0 = y_center ? yll : yll + 0.5 * r.dy;
  if (uint64_t(ncols) * uint64_t(nrows) > in.remaining() + 1)
    return Status(Error::Parse, name + ": " + std::to_string(ncols) + " x " + std::to_string(nrows) + " values do not fit in the file");
  r.values.resize(size_t(ncols) * size_t(nrows));
  for (int64_t row = 0; row < nrows; ++row)
    for (int64_t col = 0; col < ncols; ++col) {
      double v;
      if (!in.read_double(v)) return in.expected("value " + std::to_string(col + 1) + " of row " + std::to_string(row + 1));
      if (v == nodata || !std::isfinite(v)) v = std::numeric_limits<double>::quiet_NaN();
      r.values[size_t(nrows - 1 - row) * size_t(ncols) + size_t(col)] = v;
    }
  return r;
}

Result<Raster> read_ascii_grid(const std::string& path) {
  Result<std::string> bytes = read_file_bytes(path);
  if (!bytes.ok()) return bytes.status();
  return parse_ascii_grid(bytes.value(), path);
}

// ---- Background mesh field ----------------------------------------------------------------

Result<std::unique_ptr<Background2Field>> Background2Field::create(std::vector<double> xy, std::vector<uint32_t> tri,
                                                                   const std::vector<double>& values, int components) {
  const size_t nv = xy.size() / 2, nt = tri.size() / 3;
  if (nt == 0) return Status(Error::EmptyInput, "the background mesh has no triangle");
  if ((components != 1 && components != 3) || values.size() != nv * size_t(components))
    return Status(Error::InvalidArgument, "the .sol has " + std::to_string(values.size() / size_t(std::max(components, 1))) +
                                              " values for a mesh of " + std::to_string(nv) + " vertices");
  std::unique_ptr<Background2Field> f(new Background2Field());
  f->components_ = components;
  f->log_.resize(nv);
  for (size_t v = 0; v < nv; ++v) {
    if (components == 1) {
      if (!(values[v] > 0) || !std::isfinite(values[v]))
        return Status(Error::InvalidArgument, "the size at vertex " + std::to_string(v + 1) + " is not positive");
      f->log_[v].xx = values[v];
    } else {
      const Metric2 m{values[3 * v], values[3 * v + 1], values[3 * v + 2]};
      if (!is_spd(m)) return Status(Error::InvalidArgument, "the tensor at vertex " + std::to_string(v + 1) + " is not positive definite");
      f->log_[v] = log2x2(m);
    }
  }
  double lo[2] = {kInf, kInf}, hi[2] = {-kInf, -kInf};
  for (size_t i = 0; i < xy.size(); ++i) lo[i % 2] = std::min(lo[i % 2], xy[i]), hi[i % 2] = std::max(hi[i % 2], xy[i]);
  f->cell_ = std::max(std::sqrt((hi[0] - lo[0]) * (hi[1] - lo[1]) / double(nt)), 1e-300);
  f->nx_ = std::clamp(int((hi[0] - lo[0]) / f->cell_) + 1, 1, 4096);
  f->ny_ = std::clamp(int((hi[1] - lo[1]) / f->cell_) + 1, 1, 4096);
  f->cell_ = std::max({f->cell_, (hi[0] - lo[0]) / f->nx_, (hi[1] - lo[1]) / f->ny_});
  f->lo_[0] = lo[0], f->lo_[1] = lo[1];
  auto cell_of = [&](double x, double y, int& cx, int& cy) {
    cx = std::clamp(int((x - lo[0]) / f->cell_), 0, f->nx_ - 1);
    cy = std::clamp(int((y - lo[1]) / f->cell_), 0, f->ny_ - 1);
  };
  std::vector<uint32_t> count(size_t(f->nx_) * size_t(f->ny_) + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    for (uint32_t t = 0; t < nt; ++t) {
      double tlo[2] = {kInf, kInf}, thi[2] = {-kInf, -kInf};
      for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 2; ++c) {
          tlo[c] = std::min(tlo[c], xy[2 * size_t(tri[3 * t + size_t(k)]) + size_t(c)]);
          thi[c] = std::max(thi[c], xy[2 * size_t(tri[3 * t + size_t(k)]) + size_t(c)]);
        }
      int x0, y0, x1, y1;
      cell_of(tlo[0], tlo[1], x0, y0);
      cell_of(thi[0], thi[1], x1, y1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const size_t c = size_t(y) * size_t(f->nx_) + size_t(x);
          if (pass == 0) ++count[c + 1];
          else f->items_[f->start_[c] + count[c]++] = t;
        }
    }
    if (pass == 0) {
      for (size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
      f->start_ = count;
      f->items_.resize(count.back());
      std::fill(count.begin(), count.end(), 0u);
    }
  }
  f->xy_ = std::move(xy);
  f->tri_ = std::move(tri);
  return f;
}

void Background2Field::metric(const double p[3], double m[6]) const {
  // The triangle whose smallest barycentric weight is largest among those of p's cell (and,
  // when the cell is empty, of growing rings around it).
  const int cx = std::clamp(int((p[0] - lo_[0]) / cell_), 0, nx_ - 1), cy = std::clamp(int((p[1] - lo_[1]) / cell_), 0, ny_ - 1);
  double best = -kInf, bw[3] = {1, 0, 0};
  uint32_t bt = 0;
  for (int ring = 0; ring < std::max(nx_, ny_) && best == -kInf; ++ring)
    for (int y = std::max(cy - ring, 0); y <= std::min(cy + ring, ny_ - 1); ++y)
      for (int x = std::max(cx - ring, 0); x <= std::min(cx + ring, nx_ - 1); ++x) {
        if (std::max(std::abs(x - cx), std::abs(y - cy)) != ring) continue;
        const size_t c = size_t(y) * size_t(nx_) + size_t(x);
        for (uint32_t i = start_[c]; i < start_[c + 1]; ++i) {
          const uint32_t t = items_[i];
          const double* a = &xy_[2 * size_t(tri_[3 * t])];
          const double* b = &xy_[2 * size_t(tri_[3 * t + 1])];
          const double* q = &xy_[2 * size_t(tri_[3 * t + 2])];
          const double total = area(a, b, q);
          if (!(total > 0)) continue;
          const double w[3] = {area(p, b, q) / total, area(a, p, q) / total, area(a, b, p) / total};
          const double low = std::min({w[0], w[1], w[2]});
          if (low > best) best = low, bt = t, bw[0] = w[0], bw[1] = w[1], bw[2] = w[2];
        }
      }
  double w[3], sum = 0;
  for (int k = 0; k < 3; ++k) sum += (w[k] = std::max(bw[k], 0.0));
  for (double& x : w) x /= sum > 0 ? sum : 1;
  Metric2 v{0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    const Metric2& l = log_[tri_[3 * size_t(bt) + size_t(k)]];
    v.xx += w[k] * l.xx, v.xy += w[k] * l.xy, v.yy += w[k] * l.yy;
  }
  if (components_ == 1) isotropic_metric(v.xx, m);
  else to_metric6(exp2x2(v), m);
}

Result<std::unique_ptr<SizingField>> read_background_field(const std::string& sol_path, const std::string& mesh_path) {
  Result<metric::SolField> sol = metric::read_sol(sol_path);
  if (!sol.ok()) return sol.status();
  if (sol->dimension != 2)
    return Status(Error::InvalidArgument, sol_path + ": a 3D .sol (Dimension 3); the 2D mesher needs Dimension 2");
  Result<std::string> bytes = read_file_bytes(mesh_path);
  if (!bytes.ok()) return bytes.status();
  Result<Medit2d> mesh = parse_medit2d(bytes.value(), mesh_path);
  if (!mesh.ok()) return mesh.status();
  Result<std::unique_ptr<Background2Field>> f =
      Background2Field::create(std::move(mesh->xy), std::move(mesh->tri), sol->values, sol->components);
  if (!f.ok()) return Status(f.status().code(), sol_path + " on " + mesh_path + ": " + f.status().message());
  return std::unique_ptr<SizingField>(std::move(f.value()));
}

// ---- The field of the options ------------------------------------------------------------------

namespace {

// A constant size or a user field, scaled and bounded, without a lattice.
class DirectField2 final : public SizingField {
 public:
  DirectField2(const SizingOptions2& o) : hsize_(o.hsize), user_(o.metric), scale_(o.scale), hmin_(o.hmin), hmax_(o.hmax) {}
  void metric(const double p[3], double m[6]) const override {
    if (user_) {
      user_->metric(p, m);
      if (hsize_ > 0) {
        double iso[6], both[6];
        isotropic_metric(hsize_, iso);
        if (metric::intersect(m, iso, both)) std::copy(both, both + 6, m);
      }
    } else {
      isotropic_metric(hsize_, m);
    }
    if (scale_ != 1.0) metric::scale(m, 1.0 / (scale_ * scale_), m);
    if (hmin_ > 0 || hmax_ > 0) {
      double c[6];
      if (metric::clamp_sizes(m, hmin_, hmax_, c)) std::copy(c, c + 6, m);
    }
  }
  bool isotropic() const override { return !user_ || user_->isotropic(); }

 private:
  double hsize_;
  const SizingField* user_;
  double scale_, hmin_, hmax_;
};

struct Grid {
  metric::Lattice lattice;
  std::vector<uint8_t> inside;
  int nx = 0, ny = 0;
  void position(int i, int j, double p[2]) const {
    p[0] = lattice.origin[0] + lattice.spacing * i;
    p[1] = lattice.origin[1] + lattice.spacing * j;
  }
  size_t node(int i, int j) const { return size_t(j) * size_t(nx) + size_t(i); }
};

// The paper's grid in 2D: nodes near a segment take its length (pinned, marked in `known`); the
// domain's other nodes are smoothed from them.
int boundary_sizes(const Pslg& p, const Grid& g, std::vector<double>& h, std::vector<uint8_t>& known) {
  const size_t n = size_t(g.nx) * size_t(g.ny);
  const double sp = g.lattice.spacing, reach = 0.5 * std::sqrt(2.0) * sp;
  std::vector<double> pinned(n, kInf);
  for (size_t s = 0; s < p.num_segments(); ++s) {
    const double* a = p.point(p.seg[2 * s]);
    const double* b = p.point(p.seg[2 * s + 1]);
    const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
    const int i0 = std::max(int(std::floor((std::min(a[0], b[0]) - reach - g.lattice.origin[0]) / sp)), 0);
    const int i1 = std::min(int(std::ceil((std::max(a[0], b[0]) + reach - g.lattice.origin[0]) / sp)), g.nx - 1);
    const int j0 = std::max(int(std::floor((std::min(a[1], b[1]) - reach - g.lattice.origin[1]) / sp)), 0);
    const int j1 = std::min(int(std::ceil((std::max(a[1], b[1]) + reach - g.lattice.origin[1]) / sp)), g.ny - 1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        double q[2];
        g.position(i, j, q);
        if (segment_distance(a, b, q) <= reach) pinned[g.node(i, j)] = std::min(pinned[g.node(i, j)], len);
      }
  }
  double mean = 0;
  size_t count = 0;
  for (double v : pinned)
    if (v < kInf) mean += v, ++count;
  mean = count ? mean / double(count) : sp;
  h.assign(n, mean);
  for (size_t i = 0; i < n; ++i)
    if (pinned[i] < kInf) h[i] = pinned[i], known[i] = 1;
  // Over-relaxed Gauss-Seidel on the free inside nodes, over their inside or pinned neighbours.
  int it = 0;
  for (; it < 20000; ++it) {
    double change = 0;
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const size_t c = g.node(i, j);
        if (pinned[c] < kInf || !g.inside[c]) continue;
        double sum = 0;
        int k = 0;
        const int nb[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
        for (const auto& q : nb) {
          if (q[0] < 0 || q[1] < 0 || q[0] >= g.nx || q[1] >= g.ny) continue;
          const size_t d = g.node(q[0], q[1]);
          if (g.inside[d] || pinned[d] < kInf) sum += h[d], ++k;
        }
        if (!k) continue;
        const double target = sum / k, next = h[c] + 1.8 * (target - h[c]);
        change = std::max(change, std::fabs(next - h[c]));
        h[c] = std::max(next, 1e-3 * target);
      }
    if (change < 1e-3 * mean) break;
  }
  return it;
}

// Distance from each node to the nearest segment: exact near each segment, then propagated by
// nearest-segment passes in four orders (each node tries its neighbours' segments).
std::vector<double> segment_distances(const Pslg& p, const Grid& g) {
  const size_t n = size_t(g.nx) * size_t(g.ny);
  std::vector<uint32_t> best(n, kNone);
  std::vector<double> d(n, kInf);
  const double sp = g.lattice.spacing;
  auto offer = [&](size_t c, uint32_t s, const double* q) {
    const double dist = segment_distance(p.point(p.seg[2 * size_t(s)]), p.point(p.seg[2 * size_t(s) + 1]), q);
    if (dist < d[c]) d[c] = dist, best[c] = s;
  };
  for (uint32_t s = 0; s < p.num_segments(); ++s) {
    const double* a = p.point(p.seg[2 * size_t(s)]);
    const double* b = p.point(p.seg[2 * size_t(s) + 1]);
    const int i0 = std::max(int(std::floor((std::min(a[0], b[0]) - g.lattice.origin[0]) / sp)) - 1, 0);
    const int i1 = std::min(int(std::ceil((std::max(a[0], b[0]) - g.lattice.origin[0]) / sp)) + 1, g.nx - 1);
    const int j0 = std::max(int(std::floor((std::min(a[1], b[1]) - g.lattice.origin[1]) / sp)) - 1, 0);
    const int j1 = std::min(int(std::ceil((std::max(a[1], b[1]) - g.lattice.origin[1]) / sp)) + 1, g.ny - 1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        double q[2];
        g.position(i, j, q);
        if (segment_distance(a, b, q) <= 1.5 * sp) offer(g.node(i, j), s, q);
      }
  }
  for (int pass = 0; pass < 2; ++pass)
    for (int order = 0; order < 4; ++order)
      for (int jj = 0; jj < g.ny; ++jj)
        for (int ii = 0; ii < g.nx; ++ii) {
          const int i = (order & 1) ? g.nx - 1 - ii : ii, j = (order & 2) ? g.ny - 1 - jj : jj;
          const size_t c = g.node(i, j);
          double q[2];
          g.position(i, j, q);
          const int nb[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
          for (const auto& o : nb) {
            if (o[0] < 0 || o[1] < 0 || o[0] >= g.nx || o[1] >= g.ny) continue;
            const uint32_t s = best[g.node(o[0], o[1])];
            if (s != kNone && s != best[c]) offer(c, s, q);
          }
        }
  return d;
}

// The nodes not `known` (outside the domain, not on a segment, not pinned) take the value of the
// nearest known one (breadth first), so that bilinear interpolation next to the boundary reads
// domain values only.
void fill_outside(Grid& g, int components, std::vector<uint8_t> done) {
  const size_t n = size_t(g.nx) * size_t(g.ny);
  std::deque<size_t> queue;
  for (size_t c = 0; c < n; ++c)
    if (done[c]) queue.push_back(c);
  if (queue.empty()) return;
  while (!queue.empty()) {
    const size_t c = queue.front();
    queue.pop_front();
    const int i = int(c % size_t(g.nx)), j = int(c / size_t(g.nx));
    const int nb[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
    for (const auto& o : nb) {
      if (o[0] < 0 || o[1] < 0 || o[0] >= g.nx || o[1] >= g.ny) continue;
      const size_t d = g.node(o[0], o[1]);
      if (done[d]) continue;
      done[d] = 1;
      std::copy_n(&g.lattice.values[c * size_t(components)], components, &g.lattice.values[d * size_t(components)]);
      queue.push_back(d);
    }
  }
}

// Smallest size of a field sampled over the input's points and a 32 x 32 grid over its box.
double smallest_size(const SizingField& f, const Pslg& p, const double lo[2], const double hi[2]) {
  double best = kInf;
  auto probe = [&](double x, double y) {
    const Metric2 m = metric_at(f, x, y);
    const double mean = 0.5 * (m.xx + m.yy), dev = std::sqrt(0.25 * (m.xx - m.yy) * (m.xx - m.yy) + m.xy * m.xy);
    if (mean + dev > 0) best = std::min(best, 1.0 / std::sqrt(mean + dev));
  };
  for (size_t v = 0; v < p.num_points(); ++v) probe(p.xy[2 * v], p.xy[2 * v + 1]);
  for (int j = 0; j <= 32; ++j)
    for (int i = 0; i <= 32; ++i) probe(lo[0] + (hi[0] - lo[0]) * i / 32.0, lo[1] + (hi[1] - lo[1]) * j / 32.0);
  return best;
}

// The size for a regional area bound A: edges up to sqrt(2) h enclose at most the equilateral
// triangle of side sqrt(2) h, whose area is A for h = sqrt(2 A / sqrt(3)).
double area_size(double max_area) { return std::sqrt(2.0 * max_area / std::sqrt(3.0)); }

double wavelength_size(const SizingOptions2& o, double value) {
  double depth = o.elevation ? -value : value;
  if (!(depth > o.min_depth)) depth = o.min_depth;  // NaN (no data), land, shallows
  return o.wave_period * std::sqrt(9.80665 * depth) / o.points_per_wavelength;
}

// The lattice's spacing (unless given): the smallest size asked for, or the input's typical
// segment length when nothing is asked, times o.scale; at least hmin / 2.
double lattice_spacing(const Pslg& p, const Domain& domain, const SizingOptions2& o, bool has_source,
                       const double lo[2], const double hi[2]) {
  double natural = kInf;
  if (!has_source) {
    std::vector<double> len(p.num_segments());
    double mean = 0;
    for (size_t s = 0; s < len.size(); ++s) {
      const double* a = p.point(p.seg[2 * s]);
      const double* b = p.point(p.seg[2 * s + 1]);
      mean += (len[s] = std::hypot(b[0] - a[0], b[1] - a[1]));
    }
    mean /= double(std::max<size_t>(len.size(), 1));
    std::nth_element(len.begin(), len.begin() + long(len.size() / 2), len.end());
    natural = std::min(mean, 2.0 * len[len.size() / 2]);
  }
  if (o.hsize > 0) natural = std::min(natural, o.hsize);
  if (o.distance_h0 > 0) natural = std::min(natural, o.distance_h0);
  if (o.metric) natural = std::min(natural, smallest_size(*o.metric, p, lo, hi));
  for (size_t f = 0; f < domain.face_max_area.size(); ++f)
    if (domain.face_max_area[f] > 0) natural = std::min(natural, area_size(domain.face_max_area[f]));
  if (o.bathymetry) natural = std::min(natural, std::max(hi[0] - lo[0], hi[1] - lo[1]) / 256.0);
  double sp = o.spacing > 0 ? o.spacing : natural * o.scale;
  if (o.hmin > 0) sp = std::max(sp, 0.5 * o.hmin);
  if (!(sp > 0) || !std::isfinite(sp)) sp = std::max(hi[0] - lo[0], hi[1] - lo[1]) / 64.0;
  return sp;
}

// Regional area bounds as sizes, spread to the nodes around their faces too: a cell across a
// face's border then interpolates the bound, not the larger size outside.
void apply_area_bounds(const Domain& domain, const Grid& g, const std::vector<uint32_t>& face, std::vector<double>& h) {
  const size_t n = h.size();
  std::vector<double> bound(n, kInf);
  for (size_t c = 0; c < n; ++c)
    if (face[c] != kNone && domain.face_max_area[face[c]] > 0) bound[c] = area_size(domain.face_max_area[face[c]]);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      double b = kInf;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int x = i + di, y = j + dj;
          if (x >= 0 && y >= 0 && x < g.nx && y < g.ny) b = std::min(b, bound[g.node(x, y)]);
        }
      h[g.node(i, j)] = std::min(h[g.node(i, j)], b);
    }
}

}  // namespace

Result<std::unique_ptr<SizingField>> build_sizing2(const Pslg& p, const Domain& domain, const SizingOptions2& o,
                                                   SizingStats2* stats) {
  SizingStats2 local;
  SizingStats2& st = stats ? *stats : local;
  if (!(o.scale > 0) || o.hsize < 0 || o.hmin < 0 || o.hmax < 0 || (o.hmin > 0 && o.hmax > 0 && o.hmin > o.hmax) ||
      (o.hgrad != 0 && !(o.hgrad > 1)) || o.distance_h0 < 0 || o.distance_rate < 0 ||
      (o.bathymetry && !(o.wave_period > 0 && o.points_per_wavelength > 0 && o.min_depth > 0)))
    return Status(Error::InvalidArgument, "sizing: sizes and scales must be positive, hmin <= hmax, hgrad > 1");
  bool area_bound = false;
  for (double a : domain.face_max_area) area_bound |= a > 0;
  const bool has_source = o.hsize > 0 || o.metric || o.distance_h0 > 0 || o.bathymetry;
  std::vector<std::string> names;
  if (!has_source) names.push_back("boundary");
  if (o.hsize > 0) names.push_back("constant");
  if (o.metric) names.push_back("metric");
  if (o.distance_h0 > 0) names.push_back("distance");
  if (o.bathymetry) names.push_back("bathymetry");
  if (area_bound) names.push_back("region areas");
  for (size_t i = 0; i < names.size(); ++i) st.source += (i ? " + " : "") + names[i];
  if (has_source && !(o.hgrad > 0) && o.distance_h0 == 0 && !o.bathymetry && !area_bound)
    return std::unique_ptr<SizingField>(new DirectField2(o));

  // The lattice over the input's box, two cells of margin.
  double lo[2] = {kInf, kInf}, hi[2] = {-kInf, -kInf};
  for (size_t i = 0; i < p.xy.size(); ++i) lo[i % 2] = std::min(lo[i % 2], p.xy[i]), hi[i % 2] = std::max(hi[i % 2], p.xy[i]);
  double sp = lattice_spacing(p, domain, o, has_source, lo, hi);
  Grid g;
  // (Counted in doubles: a thin input's node count along its long side may pass INT_MAX.)
  const auto nodes_along = [&](int axis) { return std::ceil((hi[axis] - lo[axis]) / sp) + 5; };
  while (nodes_along(0) * nodes_along(1) > double(o.max_nodes)) sp *= 1.25;
  g.nx = int(nodes_along(0));
  g.ny = int(nodes_along(1));
  metric::Lattice& l = g.lattice;
  l.origin[0] = lo[0] - 2 * sp, l.origin[1] = lo[1] - 2 * sp, l.origin[2] = 0.0;
  l.spacing = sp;
  l.dims[0] = g.nx, l.dims[1] = g.ny, l.dims[2] = 1;
  st.lattice = true;
  st.nx = g.nx, st.ny = g.ny, st.spacing = sp;
  const size_t n = size_t(g.nx) * size_t(g.ny);
  // Which nodes are inside, and their faces (for regional area bounds). Nodes on a segment are
  // known too (their values are the boundary's).
  g.inside.assign(n, 0);
  std::vector<uint8_t> known(n, 0);
  std::vector<uint32_t> face(n, kNone);
  uint32_t hint = kNone;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      double q[2];
      g.position(i, j, q);
      const uint32_t f = domain.face_at(q, hint);
      face[g.node(i, j)] = f;
      g.inside[g.node(i, j)] = f != kNone && domain.face_inside[f];
      known[g.node(i, j)] = f == kNone || g.inside[g.node(i, j)];
    }
  // Isotropic sizes of every source but the metric.
  std::vector<double> h(n, kInf);
  if (!has_source) st.smoothing_iterations = boundary_sizes(p, g, h, known);
  if (o.hsize > 0)
    for (double& x : h) x = std::min(x, o.hsize);
  if (o.distance_h0 > 0) {
    const std::vector<double> d = segment_distances(p, g);
    for (size_t c = 0; c < n; ++c) h[c] = std::min(h[c], o.distance_h0 + o.distance_rate * d[c]);
  }
  if (area_bound) apply_area_bounds(domain, g, face, h);
  if (o.bathymetry) {
    std::vector<double> q(2 * n);
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) g.position(i, j, &q[2 * g.node(i, j)]);
    if (o.to_raster_frame)
      if (Status s = o.to_raster_frame(q); !s.ok()) return s;
    for (size_t c = 0; c < n; ++c) h[c] = std::min(h[c], wavelength_size(o, o.bathymetry->value(q[2 * c], q[2 * c + 1])));
  }
  // The metric, intersected with them; one component when everything is isotropic.
  bool tensors = false;
  std::vector<Metric2> m;
  if (o.metric) {
    m.resize(n);
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        double q[2];
        g.position(i, j, q);
        Metric2& x = m[g.node(i, j)];
        x = metric_at(*o.metric, q[0], q[1]);
        if (!is_spd(x)) return Status(Error::InvalidArgument, "sizing: the metric is not positive definite at (" +
                                                                  std::to_string(q[0]) + ", " + std::to_string(q[1]) + ")");
        double six[6];
        to_metric6(x, six);
        tensors |= !metric_is_isotropic(six);
      }
  }
  l.components = tensors ? 6 : 1;
  l.values.assign(n * size_t(l.components), 0.0);
  for (size_t c = 0; c < n; ++c) {
    if (!tensors) {
      double v = h[c];
      if (o.metric) v = std::min(v, 1.0 / std::sqrt(m[c].xx));
      l.values[c] = std::isfinite(v) ? v : 1.0;
      continue;
    }
    double a[6], b[6], both[6];
    to_metric6(m[c], a);
    if (std::isfinite(h[c])) {
      isotropic_metric(h[c], b);
      if (metric::intersect(a, b, both)) std::copy(both, both + 6, a);
    }
    const Metric2 lg = log2x2(Metric2{a[0], a[1], a[2]});
    double* out = &l.values[6 * c];
    out[0] = lg.xx, out[1] = lg.xy, out[2] = lg.yy, out[3] = 0, out[4] = 0, out[5] = 0.5 * (lg.xx + lg.yy);
  }
  fill_outside(g, l.components, std::move(known));
  if (o.scale != 1.0) {
    if (!tensors) {
      for (double& v : l.values) v *= o.scale;
    } else {
      const double s = -2.0 * std::log(o.scale);
      for (size_t c = 0; c < n; ++c) l.values[6 * c] += s, l.values[6 * c + 2] += s, l.values[6 * c + 5] += s;
    }
  }
  if (o.hmin > 0 || o.hmax > 0)
    if (Status s = metric::bound_sizes(l, o.hmin, o.hmax); !s.ok()) return s;
  if (o.hgrad > 0) {
    Result<metric::GradationStats> gs = metric::grade(l, o.hgrad);
    if (!gs.ok()) return gs.status();
    st.gradation_passes = gs->passes;
  }
  return std::unique_ptr<SizingField>(new LatticeField2(std::move(l)));
}

}  // namespace anitet::mesh2d
