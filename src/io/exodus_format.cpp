// Exodus II writer through the Exodus II C library (optional: ANITET_HAVE_EXODUS).
#include <string>
#include <vector>

#include "io/file_bytes.hpp"
#include "io/mesh_faces.hpp"
#include "io/volume_io.hpp"

#ifdef ANITET_HAVE_EXODUS
#include <exodusII.h>

#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <utility>

#include "io/lazy_library.hpp"
#endif

namespace anitet {

#ifdef ANITET_HAVE_EXODUS

bool exodus_available() { return true; }

namespace {

// The Exodus II functions this writer calls, from the library opened on the first write
// (ANITET_EXODUS_SONAME, found at configure time; see lazy_library.hpp). The calls below keep
// their names: each is a macro for its pointer here (ex_create is exodusII.h's macro for
// ex_create_int).
struct ExodusApi {
  decltype(&::ex_create_int) create_int = nullptr;
  decltype(&::ex_close) close = nullptr;
  decltype(&::ex_put_init) put_init = nullptr;
  decltype(&::ex_put_coord) put_coord = nullptr;
  decltype(&::ex_put_coord_names) put_coord_names = nullptr;
  decltype(&::ex_put_block) put_block = nullptr;
  decltype(&::ex_put_conn) put_conn = nullptr;
  decltype(&::ex_put_name) put_name = nullptr;
  decltype(&::ex_put_set_param) put_set_param = nullptr;
  decltype(&::ex_put_set) put_set = nullptr;
  decltype(&::ex_put_prop) put_prop = nullptr;
  int* errval = nullptr;  // the library's exerrval
  std::string error;  // empty: every function was found
};

const ExodusApi& exodus_api() {
  static const ExodusApi api = [] {
    static LazyLibrary library(ANITET_EXODUS_SONAME);
    ExodusApi a;
    const bool ok = library.bind(a.create_int, "ex_create_int") && library.bind(a.close, "ex_close") &&
                    library.bind(a.put_init, "ex_put_init") && library.bind(a.put_coord, "ex_put_coord") &&
                    library.bind(a.put_coord_names, "ex_put_coord_names") &&
                    library.bind(a.put_block, "ex_put_block") && library.bind(a.put_conn, "ex_put_conn") &&
                    library.bind(a.put_name, "ex_put_name") && library.bind(a.put_set_param, "ex_put_set_param") &&
                    library.bind(a.put_set, "ex_put_set") && library.bind(a.put_prop, "ex_put_prop") &&
                    library.bind(a.errval, "exerrval");
    if (!ok) a.error = library.error();  // (bind() says why whenever it fails)
    return a;
  }();
  return api;
}

#define ex_create_int (exodus_api().create_int)
#define ex_close (exodus_api().close)
#define ex_put_init (exodus_api().put_init)
#define ex_put_coord (exodus_api().put_coord)
#define ex_put_coord_names (exodus_api().put_coord_names)
#define ex_put_block (exodus_api().put_block)
#define ex_put_conn (exodus_api().put_conn)
#define ex_put_name (exodus_api().put_name)
#define ex_put_set_param (exodus_api().put_set_param)
#define ex_put_set (exodus_api().put_set)
#define ex_put_prop (exodus_api().put_prop)
#undef exerrval
#define exerrval (*exodus_api().errval)

// Writes PATH.part-PID and moves it to PATH when complete; closes the file on every path and
// removes the partial one when the write did not finish.
class ExodusFile {
 public:
  explicit ExodusFile(std::string path) : path_(std::move(path)) {}
  ~ExodusFile() {
    if (id_ >= 0) ex_close(id_);
    if (created_ && !done_) std::remove(partial_.c_str());
  }
  ExodusFile(const ExodusFile&) = delete;
  ExodusFile& operator=(const ExodusFile&) = delete;

