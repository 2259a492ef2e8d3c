// CGNS writer through the CGNS mid-level library (optional: ANITET_HAVE_CGNS).
#include <string>
#include <vector>

#include "io/file_bytes.hpp"
#include "io/mesh_faces.hpp"
#include "io/volume_io.hpp"

#ifdef ANITET_HAVE_CGNS
#include <cgnslib.h>

#include <array>
#include <cstdio>
#include <limits>
#include <utility>

#include "io/lazy_library.hpp"
#endif

namespace anitet {

#ifdef ANITET_HAVE_CGNS

bool cgns_available() { return true; }

namespace {

// The CGNS functions this writer calls, from the library opened on the first write
// (ANITET_CGNS_SONAME, found at configure time; see lazy_library.hpp). The calls below keep
// their names: each is a macro for its pointer here.
struct CgnsApi {
  decltype(&::cg_open) open = nullptr;
  decltype(&::cg_close) close = nullptr;
  decltype(&::cg_get_error) get_error = nullptr;
  decltype(&::cg_base_write) base_write = nullptr;
  decltype(&::cg_goto) go_to = nullptr;
  decltype(&::cg_dataclass_write) dataclass_write = nullptr;
  decltype(&::cg_zone_write) zone_write = nullptr;
  decltype(&::cg_coord_write) coord_write = nullptr;
  decltype(&::cg_exponents_write) exponents_write = nullptr;
  decltype(&::cg_section_write) section_write = nullptr;
  decltype(&::cg_boco_write) boco_write = nullptr;
  decltype(&::cg_boco_gridlocation_write) boco_gridlocation_write = nullptr;
  std::string error;  // empty: every function was found
};

const CgnsApi& cgns_api() {
  static const CgnsApi api = [] {
    static LazyLibrary library(ANITET_CGNS_SONAME);
    CgnsApi a;
    const bool ok = library.bind(a.open, "cg_open") && library.bind(a.close, "cg_close") &&
                    library.bind(a.get_error, "cg_get_error") && library.bind(a.base_write, "cg_base_write") &&
                    library.bind(a.go_to, "cg_goto") && library.bind(a.dataclass_write, "cg_dataclass_write") &&
                    library.bind(a.zone_write, "cg_zone_write") && library.bind(a.coord_write, "cg_coord_write") &&
                    library.bind(a.exponents_write, "cg_exponents_write") &&
                    library.bind(a.section_write, "cg_section_write") && library.bind(a.boco_write, "cg_boco_write") &&
                    library.bind(a.boco_gridlocation_write, "cg_boco_gridlocation_write");
    if (!ok) a.error = library.error();  // (bind() says why whenever it fails)
    return a;
  }();
  return api;
}

#define cg_open (cgns_api().open)
#define cg_close (cgns_api().close)
#define cg_get_error (cgns_api().get_error)
#define cg_base_write (cgns_api().base_write)
#define cg_goto (cgns_api().go_to)
#define cg_dataclass_write (cgns_api().dataclass_write)
#define cg_zone_write (cgns_api().zone_write)
#define cg_coord_write (cgns_api().coord_write)
#define cg_exponents_write (cgns_api().exponents_write)
#define cg_section_write (cgns_api().section_write)
#define cg_boco_write (cgns_api().boco_write)
#define cg_boco_gridlocation_write (cgns_api().boco_gridlocation_write)

CGNS_ENUMT(BCType_t) cgns_bc_type(PatchKind kind) {
  switch (kind) {
    case PatchKind::Inlet: return CGNS_ENUMV(BCInflow);
    case PatchKind::Outlet: return CGNS_ENUMV(BCOutflow);
    case PatchKind::Farfield: return CGNS_ENUMV(BCFarfield);
    case PatchKind::Symmetry: return CGNS_ENUMV(BCSymmetryPlane);
    case PatchKind::Patch: return CGNS_ENUMV(BCGeneral);
    case PatchKind::Wall: break;
  }
  return CGNS_ENUMV(BCWall);
}

// Writes PATH.part-PID and moves it to PATH when complete; closes the file on every path and
// removes the partial one when the write did not finish.
class CgnsFile {
 public:
  explicit CgnsFile(std::string path) : path_(std::move(path)) {}
  ~CgnsFile() {
    if (open_) cg_close(fn_);
    if (created_ && !done_) std::remove(partial_.c_str());
  }
  CgnsFile(const CgnsFile&) = delete;
  CgnsFile& operator=(const CgnsFile&) = delete;

  Status open() {
    if (cg_open(partial_.c_str(), CG_MODE_WRITE, &fn_) != CG_OK) return error("cg_open");
    open_ = created_ = true;
    return Status::success();
  }
  Status close() {
    open_ = false;
    if (cg_close(fn_) != CG_OK) return error("cg_close");
    done_ = true;
    return move_into_place(partial_, path_);
  }
  Status error(const char* call) const {
    return Status(Error::FileNotFound, path_ + ": " + call + ": " + cg_get_error());
  }
  int fn() const { return fn_; }

