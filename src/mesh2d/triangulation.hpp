// The 2D mesher's working triangulation: flat arrays with adjacency, and the kernel's local
// operations on it (point location, insertion through a cavity stopped at constrained edges,
// edge flips, vertex stars).
//
// Triangle t holds tri[3t..3t+2] counter-clockwise. Edge k of t is the one opposite its vertex
// k, from tri[3t+(k+1)%3] to tri[3t+(k+2)%3] (t on its left); nbr[3t+k] is the triangle across
// it (kNone on the mesh's boundary) and tag[3t+k] its constraint (kFree when it is none: an input
// segment's index, or another caller's id). Freed slots have tri[3t] == kNone.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/status.hpp"

namespace anitet::mesh2d {

constexpr uint32_t kNone = 0xffffffffu;
constexpr int32_t kFree = -1;

// A 2x2 metric tensor (xx xy yy): |e| = sqrt(e^T M e).
struct Metric2 {
  double xx = 1, xy = 0, yy = 1;
};

class Triangulation {
 public:
  std::vector<double> xy;       // 2 per vertex
  std::vector<uint32_t> tri;    // 3 per slot
  std::vector<uint32_t> nbr;    // 3 per slot
  std::vector<int32_t> tag;     // 3 per slot
  std::vector<uint32_t> vtri;   // per vertex: a live triangle holding it, kNone when none
  std::vector<uint32_t> free_slots;
  // {copy, original}: where the triangles around one point form several fans (the domain
  // pinches there, e.g. two squares touching at a corner), build_triangulation gives each fan
  // after the first its own copy of the vertex, so that every vertex's star is one fan.
  std::vector<std::pair<uint32_t, uint32_t>> copies;

  size_t num_vertices() const { return xy.size() / 2; }
  size_t num_slots() const { return tri.size() / 3; }
  size_t num_triangles() const { return num_slots() - free_slots.size(); }
  bool alive(uint32_t t) const { return tri[3 * size_t(t)] != kNone; }
  const double* point(uint32_t v) const { return &xy[2 * size_t(v)]; }
  uint32_t v(uint32_t t, int k) const { return tri[3 * size_t(t) + size_t(k)]; }
  uint32_t edge_a(uint32_t t, int k) const { return tri[3 * size_t(t) + size_t((k + 1) % 3)]; }
  uint32_t edge_b(uint32_t t, int k) const { return tri[3 * size_t(t) + size_t((k + 2) % 3)]; }
  uint32_t across(uint32_t t, int k) const { return nbr[3 * size_t(t) + size_t(k)]; }
  int32_t edge_tag(uint32_t t, int k) const { return tag[3 * size_t(t) + size_t(k)]; }
  bool constrained(uint32_t t, int k) const { return tag[3 * size_t(t) + size_t(k)] != kFree; }

  uint32_t add_vertex(double x, double y);
  // A new triangle a b c (counter-clockwise), no neighbours, no constraints; vtri of a, b, c set.
  uint32_t add_triangle(uint32_t a, uint32_t b, uint32_t c);
  void free_triangle(uint32_t t);
  // The index (0..2) of vertex v in t, -1 if absent.
  int index_of(uint32_t t, uint32_t v) const;
  // The index at which the neighbour across edge k of t sees t (-1 on the boundary).
  int mirror(uint32_t t, int k) const;
  // t's edge k and n's edge kn are the same edge.
  void link(uint32_t t, int k, uint32_t n, int kn);
  // Sets the tag of edge k of t and of its twin.
  void set_edge_tag(uint32_t t, int k, int32_t value);
  // The triangle t and index k whose edge k goes from a to b; false if there is none.
  bool find_edge(uint32_t a, uint32_t b, uint32_t& t, int& k) const;
  // The live triangles around v, counter-clockwise; false when v is on the mesh's boundary (the
  // list then runs from the boundary edge leaving v clockwise-most to the other).
  bool star(uint32_t v, std::vector<uint32_t>& out) const;
  // The neighbours of v (each vertex joined to it by an edge), in the order of star().
  void neighbours(uint32_t v, std::vector<uint32_t>& out) const;
  // Sets vtri of every vertex from the live triangles (kNone for vertices in none).
  void rebuild_vertex_triangles();
};

// The triangulation of the given counter-clockwise triangles (3 indices each) over xy, with
// adjacency; the edges listed (2 vertices each) get the matching tags. A vertex whose triangles
// form several fans is split into copies (Triangulation::copies). Error::InvalidMesh naming the
// edge for an edge of three or more triangles, or of two triangles of the same orientation, and
// for a listed edge that is no triangle's.
Result<Triangulation> build_triangulation(std::vector<double> xy, std::vector<uint32_t> tri,
                                          const std::vector<uint32_t>& edges = {},
                                          const std::vector<int32_t>& edge_tags = {});

// The edge between the points a and b in either direction, whichever copies of them
// (Triangulation::copies) it joins; false if there is none.
bool find_edge_of_points(const Triangulation& mesh, uint32_t a, uint32_t b, uint32_t& t, int& k);

// Exact checks of a triangulation's consistency (adjacency both ways, tags on both sides,
// positive orientation, vtri): for tests and debugging. Error::InvalidMesh naming the problem.
Status check_triangulation(const Triangulation& mesh);

struct Location {
  enum Kind { Inside, OnEdge, OnVertex, Outside };
  uint32_t t = kNone;
  Kind kind = Outside;
  int k = -1;  // OnEdge: the edge; OnVertex: the vertex; Outside: the edge the walk left by
};

// The local operations; keeps scratch arrays between calls (one per thread).
class Kernel {
 public:
  explicit Kernel(Triangulation& mesh) : m_(mesh) {}

