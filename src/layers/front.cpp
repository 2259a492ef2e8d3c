#include "layers/front.hpp"

#include <algorithm>

namespace anitet::layers {

Front::Front(const std::vector<double>& xyz, const Box3& bounds) : xyz_(xyz), bounds_(bounds) {
  index_.reset(bounds);
}

Front::Front(const Front& from, const std::vector<double>& xyz, int axis, double cut, bool low_side)
    : xyz_(xyz), tri_(from.tri_), owner_(from.owner_), box_(from.box_),
      alive_(from.alive_.size(), 0), bounds_(from.bounds_), reuse_slots_(false) {
  index_.reset(bounds_);
  for (uint32_t f = 0; f < from.alive_.size(); ++f) {
    if (!from.alive_[f]) continue;
    const Box3& b = from.box_[f];
    if (!(low_side ? b.lo[axis] < cut : b.hi[axis] > cut)) continue;
    index_.insert(f, box_[f]);
    alive_[f] = 1;
    ++num_alive_;
  }
  // Each star in from's order (a push takes its star in that order: the same tets as on from).
  star_.resize(from.star_.size());
  for (size_t v = 0; v < from.star_.size(); ++v)
    for (uint32_t f : from.star_[v])
      if (alive_[f]) star_[v].push_back(f);
}

namespace {

Box3 triangle_box(const std::vector<double>& xyz, const uint32_t* t) {
  Box3 b;
  for (int k = 0; k < 3; ++k) {
    const double x = xyz[3 * size_t(t[0]) + k], y = xyz[3 * size_t(t[1]) + k],
                 z = xyz[3 * size_t(t[2]) + k];
    b.lo[k] = std::min(x, std::min(y, z));
    b.hi[k] = std::max(x, std::max(y, z));
  }
  return b;
}

}  // namespace

void Front::link(uint32_t f) {
  const uint32_t* t = tri(f);
  for (int k = 0; k < 3; ++k) {
    if (star_.size() <= t[k]) star_.resize(size_t(t[k]) + 1);
    star_[t[k]].push_back(f);
  }
  box_[f] = triangle_box(xyz_, t);
  index_.insert(f, box_[f]);
  alive_[f] = 1;
  ++num_alive_;
}

void Front::unlink(uint32_t f) {
  const uint32_t* t = tri(f);
  for (int k = 0; k < 3; ++k) {
    std::vector<uint32_t>& s = star_[t[k]];
    auto it = std::find(s.begin(), s.end(), f);
    *it = s.back();
    s.pop_back();
  }
  index_.erase(f);
  alive_[f] = 0;
  --num_alive_;
}

uint32_t Front::add(uint32_t a, uint32_t b, uint32_t c, uint32_t owner_tet) {
  uint32_t f;
  if (reuse_slots_ && !free_.empty()) {
    f = free_.back();
    free_.pop_back();
  } else {
    f = static_cast<uint32_t>(alive_.size());
    tri_.resize(tri_.size() + 3);
    owner_.push_back(kNone);
    box_.emplace_back();
    alive_.push_back(0);
  }
  tri_[3 * size_t(f)] = a;
  tri_[3 * size_t(f) + 1] = b;
  tri_[3 * size_t(f) + 2] = c;
  owner_[f] = owner_tet;
  link(f);
  if (in_transaction_) log_.push_back(int64_t(f) + 1);
  return f;
}

void Front::remove(uint32_t f) {
  unlink(f);
  if (in_transaction_) {
    log_.push_back(-(int64_t(f) + 1));
    pending_free_.push_back(f);
  } else {
    free_.push_back(f);
  }
}

uint32_t Front::find(uint32_t a, uint32_t b, uint32_t c) const {
  for (uint32_t f : star(a)) {
    const uint32_t* t = tri(f);
    const bool has_b = t[0] == b || t[1] == b || t[2] == b;
    const bool has_c = t[0] == c || t[1] == c || t[2] == c;
    if (has_b && has_c) return f;
  }
  return kNone;
}

void Front::begin() {
  in_transaction_ = true;
  log_.clear();
  pending_free_.clear();
}

void Front::commit() {
  in_transaction_ = false;
  free_.insert(free_.end(), pending_free_.begin(), pending_free_.end());
  pending_free_.clear();
  log_.clear();
}

void Front::rollback() {
  in_transaction_ = false;
  for (auto it = log_.rbegin(); it != log_.rend(); ++it) {
    if (*it > 0) {
      const auto f = static_cast<uint32_t>(*it - 1);
      unlink(f);
      free_.push_back(f);
    } else {
      link(static_cast<uint32_t>(-*it - 1));  // slot data untouched since its removal
    }
  }
  // Slots removed inside the transaction were held back from free_, and are alive again now.
  pending_free_.clear();
  log_.clear();
}

}  // namespace anitet::layers
