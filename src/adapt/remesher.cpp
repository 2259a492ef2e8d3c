#include "adapt/remesher.hpp"

#include <algorithm>
#include <cmath>

#include "adapt/surface_geometry.hpp"

namespace anitet::adapt {

double Remesher::quality(const uint32_t v[4], uint32_t moved, const double* pos, const double* met, double det) const {
  const double* p[4];
  const double* m[4];
  double d[4];
  for (int i = 0; i < 4; ++i) {
    if (v[i] == moved) {
      p[i] = pos, d[i] = det, m[i] = met;
    } else {
      p[i] = mesh_.p(v[i]), d[i] = mesh_.mdet[v[i]], m[i] = mesh_.m(v[i]);
    }
  }
  // The worst of the mean ratios in the four corners' metrics: one metric does not see how the
  // metric turns over the tet (the sphere case's wall: the normal of a corner's metric is not
  // its neighbour's), and the moves and swaps then worked against the lengths. The edges and
  // the volume once; per metric M, q^3 = 432 vol6^2 det M / l2(M)^3 (ugawg_mean_ratio's form
  // cubed), so one cube root for the worst.
  double e[6][3];
  for (int k = 0; k < 6; ++k)
    for (int c = 0; c < 3; ++c) e[k][c] = p[kEdgeVertex[k][1]][c] - p[kEdgeVertex[k][0]][c];
  const double vol6 = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                      e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  if (!(vol6 > 0.0)) return -1.0;
  double worst = HUGE_VAL;  // det M / l2(M)^3
  for (int i = 0; i < 4; ++i) {
    if (!(d[i] > 0.0)) return 0.0;
    double l2 = 0.0;
    for (int k = 0; k < 6; ++k) l2 += quad_form(m[i], e[k]);
    worst = std::min(worst, d[i] / (l2 * l2 * l2));
  }
  return 6.0 * cbrt_positive(2.0 * vol6 * vol6 * worst);
}

const double* Remesher::side_normal(uint32_t v, const double face_n[3]) const {
  const uint8_t tag = mesh_.tag[v];
  if (tag & ptag::kFrozen) return face_n;
  const double* n1 = &mesh_.nrm[3 * size_t(v)];
  if (!(tag & ptag::kRidge)) return n1;
  const double* n2 = &mesh_.nrm2[3 * size_t(v)];
  return std::fabs(geom::dot(n1, face_n)) >= std::fabs(geom::dot(n2, face_n)) ? n1 : n2;
}

double Remesher::surface_fit(const uint32_t v[3], const double n[3], bool oriented,
                             const PointGeometry* moved) const {
  double fit = 1.0;
  for (int k = 0; k < 3; ++k) {
    const bool m = moved && v[k] == moved->id;
    const uint8_t tag = m ? moved->tag : mesh_.tag[v[k]];
    if (tag & ptag::kFrozen) continue;  // a corner: any plane through it fits
    const double* n1 = m ? moved->nrm : &mesh_.nrm[3 * size_t(v[k])];
    const double* n2 = m ? moved->nrm2 : &mesh_.nrm2[3 * size_t(v[k])];
    auto cosine = [&](const double* x) { return oriented ? geom::dot(n, x) : std::fabs(geom::dot(n, x)); };
    double c = cosine(n1);
    if ((tag & ptag::kRidge) && n2) c = std::max(c, cosine(n2));  // the nearer side of the ridge
    fit = std::min(fit, c);
  }
  return fit;
}

void Remesher::collect_edges(double below, double above, std::vector<EdgeRec>& out) {
  out.clear();
  std::vector<uint32_t>& ball = ball2_;
  for (uint32_t v = 0; v < mesh_.num_points(); ++v) {
    if ((mesh_.tag[v] & ptag::kRemoved) || !mesh_.active(v)) continue;
    mesh_.ball(v, ball);
    // ball() raised the stamp: points marked with it are seen for v. Each edge once: from its
    // smaller end when both are active.
    for (uint32_t t : ball) {
      const uint32_t* w = mesh_.verts(t);
      for (int i = 0; i < 4; ++i) {
        const uint32_t x = w[i];
        if (x == v || (x < v && mesh_.active(x)) || mesh_.point_marked(x)) continue;
        mesh_.mark_point(x);
        const double l = length(v, x);
        if (l < below || l > above) out.push_back({l, v, x, t});
      }
    }
  }
}

bool Remesher::replace(const std::vector<uint32_t>& old, const std::vector<TetVerts>& fresh, bool surface_change,
                       int32_t surface_label) {
  if (old.empty() || fresh.empty()) return false;
  const int32_t region = mesh_.region[old[0]];
  mesh_.next_stamp();
  for (uint32_t t : old) {
    if (mesh_.region[t] != region) return false;
    mesh_.mark_tet(t);
  }
  match_.clear();
  outer_.clear();
  auto key_of = [](uint32_t x, uint32_t y, uint32_t z) {
    std::array<uint32_t, 3> k = {x, y, z};
    if (k[0] > k[1]) std::swap(k[0], k[1]);
    if (k[1] > k[2]) std::swap(k[1], k[2]);
    if (k[0] > k[1]) std::swap(k[0], k[1]);
    return k;
  };
  for (uint32_t t : old) {
    const uint32_t* w = mesh_.verts(t);
    for (int i = 0; i < 4; ++i) {
      const uint32_t a = mesh_.adj[4 * size_t(t) + i];
      if (a != kNone && mesh_.tet_marked(adj_tet(a))) {
        if (mesh_.is_bnd_face(t, i)) return false;  // an inner boundary face would vanish
        continue;
      }
      match_.push_back({key_of(w[kFaceVertex[i][0]], w[kFaceVertex[i][1]], w[kFaceVertex[i][2]]),
                        uint32_t(outer_.size()), false});
      outer_.push_back({a, mesh_.is_bnd_face(t, i), mesh_.fref[4 * size_t(t) + i]});
    }
  }
  for (uint32_t n = 0; n < fresh.size(); ++n)
    for (int i = 0; i < 4; ++i) {
      const TetVerts& w = fresh[n];
      match_.push_back({key_of(w[size_t(kFaceVertex[i][0])], w[size_t(kFaceVertex[i][1])], w[size_t(kFaceVertex[i][2])]),
                        4 * n + uint32_t(i), true});
    }
  std::sort(match_.begin(), match_.end(), [](const FaceMatch& x, const FaceMatch& y) {
    return x.key != y.key ? x.key < y.key : x.is_new < y.is_new;
  });
  // Validate: pairs (old, new) or (new, new); alone: a new hull face or a vanishing old hull face
  // of a surface change.
  size_t new_alone = 0, old_alone = 0;
  for (size_t k = 0; k < match_.size();) {
    size_t e = k + 1;
    while (e < match_.size() && match_[e].key == match_[k].key) ++e;
    if (e - k > 2) return false;
    if (e - k == 2) {
      if (!match_[k + 1].is_new) return false;
    } else if (!surface_change) {
      return false;
    } else if (match_[k].is_new) {
      ++new_alone;
    } else {
      const OuterFace& f = outer_[match_[k].src];
      if (f.adj != kNone || !f.bnd) return false;
      ++old_alone;
    }
    k = e;
  }
  if (new_alone != old_alone) return false;
  for (uint32_t t : old) mesh_.delete_tet(t);
  created_.resize(fresh.size());
  for (size_t n = 0; n < fresh.size(); ++n) {
    const TetVerts& w = fresh[n];
    created_[n] = mesh_.new_tet(w[0], w[1], w[2], w[3], region);
  }
  for (size_t k = 0; k < match_.size();) {
    size_t e = k + 1;
    while (e < match_.size() && match_[e].key == match_[k].key) ++e;
    const FaceMatch& x = match_[k];
    if (e - k == 2) {
      const FaceMatch& y = match_[k + 1];  // new
      const uint32_t ty = created_[y.src >> 2];
      const int iy = int(y.src & 3u);
      if (x.is_new) {
        const uint32_t tx = created_[x.src >> 2];
        const int ix = int(x.src & 3u);
        mesh_.adj[4 * size_t(tx) + ix] = 4 * ty + uint32_t(iy);
        mesh_.adj[4 * size_t(ty) + iy] = 4 * tx + uint32_t(ix);
      } else {
        const OuterFace& f = outer_[x.src];
        mesh_.adj[4 * size_t(ty) + iy] = f.adj;
        if (f.adj != kNone) mesh_.adj[f.adj] = 4 * ty + uint32_t(iy);
        if (f.bnd) {
          mesh_.bnd[ty] |= uint8_t(1u << iy);
          mesh_.fref[4 * size_t(ty) + iy] = f.label;
        }
      }
    } else if (x.is_new) {  // a new hull face
      const uint32_t tx = created_[x.src >> 2];
      const int ix = int(x.src & 3u);
      mesh_.adj[4 * size_t(tx) + ix] = kNone;
      mesh_.bnd[tx] |= uint8_t(1u << ix);
      mesh_.fref[4 * size_t(tx) + ix] = surface_label;
    }
    k = e;
  }
  for (uint32_t t : created_) {
    const uint32_t* w = mesh_.verts(t);
    for (int i = 0; i < 4; ++i) mesh_.ptet[w[i]] = t;
    update_quality(t);
    mesh_.touch_tet(t);
  }
  return true;
}

}  // namespace anitet::adapt
