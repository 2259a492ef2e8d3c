#include "mesh2d/segment_grid.hpp"

#include <limits>

namespace anitet::mesh2d {

void SegmentGrid::setup(const double lo[2], const double hi[2], size_t cells) {
  const double w = std::max(hi[0] - lo[0], 0.0), h = std::max(hi[1] - lo[1], 0.0);
  cells = std::clamp<size_t>(cells, 1, size_t(1) << 22);
  double cell = std::sqrt(w * h / double(cells));
  if (!(cell > 0)) cell = std::max(w, h) / double(cells);
  if (!(cell > 0) || !std::isfinite(cell)) cell = 1.0;
  nx_ = int(std::clamp(std::floor(w / cell) + 1, 1.0, 4096.0));
  ny_ = int(std::clamp(std::floor(h / cell) + 1, 1.0, 4096.0));
  cell = std::max({cell, w / nx_, h / ny_});
  inv_cell_ = 1.0 / cell;
  lo_[0] = lo[0];
  lo_[1] = lo[1];
  cells_.assign(size_t(nx_) * size_t(ny_), {});
}

SegmentGrid::SegmentGrid(const double lo[2], const double hi[2], size_t cells) { setup(lo, hi, cells); }

SegmentGrid::SegmentGrid(const std::vector<double>& xy, const std::vector<uint32_t>& seg) {
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  for (uint32_t v : seg)
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], xy[2 * size_t(v) + size_t(k)]);
      hi[k] = std::max(hi[k], xy[2 * size_t(v) + size_t(k)]);
    }
  if (seg.empty()) lo[0] = lo[1] = hi[0] = hi[1] = 0;
  setup(lo, hi, seg.size() / 2);
  for (size_t s = 0; s < seg.size() / 2; ++s)
    insert(uint32_t(s), &xy[2 * size_t(seg[2 * s])], &xy[2 * size_t(seg[2 * s + 1])]);
}

void SegmentGrid::cell_range(const double lo[2], const double hi[2], int c[4]) const {
  auto cell = [&](double v, double origin, int n) {
    const double f = std::floor((v - origin) * inv_cell_);
    return int(std::clamp(f, 0.0, double(n - 1)));  // NaN clamps to 0
  };
  c[0] = cell(lo[0], lo_[0], nx_);
  c[1] = cell(lo[1], lo_[1], ny_);
  c[2] = cell(hi[0], lo_[0], nx_);
  c[3] = cell(hi[1], lo_[1], ny_);
}

void SegmentGrid::insert(uint32_t id, const double* a, const double* b) {
  if (id >= alive_.size()) {
    alive_.resize(size_t(id) + 1, 0);
    stamp_.resize(size_t(id) + 1, 0);
    range_.resize(4 * (size_t(id) + 1), 0);
  }
  const double lo[2] = {std::min(a[0], b[0]), std::min(a[1], b[1])};
  const double hi[2] = {std::max(a[0], b[0]), std::max(a[1], b[1])};
  int* c = &range_[4 * size_t(id)];
  cell_range(lo, hi, c);
  alive_[id] = 1;
  for (int j = c[1]; j <= c[3]; ++j)
    for (int i = c[0]; i <= c[2]; ++i) cells_[size_t(j) * size_t(nx_) + size_t(i)].push_back(id);
}

}  // namespace anitet::mesh2d
