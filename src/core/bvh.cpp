#include "core/bvh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace anitet {

namespace {

constexpr uint32_t kLeafSize = 4;

Box3 empty_box() {
  const double inf = std::numeric_limits<double>::infinity();
  return Box3{{inf, inf, inf}, {-inf, -inf, -inf}};
}

void grow(Box3& box, const Box3& other) {
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = std::min(box.lo[k], other.lo[k]);
    box.hi[k] = std::max(box.hi[k], other.hi[k]);
  }
}

// A NaN centre would break the strict weak ordering nth_element relies on.
double finite_or_zero(double x) { return std::isfinite(x) ? x : 0.0; }

}  // namespace

void TriangleBVH::build(const double* xyz, const uint32_t* tri, size_t num_triangles) {
  nodes_.clear();
  order_.resize(num_triangles);
  tri_box_.resize(num_triangles);
  std::vector<double> centre(3 * num_triangles);
  for (size_t t = 0; t < num_triangles; ++t) {
    Box3 box = empty_box();
    for (int c = 0; c < 3; ++c) {
      const double* p = xyz + 3 * size_t(tri[3 * t + c]);
      for (int k = 0; k < 3; ++k) {
        box.lo[k] = std::min(box.lo[k], p[k]);
        box.hi[k] = std::max(box.hi[k], p[k]);
      }
    }
    tri_box_[t] = box;
    for (int k = 0; k < 3; ++k) centre[3 * t + k] = finite_or_zero(0.5 * (box.lo[k] + box.hi[k]));
    order_[t] = static_cast<uint32_t>(t);
  }
  if (num_triangles == 0) return;

  // Object-median split on the widest axis of the centres: balanced, depth <= log2(n) + 1.
  struct Task {
    uint32_t node, begin, end;
  };
  std::vector<Task> stack;
  nodes_.reserve(2 * (num_triangles / kLeafSize + 1));
  nodes_.push_back(Node{empty_box(), 0, 0});
  stack.push_back(Task{0, 0, static_cast<uint32_t>(num_triangles)});
  while (!stack.empty()) {
    const Task task = stack.back();
    stack.pop_back();
    Box3 box = empty_box();
    Box3 centres = empty_box();
    for (uint32_t k = task.begin; k < task.end; ++k) {
      const uint32_t t = order_[k];
      grow(box, tri_box_[t]);
      const double* c = &centre[3 * size_t(t)];
      grow(centres, Box3{{c[0], c[1], c[2]}, {c[0], c[1], c[2]}});
    }
    nodes_[task.node].box = box;
    const uint32_t count = task.end - task.begin;
    if (count <= kLeafSize) {
      nodes_[task.node].first = task.begin;
      nodes_[task.node].count = count;
      continue;
    }
    int axis = 0;
    for (int k = 1; k < 3; ++k) {
      if (centres.hi[k] - centres.lo[k] > centres.hi[axis] - centres.lo[axis]) axis = k;
    }
    const uint32_t mid = task.begin + count / 2;
    std::nth_element(order_.begin() + task.begin, order_.begin() + mid, order_.begin() + task.end,
                     [&](uint32_t a, uint32_t b) {
                       return centre[3 * size_t(a) + axis] < centre[3 * size_t(b) + axis];
                     });
    const auto left = static_cast<uint32_t>(nodes_.size());
    nodes_.push_back(Node{empty_box(), 0, 0});
    nodes_.push_back(Node{empty_box(), 0, 0});
    nodes_[task.node].first = left;
    nodes_[task.node].count = 0;
    stack.push_back(Task{left, task.begin, mid});
    stack.push_back(Task{left + 1, mid, task.end});
  }
}

}  // namespace anitet