  // Where p is: a visibility walk from `start` (a live triangle) with exact orientations.
  Location locate(const double p[2], uint32_t start);
  // Inserts p, found at `loc` (Inside or OnEdge), with a Bowyer-Watson cavity grown through
  // unconstrained edges to the triangles whose circumcircle holds p (in `metric` when given:
  // the circles are its unit circle's images), then shrunk until it is star-shaped from p and
  // holds no vertex inside. On a constrained edge only with split_constraints (both halves keep
  // its tag). Returns the new vertex, or kNone when refused (nothing changed then).
  uint32_t insert(const double p[2], const Location& loc, const Metric2* metric = nullptr,
                  bool split_constraints = false);
  // The same for the vertex v already in the vertex list but in no triangle (Euclidean).
  uint32_t insert_vertex(uint32_t v, const Location& loc);
  // Flips edge k of t when it is unconstrained, interior and its quadrilateral strictly
  // convex. Afterwards t and its old neighbour hold the new edge.
  bool flip(uint32_t t, int k);
  // Whether v can be collapsed onto its neighbour w (v removed, w taking its place in v's
  // other triangles): the link condition, every changed triangle still positive (exact), and
  // v's constrained edges: none (then v must be interior), or two of one tag, one of them vw.
  bool can_collapse(uint32_t v, uint32_t w);
  // Collapses v onto w (can_collapse must hold). v is left in no triangle.
  void collapse(uint32_t v, uint32_t w);
  // The triangles of the last successful insert (the new vertex's star).
  const std::vector<uint32_t>& created() const { return created_; }

 private:
  struct CavitySeeds {
    uint32_t seed[2] = {kNone, kNone};
    uint32_t a = kNone, b = kNone;  // the edge p lies on (OnEdge)
    int k = -1;                     // its index in seed[0]
    bool on_boundary = false;       // that edge is on the mesh's boundary
    bool is_split_edge(const Triangulation& m, uint32_t t, int edge) const;
  };
  struct BoundaryEdge {
    uint32_t a, b, out;
    int out_k;
    int32_t tag;
  };
  uint32_t insert_impl(const double* p, const Location& loc, const Metric2* metric, bool split_constraints,
                       uint32_t existing);
  bool conflict(uint32_t t, const double p[2], const Metric2* metric) const;
  uint32_t cavity_defect(const double p[2], const CavitySeeds& seeds);
  bool in_cavity(uint32_t t) const { return t < in_.size() && in_[t] == cstamp_; }
  static uint32_t next_stamp(std::vector<uint32_t>& marks, uint32_t& stamp, size_t size);

  Triangulation& m_;
  std::vector<uint32_t> in_;     // cavity membership (== cstamp_)
  std::vector<uint32_t> vmark_;  // cavity boundary vertices (== vstamp_)
  std::vector<uint32_t> vslot_;  // the new triangle starting at a boundary vertex
  uint32_t cstamp_ = 0, vstamp_ = 0;
  std::vector<uint32_t> cavity_, stack_, created_, fan_, nv_, nw_;
  std::vector<BoundaryEdge> boundary_;
  uint64_t rng_ = 0x9e3779b97f4a7c15ull;
};

// The circumcentre of a b c (counter-clockwise, not flat) in doubles.
void circumcenter(const double* a, const double* b, const double* c, double out[2]);

}  // namespace anitet::mesh2d