 private:
  std::string path_;
  std::string partial_ = partial_path(path_);  // written, then moved to path_ by close()
  int fn_ = -1;
  bool open_ = false, created_ = false, done_ = false;
};

}  // namespace

std::string cgns_load_error() { return cgns_api().error; }

Status write_cgns(const VolumeMesh& mesh, const std::string& path, const PatchNames& patch_names,
                  const PatchTypes& patch_types) {
  if (Status s = check_volume_arrays(mesh); !s.ok()) return s;
  Result<std::vector<PatchTriangles>> patches = patch_triangles(mesh, patch_names, patch_types);
  if (!patches.ok()) return patches.status();
  Result<MeshFaces> faces = build_mesh_faces(mesh);
  if (!faces.ok()) return faces.status();
  const size_t nv = mesh.num_vertices(), nt = mesh.num_tets(), nb = mesh.num_boundary_triangles();
  if (nv + nt + nb > size_t(std::numeric_limits<cgsize_t>::max())) {
    return Status(Error::InvalidArgument, path + ": too many elements for this CGNS build's 32-bit sizes");
  }
  if (nt == 0) return Status(Error::InvalidArgument, path + ": a CGNS zone needs at least one tetrahedron");
  if (!cgns_api().error.empty()) return Status(Error::NotImplemented, path + ": " + cgns_api().error);

  CgnsFile file(path);
  if (Status s = file.open(); !s.ok()) return s;
  const int fn = file.fn();
  int base = 0, zone = 0, index = 0;
  if (cg_base_write(fn, "Base", 3, 3, &base) != CG_OK) return file.error("cg_base_write");
  // The coordinates are dimensional in units anitet does not know: NormalizedByUnknownDimensional
  // (SIDS), set on the base so that every array below inherits it.
  if (cg_goto(fn, base, "end") != CG_OK) return file.error("cg_goto");
  if (cg_dataclass_write(CGNS_ENUMV(NormalizedByUnknownDimensional)) != CG_OK) return file.error("cg_dataclass_write");
  const cgsize_t size[3] = {cgsize_t(nv), cgsize_t(nt), 0};
  if (cg_zone_write(fn, base, "Zone1", size, CGNS_ENUMV(Unstructured), &zone) != CG_OK) {
    return file.error("cg_zone_write");
  }
  std::vector<double> coord(nv);
  const char* coord_names[3] = {"CoordinateX", "CoordinateY", "CoordinateZ"};
  for (int k = 0; k < 3; ++k) {
    for (size_t v = 0; v < nv; ++v) coord[v] = mesh.xyz[3 * v + size_t(k)];
    if (cg_coord_write(fn, base, zone, CGNS_ENUMV(RealDouble), coord_names[k], coord.data(), &index) != CG_OK) {
      return file.error("cg_coord_write");
    }
    // A length: exponents of mass, length, time, temperature, angle.
    const double length[5] = {0.0, 1.0, 0.0, 0.0, 0.0};
    if (cg_goto(fn, base, "Zone_t", zone, "GridCoordinates_t", 1, "DataArray_t", index, "end") != CG_OK ||
        cg_exponents_write(CGNS_ENUMV(RealDouble), length) != CG_OK) {
      return file.error("cg_exponents_write");
    }
  }
  std::vector<cgsize_t> conn(4 * nt);
  for (size_t i = 0; i < 4 * nt; ++i) conn[i] = cgsize_t(mesh.tet[i]) + 1;
  if (cg_section_write(fn, base, zone, "GridElements", CGNS_ENUMV(TETRA_4), 1, cgsize_t(nt), 0, conn.data(),
                       &index) != CG_OK) {
    return file.error("cg_section_write");
  }
  cgsize_t next = cgsize_t(nt) + 1;  // element ids continue after the tets
  for (const PatchTriangles& p : patches.value()) {
    if (p.tris.empty()) continue;
    conn.clear();
    for (uint32_t b : p.tris) {
      for (uint32_t v : outward_triangle(mesh, faces.value(), b)) conn.push_back(cgsize_t(v) + 1);
    }
    const cgsize_t range[2] = {next, next + cgsize_t(p.tris.size()) - 1};
    if (cg_section_write(fn, base, zone, p.patch.name.c_str(), CGNS_ENUMV(TRI_3), range[0], range[1], 0,
                         conn.data(), &index) != CG_OK) {
      return file.error("cg_section_write");
    }
    int bc = 0;
    if (cg_boco_write(fn, base, zone, p.patch.name.c_str(), cgns_bc_type(p.patch.kind),
                      CGNS_ENUMV(PointRange), 2, range, &bc) != CG_OK) {
      return file.error("cg_boco_write");
    }
    if (cg_boco_gridlocation_write(fn, base, zone, bc, CGNS_ENUMV(FaceCenter)) != CG_OK) {
      return file.error("cg_boco_gridlocation_write");
    }
    next = range[1] + 1;
  }
  return file.close();
}

#else  // !ANITET_HAVE_CGNS

bool cgns_available() { return false; }
std::string cgns_load_error() { return "anitet was not built with CGNS"; }

Status write_cgns(const VolumeMesh&, const std::string& path, const PatchNames&, const PatchTypes&) {
  return Status(Error::NotImplemented, path + ": anitet was not built with CGNS (install libcgns-dev and "
                                              "configure again to write .cgns)");
}

#endif

}  // namespace anitet
