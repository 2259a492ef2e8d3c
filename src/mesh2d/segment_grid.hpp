// A uniform grid of segments (by their bounding boxes): the neighbour searches of the input's
// crossing check and of stage 1's front. Segments are numbered by the caller; removed ones are
// skipped lazily.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace anitet::mesh2d {

class SegmentGrid {
 public:
  // Empty, over the box lo..hi with about `cells` cells in all (the box grows to hold
  // everything inserted later: cells clamp, so far points only cost time).
  SegmentGrid(const double lo[2], const double hi[2], size_t cells);
  // Holding the segments seg (2 point indices each) of the points xy (2 per point), numbered
  // as in seg; about one cell per segment.
  SegmentGrid(const std::vector<double>& xy, const std::vector<uint32_t>& seg);

  void insert(uint32_t id, const double* a, const double* b);
  void remove(uint32_t id) {
    if (id < alive_.size()) alive_[id] = 0;
  }

  // f(id) for each live segment whose box meets the box lo..hi, once each; stops (and returns
  // false) when f returns false.
  template <class F>
  bool for_each_in_box(const double lo[2], const double hi[2], F&& f) {
    int c[4];
    cell_range(lo, hi, c);
    if (++epoch_ == 0) {
      std::fill(stamp_.begin(), stamp_.end(), 0u);
      epoch_ = 1;
    }
    for (int j = c[1]; j <= c[3]; ++j)
      for (int i = c[0]; i <= c[2]; ++i)
        for (uint32_t id : cells_[size_t(j) * size_t(nx_) + size_t(i)]) {
          if (!alive_[id] || stamp_[id] == epoch_) continue;
          stamp_[id] = epoch_;
          if (!f(id)) return false;
        }
    return true;
  }
  template <class F>
  bool for_each_near(double x, double y, F&& f) {
    const double p[2] = {x, y};
    return for_each_in_box(p, p, f);
  }
  // f(s, t), s < t, once for each pair of live segments whose boxes share a cell.
  template <class F>
  bool for_each_pair(F&& f) {
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i) {
        const std::vector<uint32_t>& ids = cells_[size_t(j) * size_t(nx_) + size_t(i)];
        for (size_t u = 0; u < ids.size(); ++u)
          for (size_t v = u + 1; v < ids.size(); ++v) {
            const uint32_t s = std::min(ids[u], ids[v]), t = std::max(ids[u], ids[v]);
            if (!alive_[s] || !alive_[t]) continue;
            // Tested in the first cell the two boxes share only.
            const int* a = &range_[4 * size_t(s)];
            const int* b = &range_[4 * size_t(t)];
            if (std::max(a[0], b[0]) != i || std::max(a[1], b[1]) != j) continue;
            if (!f(s, t)) return false;
          }
      }
    return true;
  }

 private:
  void cell_range(const double lo[2], const double hi[2], int c[4]) const;
  void setup(const double lo[2], const double hi[2], size_t cells);

  double lo_[2] = {0, 0};
  double inv_cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<uint32_t>> cells_;
  std::vector<int> range_;  // 4 per id: the cells ix0 iy0 ix1 iy1 of its box
  std::vector<uint8_t> alive_;
  std::vector<uint32_t> stamp_;
  uint32_t epoch_ = 0;
};

}  // namespace anitet::mesh2d
