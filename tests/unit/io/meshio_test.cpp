// Every file our writers produce must read in meshio (python3-meshio), the common converter.
// Skipped when /usr/bin/python3 cannot import meshio.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "io/surface_io.hpp"
#include "io/volume_io.hpp"
#include "io_test_util.hpp"

namespace anitet {
namespace {

bool have_meshio() {
  return std::system("/usr/bin/python3 -c 'import meshio' >/dev/null 2>&1") == 0;
}

// Runs a Python script (written to a file) with the output directory as its argument; true
// when it exits with 0.
bool run_python(const std::string& script) {
  const std::string path = test::temp_dir() + "/check_meshio.py";
  if (!write_file_bytes(path, script).ok()) return false;
  const std::string command = "/usr/bin/python3 '" + path + "' '" + test::temp_dir() + "' 1>&2";
  return std::system(command.c_str()) == 0;
}

VolumeMesh box_volume() {
  VolumeMesh mesh;
  mesh.xyz = test::box_xyz();
  mesh.tet = test::kBoxTets;
  mesh.region = test::kBoxRegions;
  mesh.bnd_tri = test::kBoxTris;
  mesh.bnd_patch = test::kBoxPatches;
  mesh.vertex_metric.assign(8 * 6, 0.0);
  for (size_t v = 0; v < 8; ++v) {
    mesh.vertex_metric[6 * v] = mesh.vertex_metric[6 * v + 2] = mesh.vertex_metric[6 * v + 5] = 1.0;
  }
  return mesh;
}

TEST(Meshio, ReadsEveryVolumeFileWeWrite) {
  if (!have_meshio()) GTEST_SKIP() << "/usr/bin/python3 has no meshio";
  const std::string dir = test::temp_dir();
  VolumeMesh mesh = box_volume();
  std::vector<TetScalar> quality = {{"quality", {0.1, 0.2, 0.3, 0.4, 0.5, 0.6}}};
  for (const char* ext : {"mesh", "msh", "vtu"}) {
    ASSERT_TRUE(write_volume_mesh(mesh, dir + "/box." + ext, quality).ok()) << ext;
  }
  VolumeMesh zero = mesh;  // labels that are not positive: Gmsh renumbers them
  zero.region.assign(6, 0);
  zero.bnd_patch.assign(12, 0);
  ASSERT_TRUE(write_volume_mesh(zero, dir + "/zero.msh").ok());
  ASSERT_TRUE(write_sol(mesh, dir + "/box.sol").ok());
  const std::string script = R"(
import sys, warnings
import numpy as np
import meshio
warnings.simplefilter("ignore")
d = sys.argv[1]
def cells(m):
    out = {}
    for i, c in enumerate(m.cells):
        out.setdefault(c.type, []).append(i)
    return out
def check(name, region_key, patch_key, regions, patches):
    m = meshio.read(d + "/" + name)
    assert m.points.shape == (8, 3), name
    assert np.array_equal(m.points[7], [1.5, 0.1, 2.0]), name
    c = cells(m)
    tets = np.concatenate([m.cells[i].data for i in c["tetra"]])
    tris = np.concatenate([m.cells[i].data for i in c["triangle"]])
    assert len(tets) == 6 and len(tris) == 12, name
    r = np.concatenate([m.cell_data[region_key][i] for i in c["tetra"]])
    p = np.concatenate([m.cell_data[patch_key][i] for i in c["triangle"]])
    assert sorted(r.tolist()) == sorted(regions), (name, r)
    assert sorted(p.tolist()) == sorted(patches), (name, p)
    return m
R = [1, 1, 1, 2, 2, 2]
P = [1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6]
check("box.mesh", "medit:ref", "medit:ref", R, P)
check("box.msh", "gmsh:physical", "gmsh:physical", R, P)
check("zero.msh", "gmsh:physical", "gmsh:physical", [1] * 6, [1] * 12)
m = check("box.vtu", "region", "patch", R, P)
c = cells(m)
q = np.concatenate([m.cell_data["quality"][i] for i in c["tetra"]])
assert np.allclose(sorted(q), [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]), q
assert m.point_data["metric"].shape == (8, 6)
print("meshio read all volume files")
)";
  EXPECT_TRUE(run_python(script));
}

// The .vtu reader takes every encoding VTK and meshio write: ascii; binary inline base64, plain
// or zlib (meshio's default); appended raw or base64, UInt32 or UInt64 headers, zlib in several
// blocks (ParaView's default is appended raw + zlib). Written from our ascii box by meshio and by
// hand, each read back as the same mesh.
TEST(Meshio, VtuInEveryEncodingReadsAsTheSameMesh) {
  if (!have_meshio()) GTEST_SKIP() << "/usr/bin/python3 has no meshio";
  const std::string dir = test::temp_dir();
  const VolumeMesh mesh = box_volume();
  ASSERT_TRUE(write_volume_mesh(mesh, dir + "/enc.vtu").ok());
  const std::string script = R"(
import sys, base64, struct, zlib
import numpy as np
import meshio
d = sys.argv[1]
m = meshio.read(d + "/enc.vtu")
tets, tris = m.cells_dict["tetra"], m.cells_dict["triangle"]
region = np.asarray(m.cell_data_dict["region"]["tetra"], dtype=np.int32)
patch = np.asarray(m.cell_data_dict["patch"]["triangle"], dtype=np.int32)
out = meshio.Mesh(m.points, [("tetra", tets), ("triangle", tris)],
                  cell_data={"region": [region, np.zeros(len(tris), np.int32)],
                             "patch": [np.zeros(len(tets), np.int32), patch]})
meshio.write(d + "/enc-binary.vtu", out, binary=True, compression=None)
meshio.write(d + "/enc-zlib.vtu", out, binary=True, compression="zlib")

def encoded(raw, header, block, b64):
    f = "<Q" if header == "UInt64" else "<I"
    if block is None:
        head, body = struct.pack(f, len(raw)), raw
    else:
        chunks = [raw[i:i + block] for i in range(0, len(raw), block)]
        packed = [zlib.compress(c) for c in chunks]
        last = len(chunks[-1]) % block if chunks else 0
        head = struct.pack("<" + f[1] * (3 + len(packed)), len(packed), block, last, *map(len, packed))
        body = b"".join(packed)
    return base64.b64encode(head) + base64.b64encode(body) if b64 else head + body

def appended(name, header, block, b64):
    n_t, n_b = len(tets), len(tris)
    arrays = [
        ("Points", "Points", "Float64", 3, np.asarray(m.points, np.float64)),
        ("Cells", "connectivity", "Int64", 1, np.concatenate([tets.ravel(), tris.ravel()]).astype(np.int64)),
        ("Cells", "offsets", "Int32", 1, np.concatenate([4 * np.arange(1, n_t + 1),
                                                          4 * n_t + 3 * np.arange(1, n_b + 1)]).astype(np.int32)),
        ("Cells", "types", "UInt8", 1, np.array([10] * n_t + [5] * n_b, np.uint8)),
        ("CellData", "region", "Int16", 1, np.concatenate([region, np.zeros(n_b)]).astype(np.int16)),
        ("CellData", "patch", "Int64", 1, np.concatenate([np.zeros(n_t), patch]).astype(np.int64))]
    xml = ('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" '
           'header_type="%s"%s>\n<UnstructuredGrid>\n<Piece NumberOfPoints="%d" NumberOfCells="%d">\n'
           % (header, ' compressor="vtkZLibDataCompressor"' if block else "", len(m.points), n_t + n_b))
    data = b""
    for section in ("Points", "Cells", "CellData"):
        xml += "<%s>\n" % section
        for s, a, t, k, v in arrays:
            if s == section:
                xml += ('<DataArray type="%s" Name="%s" NumberOfComponents="%d" format="appended" offset="%d"/>\n'
                        % (t, a, k, len(data)))
                data += encoded(v.tobytes(), header, block, b64)
        xml += "</%s>\n" % section
    xml += '</Piece>\n</UnstructuredGrid>\n<AppendedData encoding="%s">\n_' % ("base64" if b64 else "raw")
    with open(d + "/" + name, "wb") as f:
        f.write(xml.encode() + data + b"\n</AppendedData>\n</VTKFile>\n")

appended("enc-raw64.vtu", "UInt64", None, False)
appended("enc-raw32-zlib.vtu", "UInt32", 40, False)
appended("enc-b64-zlib.vtu", "UInt64", 64, True)
appended("enc-b64.vtu", "UInt32", None, True)
)";
  ASSERT_TRUE(run_python(script));
  for (const char* name : {"enc-binary", "enc-zlib", "enc-raw64", "enc-raw32-zlib", "enc-b64-zlib", "enc-b64"}) {
    Result<VolumeMesh> back = read_volume_mesh(dir + "/" + name + ".vtu");
    ASSERT_TRUE(back.ok()) << name << ": " << back.status().message();
    EXPECT_EQ(back->xyz, mesh.xyz) << name;
    EXPECT_EQ(back->tet, mesh.tet) << name;
    EXPECT_EQ(back->region, mesh.region) << name;
    EXPECT_EQ(back->bnd_tri, mesh.bnd_tri) << name;
    EXPECT_EQ(back->bnd_patch, mesh.bnd_patch) << name;
  }
}

TEST(Meshio, ReadsEverySurfaceFileWeWrite) {
  if (!have_meshio()) GTEST_SKIP() << "/usr/bin/python3 has no meshio";
  const std::string dir = test::temp_dir();
  SurfaceMesh mesh;
  mesh.xyz = test::box_xyz();
  mesh.tri = test::kBoxTris;
  mesh.patch = test::kBoxPatches;
  for (const char* ext : {"off", "obj", "stl", "mesh"}) {
    ASSERT_TRUE(write_surface(mesh, dir + "/surface." + ext).ok()) << ext;
  }
  const std::string script = R"(
import sys, warnings
import numpy as np
import meshio
warnings.simplefilter("ignore")
for ext in ["off", "obj", "stl", "mesh"]:
    m = meshio.read(sys.argv[1] + "/surface." + ext)
    tris = np.concatenate([c.data for c in m.cells if c.type == "triangle"])
    assert len(tris) == 12, ext
    assert len(np.unique(m.points, axis=0)) == 8, ext
print("meshio read all surface files")
)";
  EXPECT_TRUE(run_python(script));
}

}  // namespace
}  // namespace anitet
