// Gmsh .msh 4.1 ASCII writer: one volume entity per region and one surface entity per patch, so
// that Gmsh and meshio see regions and patches. All nodes sit in one block on the first volume.
#include <algorithm>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "io/number_text.hpp"
#include "io/volume_io.hpp"

namespace anitet {

namespace {

// Entity tags for the distinct labels: the labels themselves when all are positive, else 1, 2, ...
// in increasing label order. Every entity gets its tag as physical tag too: meshio needs all
// entities or none to have one, and Gmsh needs physical tags to be positive.
std::map<int32_t, int32_t> entity_tags(const std::vector<int32_t>& labels, size_t count) {
  std::map<int32_t, int32_t> tags;
  if (labels.empty() && count > 0) tags[0] = 0;
  for (int32_t label : labels) tags[label] = 0;
  bool all_positive = !tags.empty() && tags.begin()->first > 0;
  int32_t next = 1;
  for (auto& [label, tag] : tags) tag = all_positive ? label : next++;
  return tags;
}

void append_entity(std::string& out, int32_t tag, const double box[6]) {
  append_int(out, tag);
  for (int k = 0; k < 6; ++k) {
    out += ' ';
    append_double(out, box[k]);
  }
  out += " 1 ";
  append_int(out, tag);
  out += " 0\n";  // no bounding entities
}

}  // namespace

Result<std::string> to_gmsh(const VolumeMesh& mesh, const PatchNames& patch_names) {
  Status valid = check_volume_arrays(mesh);
  if (!valid.ok()) return valid;
  if (Result<std::vector<NamedPatch>> named = named_patches(mesh.bnd_patch, patch_names); !named.ok()) {
    return named.status();
  }
  const size_t nv = mesh.num_vertices(), nt = mesh.num_tets(), nb = mesh.num_boundary_triangles();
  std::map<int32_t, int32_t> volumes = entity_tags(mesh.region, nt);
  std::map<int32_t, int32_t> surfaces = entity_tags(mesh.bnd_patch, nb);
  if (volumes.empty() && nv > 0) volumes[0] = 1;  // somewhere to put the nodes

  double box[6] = {0, 0, 0, 0, 0, 0};
  if (nv > 0) {
    for (int k = 0; k < 3; ++k) {
      box[k] = std::numeric_limits<double>::infinity();
      box[3 + k] = -box[k];
    }
    for (size_t v = 0; v < nv; ++v) {
      for (int k = 0; k < 3; ++k) {
        box[k] = std::min(box[k], mesh.xyz[3 * v + k]);
        box[3 + k] = std::max(box[3 + k], mesh.xyz[3 * v + k]);
      }
    }
  }
  std::string out = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  // Names of the physical groups: each patch's name, region<label> for each volume.
  const size_t named_surfaces = nb > 0 ? surfaces.size() : 0, named_volumes = nt > 0 ? volumes.size() : 0;
  if (named_surfaces + named_volumes > 0) {
    out += "$PhysicalNames\n";
    append_line(out, uint64_t{named_surfaces + named_volumes});
    auto append_name = [&out](int dim, int32_t tag, const std::string& name) {
      append_int(out, dim);
      out += ' ';
      append_int(out, tag);
      out += " \"" + name + "\"\n";
    };
    if (nb > 0) for (const auto& [label, tag] : surfaces) append_name(2, tag, patch_name(patch_names, label));
    if (nt > 0) for (const auto& [label, tag] : volumes) append_name(3, tag, region_name(label));
    out += "$EndPhysicalNames\n";
  }
  out += "$Entities\n";
  append_line(out, uint64_t{0}, uint64_t{0}, uint64_t{surfaces.size()}, uint64_t{volumes.size()});
  for (const auto& entry : surfaces) append_entity(out, entry.second, box);
  for (const auto& entry : volumes) append_entity(out, entry.second, box);
  out += "$EndEntities\n$Nodes\n";
  if (nv == 0) {
    out += "0 0 0 0\n";
  } else {
    append_line(out, uint64_t{1}, uint64_t{nv}, uint64_t{1}, uint64_t{nv});
    append_line(out, int32_t{3}, volumes.begin()->second, int32_t{0}, uint64_t{nv});
    for (size_t v = 0; v < nv; ++v) append_line(out, uint64_t{v + 1});
    for (size_t v = 0; v < nv; ++v) {
      append_line(out, mesh.xyz[3 * v], mesh.xyz[3 * v + 1], mesh.xyz[3 * v + 2]);
    }
  }
  out += "$EndNodes\n$Elements\n";
  // One block per entity: triangles by patch, then tets by region, each in input order.
  const size_t blocks = (nb > 0 ? surfaces.size() : 0) + (nt > 0 ? volumes.size() : 0);
  append_line(out, uint64_t{blocks}, uint64_t{nb + nt}, uint64_t{nb + nt > 0 ? 1u : 0u},
              uint64_t{nb + nt});
  uint64_t element_tag = 1;
  auto write_blocks = [&](const std::map<int32_t, int32_t>& entities,
                          const std::vector<int32_t>& labels, const std::vector<uint32_t>& vertices,
                          size_t count, int n, int dim, int type) {
    auto label_of = [&](size_t e) { return labels.empty() ? 0 : labels[e]; };
    std::vector<uint32_t> order(count);
    for (size_t e = 0; e < count; ++e) order[e] = static_cast<uint32_t>(e);
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return label_of(a) < label_of(b); });
    for (size_t first = 0; first < count;) {
      const int32_t label = label_of(order[first]);
      size_t last = first;
      while (last < count && label_of(order[last]) == label) ++last;
      append_line(out, int32_t{dim}, entities.at(label), int32_t{type}, uint64_t{last - first});
      for (size_t i = first; i < last; ++i) {
        append_int(out, static_cast<int64_t>(element_tag++));
        for (int k = 0; k < n; ++k) {
          out += ' ';
          append_int(out, int64_t{vertices[n * order[i] + k]} + 1);
        }
        out += '\n';
      }
      first = last;
    }
  };
  write_blocks(surfaces, mesh.bnd_patch, mesh.bnd_tri, nb, 3, 2, 2);
  write_blocks(volumes, mesh.region, mesh.tet, nt, 4, 3, 4);
  out += "$EndElements\n";
  return out;
}

}  // namespace anitet
