#include "adapt/adapt_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/metric_measures.hpp"
#include "predicates/predicates.hpp"

namespace anitet::adapt {

void other_two(int ia, int ib, int& i, int& j) {
  int rest[2], n = 0;
  for (int k = 0; k < 4; ++k)
    if (k != ia && k != ib) rest[n++] = k;
  const int perm[4] = {ia, ib, rest[0], rest[1]};
  int inversions = 0;
  for (int x = 0; x < 4; ++x)
    for (int y = x + 1; y < 4; ++y) inversions += perm[x] > perm[y];
  if (inversions % 2 == 0) {
    i = rest[0];
    j = rest[1];
  } else {
    i = rest[1];
    j = rest[0];
  }
}

uint32_t AdaptMesh::add_point(const double x[3], const double mm[6], uint8_t t, uint32_t h) {
  const auto v = static_cast<uint32_t>(tag.size());
  xyz.insert(xyz.end(), x, x + 3);
  met.insert(met.end(), mm, mm + 6);
  mdet.push_back(metric_det(mm));
  for (auto* g : {&nrm, &nrm2, &tng}) g->insert(g->end(), 3, 0.0);
  tag.push_back(t);
  ptet.push_back(kNone);
  hint.push_back(h);
  touched.push_back(epoch);
  pmark_.push_back(0);
  return v;
}

void AdaptMesh::set_metric(uint32_t v, const double mm[6]) {
  for (int k = 0; k < 6; ++k) met[6 * size_t(v) + size_t(k)] = mm[k];
  mdet[v] = metric_det(mm);
}

uint32_t AdaptMesh::new_tet(uint32_t a, uint32_t b, uint32_t c, uint32_t d, int32_t reg) {
  uint32_t t;
  if (!free_tets.empty()) {
    t = free_tets.back();
    free_tets.pop_back();
  } else {
    t = static_cast<uint32_t>(num_slots());
    tv.resize(tv.size() + 4);
    adj.resize(adj.size() + 4);
    fref.resize(fref.size() + 4);
    bnd.push_back(0);
    region.push_back(0);
    qual.push_back(0.0);
    tmark_.push_back(0);
  }
  uint32_t* w = &tv[4 * size_t(t)];
  w[0] = a, w[1] = b, w[2] = c, w[3] = d;
  for (int i = 0; i < 4; ++i) adj[4 * size_t(t) + i] = kNone, fref[4 * size_t(t) + i] = 0;
  bnd[t] = 0;
  region[t] = reg;
  return t;
}

void AdaptMesh::delete_tet(uint32_t t) {
  bnd[t] = kTetDeleted;
  free_tets.push_back(t);
}

uint32_t AdaptMesh::next_stamp() {
  if (++stamp_ == 0) {  // wrapped: clear every mark once
    std::fill(tmark_.begin(), tmark_.end(), 0);
    std::fill(pmark_.begin(), pmark_.end(), 0);
    stamp_ = 1;
  }
  return stamp_;
}

void AdaptMesh::sync_marks() {
  tmark_.resize(num_slots(), 0);
  pmark_.resize(num_points(), 0);
}

uint32_t AdaptMesh::tet_of(uint32_t v) {
  uint32_t t = ptet[v];
  if (t != kNone && t < num_slots() && !dead(t) && local(t, v) >= 0) return t;
  for (t = 0; t < num_slots(); ++t)
    if (!dead(t) && local(t, v) >= 0) return ptet[v] = t;
  return ptet[v] = kNone;
}

void AdaptMesh::ball(uint32_t v, std::vector<uint32_t>& out) {
  out.clear();
  const uint32_t t0 = tet_of(v);
  if (t0 == kNone) return;
  next_stamp();
  out.push_back(t0);
  mark_tet(t0);
  for (size_t k = 0; k < out.size(); ++k) {
    const uint32_t t = out[k];
    const uint32_t* w = verts(t);
    for (int i = 0; i < 4; ++i) {
      if (w[i] == v) continue;
      const uint32_t a = adj[4 * size_t(t) + i];
      if (a == kNone) continue;
      const uint32_t n = adj_tet(a);
      if (tet_marked(n)) continue;
      mark_tet(n);
      out.push_back(n);
    }
  }
}

uint32_t AdaptMesh::edge_tet(uint32_t a, uint32_t b, std::vector<uint32_t>& scratch) {
  ball(a, scratch);
  for (uint32_t t : scratch)
    if (local(t, b) >= 0) return t;
  return kNone;
}

bool AdaptMesh::shell(uint32_t a, uint32_t b, uint32_t t0, Shell& s, size_t max_tets) const {
  s.tets.clear();
  s.ring.clear();
  s.open = false;
  s.num_boundary = 0;
  const int ia = local(t0, a), ib = local(t0, b);
  if (ia < 0 || ib < 0) return false;
  int ix, iy;
  other_two(ia, ib, ix, iy);
  const uint32_t x0 = verts(t0)[ix], y0 = verts(t0)[iy];
  // Forward: leave (a b x y) across the face opposite x (a b y).
  s.tets.push_back(t0);
  s.ring.push_back(x0);
  s.ring.push_back(y0);
  uint32_t t = t0, y = y0;
  int fx = ix;
  for (;;) {
    const uint32_t n = adj[4 * size_t(t) + fx];
    if (n == kNone) {
      s.open = true;
      break;
    }
    const uint32_t nt = adj_tet(n);
    if (nt == t0) {
      s.ring.pop_back();  // back at x0
      break;
    }
    if (s.tets.size() >= max_tets) return false;
    const uint32_t* w = verts(nt);
    int iz = -1, iyn = -1;
    for (int k = 0; k < 4; ++k) {
      if (w[k] == y) iyn = k;
      else if (w[k] != a && w[k] != b) iz = k;
    }
    if (iz < 0 || iyn < 0) return false;
    s.tets.push_back(nt);
    s.ring.push_back(w[iz]);
    t = nt;
    y = w[iz];
    fx = iyn;
  }
  if (s.open) {
    // Backward from t0 across the face opposite y0 (a b x0), prepending.
    std::vector<uint32_t> back_tets, back_ring;
    t = t0;
    uint32_t x = x0;
    int fy = iy;
    for (;;) {
      const uint32_t n = adj[4 * size_t(t) + fy];
      if (n == kNone) break;
      const uint32_t nt = adj_tet(n);
      if (s.tets.size() + back_tets.size() >= max_tets) return false;
      const uint32_t* w = verts(nt);
      int iz = -1, ixn = -1;
      for (int k = 0; k < 4; ++k) {
        if (w[k] == x) ixn = k;
        else if (w[k] != a && w[k] != b) iz = k;
      }
      if (iz < 0 || ixn < 0) return false;
      back_tets.push_back(nt);
      back_ring.push_back(w[iz]);
      t = nt;
      x = w[iz];
      fy = ixn;
    }
    if (!back_tets.empty()) {
      std::reverse(back_tets.begin(), back_tets.end());
      std::reverse(back_ring.begin(), back_ring.end());
      s.tets.insert(s.tets.begin(), back_tets.begin(), back_tets.end());
      s.ring.insert(s.ring.begin(), back_ring.begin(), back_ring.end());
    }
  }
  // Boundary faces through ab: in tets[k], the face (a b ring[k]) is opposite ring[k+1]; the
  // open shell's last face (a b ring.back()) is opposite ring[k] of the last tet.
  auto note = [&](uint32_t tt, uint32_t opposite, uint32_t ring_index) {
    const int f = local(tt, opposite);
    if (!is_bnd_face(tt, f)) return;
    if (s.num_boundary < 4) {
      s.bnd_ring[size_t(s.num_boundary)] = ring_index;
      s.bnd_label[size_t(s.num_boundary)] = fref[4 * size_t(tt) + f];
    }
    ++s.num_boundary;
  };
  const size_t k = s.tets.size();
  for (size_t i = 0; i < k; ++i) note(s.tets[i], s.ring_at(i + 1), uint32_t(i));
  if (s.open) note(s.tets[k - 1], s.ring[k - 1], uint32_t(k));
  return true;
}

std::string AdaptMesh::check() const {
  std::ostringstream out;
  for (uint32_t t = 0; t < num_slots(); ++t) {
    if (dead(t)) continue;
    const uint32_t* w = verts(t);
    for (int i = 0; i < 4; ++i) {
      if (w[i] >= num_points() || (tag[w[i]] & ptag::kRemoved)) {
        out << "tet " << t << " has a removed or missing point " << w[i];
        return out.str();
      }
    }
    if (predicates::orient3d(p(w[0]), p(w[1]), p(w[2]), p(w[3])) <= 0) {
      out << "tet " << t << " is not positive";
      return out.str();
    }
    for (int i = 0; i < 4; ++i) {
      const uint32_t a = adj[4 * size_t(t) + i];
      if (a == kNone) {
        if (!is_bnd_face(t, i)) {
          out << "hull face " << i << " of tet " << t << " is not a boundary face";
          return out.str();
        }
        continue;
      }
      const uint32_t n = adj_tet(a);
      const int j = adj_face(a);
      if (n >= num_slots() || dead(n) || adj[4 * size_t(n) + j] != 4 * t + uint32_t(i)) {
        out << "face " << i << " of tet " << t << ": neighbour " << n << " does not point back";
        return out.str();
      }
      std::array<uint32_t, 3> f1, f2;
      for (int k = 0; k < 3; ++k) f1[size_t(k)] = w[kFaceVertex[i][k]], f2[size_t(k)] = verts(n)[kFaceVertex[j][k]];
      std::sort(f1.begin(), f1.end());
      std::sort(f2.begin(), f2.end());
      if (f1 != f2) {
        out << "face " << i << " of tet " << t << " does not match its neighbour's";
        return out.str();
      }
      if (is_bnd_face(t, i) != is_bnd_face(n, j) ||
          (is_bnd_face(t, i) && fref[4 * size_t(t) + i] != fref[4 * size_t(n) + j])) {
        out << "face " << i << " of tet " << t << ": boundary flags differ across it";
        return out.str();
      }
    }
  }
  {  // The tets fill the region the hull faces bound: the volumes agree (an overlap adds volume).
    long double vt = 0, vs = 0, scale = 0;
    for (uint32_t t = 0; t < num_slots(); ++t) {
      if (dead(t)) continue;
      const double *a = p(verts(t)[0]), *b = p(verts(t)[1]), *c = p(verts(t)[2]), *d = p(verts(t)[3]);
      const long double v = ((long double)(b[0] - a[0]) * ((c[1] - a[1]) * (d[2] - a[2]) - (c[2] - a[2]) * (d[1] - a[1])) -
                             (long double)(b[1] - a[1]) * ((c[0] - a[0]) * (d[2] - a[2]) - (c[2] - a[2]) * (d[0] - a[0])) +
                             (long double)(b[2] - a[2]) * ((c[0] - a[0]) * (d[1] - a[1]) - (c[1] - a[1]) * (d[0] - a[0]))) / 6;
      vt += v;
      scale += std::fabs((double)v);
      for (int i = 0; i < 4; ++i) {
        if (adj[4 * size_t(t) + i] != kNone) continue;
        // Out of the tet: kFaceVertex reversed; volume of the cone from the origin.
        const double *x = p(verts(t)[kFaceVertex[i][0]]), *y = p(verts(t)[kFaceVertex[i][2]]), *z = p(verts(t)[kFaceVertex[i][1]]);
        vs += ((long double)x[0] * (y[1] * z[2] - y[2] * z[1]) - (long double)x[1] * (y[0] * z[2] - y[2] * z[0]) +
               (long double)x[2] * (y[0] * z[1] - y[1] * z[0])) / 6;
      }
    }
    if (std::fabs((double)(vt - vs)) > 1e-9 * (double)scale) {
      out << "the tets' volume " << (double)vt << " is not the hull's " << (double)vs << " (an overlap)";
      return out.str();
    }
  }
  {  // The hull is a closed manifold: each of its edges in two hull faces.
    std::vector<uint64_t> e;
    for (uint32_t t = 0; t < num_slots(); ++t) {
      if (dead(t)) continue;
      for (int i = 0; i < 4; ++i) {
        if (adj[4 * size_t(t) + i] != kNone) continue;
        for (int j = 0; j < 3; ++j)
          e.push_back(edge_key(verts(t)[kFaceVertex[i][j]], verts(t)[kFaceVertex[i][(j + 1) % 3]]));
      }
    }
    std::sort(e.begin(), e.end());
    for (size_t k = 0; k < e.size();) {
      size_t j = k + 1;
      while (j < e.size() && e[j] == e[k]) ++j;
      if (j - k != 2) {
        out << "hull edge " << (e[k] >> 32) << " " << (e[k] & 0xffffffffu) << " is in " << (j - k) << " hull faces";
        return out.str();
      }
      k = j;
    }
  }
  {  // No face of three tets (one with its face on the hull while two others share it).
    std::vector<std::array<uint32_t, 4>> keys;
    for (uint32_t t = 0; t < num_slots(); ++t) {
      if (dead(t)) continue;
      for (int i = 0; i < 4; ++i) {
        std::array<uint32_t, 4> k = {verts(t)[kFaceVertex[i][0]], verts(t)[kFaceVertex[i][1]], verts(t)[kFaceVertex[i][2]], t};
        std::sort(k.begin(), k.begin() + 3);
        keys.push_back(k);
      }
    }
    std::sort(keys.begin(), keys.end());
    for (size_t k = 2; k < keys.size(); ++k)
      if (keys[k][0] == keys[k - 2][0] && keys[k][1] == keys[k - 2][1] && keys[k][2] == keys[k - 2][2]) {
        out << "face (" << keys[k][0] << " " << keys[k][1] << " " << keys[k][2] << ") of tets " << keys[k - 2][3] << " "
            << keys[k - 1][3] << " " << keys[k][3];
        return out.str();
      }
  }
  for (uint32_t v = 0; v < num_points(); ++v) {
    if (tag[v] & ptag::kRemoved) continue;
    const uint32_t t = ptet[v];
    if (t == kNone || t >= num_slots() || dead(t) || local(t, v) < 0) {
      out << "point " << v << " has no live tet";
      return out.str();
    }
  }
  return {};
}

}  // namespace anitet::adapt