  Status create() {
    int cpu_word_size = sizeof(double), io_word_size = sizeof(double);
    id_ = ex_create(partial_.c_str(), EX_CLOBBER, &cpu_word_size, &io_word_size);
    if (id_ < 0) return error("ex_create", id_);
    created_ = true;
    return Status::success();
  }
  Status close() {
    const int rc = ex_close(id_);
    id_ = -1;
    if (rc < 0) return error("ex_close", rc);
    done_ = true;
    return move_into_place(partial_, path_);
  }
  Status error(const char* call, int rc) const {
    // exerrval: an errno value (> 0) or a netCDF/Exodus code (< 0). (nc_strerror would need
    // the netCDF build Exodus links, which Debian does not expose.)
    const int code = exerrval;
    const std::string why = code > 0 ? std::strerror(code) : "netCDF/Exodus code " + std::to_string(code);
    return Status(Error::FileNotFound,
                  path_ + ": " + call + " failed (Exodus error " + std::to_string(rc) + ": " + why + ")");
  }
  int id() const { return id_; }

 private:
  std::string path_;
  std::string partial_ = partial_path(path_);  // written, then moved to path_ by close()
  int id_ = -1;
  bool created_ = false, done_ = false;
};

}  // namespace

std::string exodus_load_error() { return exodus_api().error; }

Status write_exodus(const VolumeMesh& mesh, const std::string& path, const PatchNames& patch_names,
                    const PatchTypes& patch_types) {
  if (Status s = check_volume_arrays(mesh); !s.ok()) return s;
  Result<std::vector<PatchTriangles>> patches = patch_triangles(mesh, patch_names, patch_types);
  if (!patches.ok()) return patches.status();
  Result<MeshFaces> built = build_mesh_faces(mesh);
  if (!built.ok()) return built.status();
  const MeshFaces& faces = built.value();
  const size_t nv = mesh.num_vertices(), nt = mesh.num_tets();
  if (nv > size_t(std::numeric_limits<int>::max()) || nt > size_t(std::numeric_limits<int>::max())) {
    return Status(Error::InvalidArgument, path + ": too many vertices or tets for Exodus's 32-bit ids");
  }
  if (nt == 0) return Status(Error::InvalidArgument, path + ": an Exodus file needs at least one tetrahedron");

  // Blocks: the tets of each region, in mesh order; element ids run block by block.
  std::map<int32_t, std::vector<uint32_t>> blocks;
  for (size_t t = 0; t < nt; ++t) blocks[mesh.region.empty() ? 0 : mesh.region[t]].push_back(uint32_t(t));
  std::vector<int32_t> region_labels;
  for (const auto& entry : blocks) region_labels.push_back(entry.first);
  const std::map<int32_t, int32_t> block_ids = positive_ids(region_labels);
  std::vector<int> element_id(nt);  // 1-based Exodus element number of each tet
  int next = 1;
  for (const auto& entry : blocks) {
    for (uint32_t t : entry.second) element_id[t] = next++;
  }
  // Side sets: every boundary triangle must be a tet face (an element side).
  std::vector<int32_t> patch_labels;
  for (const PatchTriangles& p : patches.value()) patch_labels.push_back(p.patch.label);
  const std::map<int32_t, int32_t> set_ids = positive_ids(patch_labels);
  for (const PatchTriangles& p : patches.value()) {
    for (uint32_t b : p.tris) {
      if (faces.bnd_face[b] == MeshFaces::kNone) {
        return Status(Error::InvalidArgument, "boundary triangle " + std::to_string(b) + " (patch '" +
                                                  p.patch.name + "') is not a face of any tet: an Exodus side "
                                                  "set lists element sides");
      }
    }
  }

  if (!exodus_api().error.empty()) return Status(Error::NotImplemented, path + ": " + exodus_api().error);
  ExodusFile file(path);
  if (Status s = file.create(); !s.ok()) return s;
  const int id = file.id();
  int rc = ex_put_init(id, "anitet tetrahedral mesh", 3, int64_t(nv), int64_t(nt), int64_t(blocks.size()), 0,
                       int64_t(patches.value().size()));
  if (rc < 0) return file.error("ex_put_init", rc);
  std::vector<double> x(nv), y(nv), z(nv);
  for (size_t v = 0; v < nv; ++v) {
    x[v] = mesh.xyz[3 * v];
    y[v] = mesh.xyz[3 * v + 1];
    z[v] = mesh.xyz[3 * v + 2];
  }
  if ((rc = ex_put_coord(id, x.data(), y.data(), z.data())) < 0) return file.error("ex_put_coord", rc);
  char coord_x[] = "x", coord_y[] = "y", coord_z[] = "z";
  char* coord_names[3] = {coord_x, coord_y, coord_z};
  if ((rc = ex_put_coord_names(id, coord_names)) < 0) return file.error("ex_put_coord_names", rc);

  std::vector<int> conn;
  for (const auto& [label, tets] : blocks) {
    const int32_t block = block_ids.at(label);
    // "TETRA" with 4 nodes per element: the Exodus II manual's name for the linear tet. ("TETRA4"
    // means the same to SEACAS and ParaView, but Debian 12's meshio 5.0 cannot read it.)
    rc = ex_put_block(id, EX_ELEM_BLOCK, block, "TETRA", int64_t(tets.size()), 4, 0, 0, 0);
    if (rc < 0) return file.error("ex_put_block", rc);
    conn.clear();
    for (uint32_t t : tets) {
      for (int k = 0; k < 4; ++k) conn.push_back(int(mesh.tet[4 * size_t(t) + size_t(k)]) + 1);
    }
    if ((rc = ex_put_conn(id, EX_ELEM_BLOCK, block, conn.data(), nullptr, nullptr)) < 0) {
      return file.error("ex_put_conn", rc);
    }
    if ((rc = ex_put_name(id, EX_ELEM_BLOCK, block, region_name(label).c_str())) < 0) {
      return file.error("ex_put_name", rc);
    }
  }
  std::vector<int> elements, sides;
  for (const PatchTriangles& p : patches.value()) {
    const int32_t set = set_ids.at(p.patch.label);
    elements.clear();
    sides.clear();
    for (uint32_t b : p.tris) {
      const int64_t face = faces.bnd_face[b];
      elements.push_back(element_id[size_t(face / 4)]);
      sides.push_back(int(face % 4) + 1);  // kOutwardFace is Exodus's side order
    }
    if ((rc = ex_put_set_param(id, EX_SIDE_SET, set, int64_t(p.tris.size()), 0)) < 0) {
      return file.error("ex_put_set_param", rc);
    }
    if ((rc = ex_put_set(id, EX_SIDE_SET, set, elements.data(), sides.data())) < 0) {
      return file.error("ex_put_set", rc);
    }
    if ((rc = ex_put_name(id, EX_SIDE_SET, set, p.patch.name.c_str())) < 0) return file.error("ex_put_name", rc);
  }
  // The patches' kinds as side-set properties: one per kind present, named as --patch-types names
  // it in capitals (WALL, INLET, ...), 1 on the side sets of that kind and 0 on the others.
  for (const PatchTriangles& p : patches.value()) {
    std::string kind = patch_kind_name(p.patch.kind);
    for (char& c : kind) c = char(c - 'a' + 'A');
    if ((rc = ex_put_prop(id, EX_SIDE_SET, set_ids.at(p.patch.label), kind.c_str(), 1)) < 0)
      return file.error("ex_put_prop", rc);
  }
  return file.close();
}

#else  // !ANITET_HAVE_EXODUS

bool exodus_available() { return false; }
std::string exodus_load_error() { return "anitet was not built with Exodus II"; }

Status write_exodus(const VolumeMesh&, const std::string& path, const PatchNames&, const PatchTypes&) {
  return Status(Error::NotImplemented, path + ": anitet was not built with Exodus II (install libexodusii-dev "
                                              "and configure again to write .exo/.e)");
}

#endif

}  // namespace anitet
