// Volume meshes: creation from caller arrays or a file, accessors, writing, quality.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "caller_sizing.hpp"
#include "handles.hpp"
#include "io/volume_io.hpp"
#include "metric/sol_field.hpp"
#include "prism_cells.hpp"
#include "quality/quality_report.hpp"
#include "shim.hpp"

using namespace anitet::capi;

namespace {

anitet::Result<anitet::QualityReport> measure(const anitet_mesh* mesh, const anitet_surface* input) {
  anitet::QualityOptions options;
  return anitet::compute_quality_report(mesh->mesh, input ? &input->mesh : nullptr, options);
}

bool has_patch(const anitet_mesh& mesh, int32_t label) {
  const auto& labels = mesh.mesh.bnd_patch;
  return std::find(labels.begin(), labels.end(), label) != labels.end();
}

int no_patch(const char* fn, int32_t label) {
  return set_error(ANITET_ERR_INVALID_ARGUMENT,
                   std::string(fn) + ": no boundary triangle has patch label " + std::to_string(label));
}

// ANITET_PATCH_TYPE_* are anitet::PatchKind's values.
static_assert(ANITET_PATCH_TYPE_WALL == int(anitet::PatchKind::Wall) &&
                  ANITET_PATCH_TYPE_INLET == int(anitet::PatchKind::Inlet) &&
                  ANITET_PATCH_TYPE_OUTLET == int(anitet::PatchKind::Outlet) &&
                  ANITET_PATCH_TYPE_FARFIELD == int(anitet::PatchKind::Farfield) &&
                  ANITET_PATCH_TYPE_SYMMETRY == int(anitet::PatchKind::Symmetry) &&
                  ANITET_PATCH_TYPE_PATCH == int(anitet::PatchKind::Patch),
              "ANITET_PATCH_TYPE_* differ from anitet::PatchKind");

}  // namespace

extern "C" {

int anitet_mesh_create(const double* xyz, int64_t num_points, const int32_t* tets,
                       int64_t num_tets, const int32_t* regions, const int32_t* bnd_tri,
                       int64_t num_boundary_triangles, const int32_t* bnd_patch,
                       int32_t index_base, anitet_mesh** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (index_base != 0 && index_base != 1) return bad_index_base(fn, index_base);
    if (num_points < 0 || num_tets < 0 || num_boundary_triangles < 0) {
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": negative count");
    }
    if (num_points == 0 || num_tets == 0) {
      return set_error(ANITET_ERR_EMPTY_INPUT, std::string(fn) + ": no point or no tet");
    }
    if (xyz == nullptr) return null_argument(fn, "xyz");
    if (tets == nullptr) return null_argument(fn, "tets");
    if (num_boundary_triangles > 0 && bnd_tri == nullptr) return null_argument(fn, "bnd_tri");
    if (num_points > int64_t(INT32_MAX)) {
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": too many points for int32_t indices");
    }
    auto mesh = std::make_unique<anitet_mesh>();
    anitet::VolumeMesh& m = mesh->mesh;
    m.xyz.assign(xyz, xyz + 3 * num_points);
    int code = convert_indices(fn, "tet", tets, num_tets, 4, num_points, index_base, m.tet);
    if (code != ANITET_OK) return code;
    if (regions) m.region.assign(regions, regions + num_tets);
    else m.region.assign(size_t(num_tets), 0);
    if (num_boundary_triangles > 0) {
      code = convert_indices(fn, "boundary triangle", bnd_tri, num_boundary_triangles, 3,
                             num_points, index_base, m.bnd_tri);
      if (code != ANITET_OK) return code;
      if (bnd_patch) m.bnd_patch.assign(bnd_patch, bnd_patch + num_boundary_triangles);
      else m.bnd_patch.assign(size_t(num_boundary_triangles), 0);
    }
    *out = mesh.release();
    return ok();
  });
}

int anitet_mesh_read(const char* path, anitet_mesh** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (path == nullptr) return null_argument(fn, "path");
    anitet::Result<anitet::VolumeMesh> read = anitet::read_volume_mesh(std::string(path));
    if (!read.ok()) return set_status(fn, read.status());
    auto mesh = std::make_unique<anitet_mesh>();
    mesh->mesh = std::move(read).value();
    if (mesh->mesh.region.empty()) mesh->mesh.region.assign(mesh->mesh.num_tets(), 0);
    *out = mesh.release();
    return ok();
  });
}

void anitet_mesh_destroy(anitet_mesh* mesh) { delete mesh; }

int anitet_mesh_write(const anitet_mesh* mesh, const char* path) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (path == nullptr) return null_argument(fn, "path");
    if (mesh->prism.empty())
      return set_status(fn, anitet::write_volume_mesh(mesh->mesh, std::string(path), mesh->patch_names,
                                                      mesh->patch_types));
    // The mesher's options asked for prism cells (bl_cells): a format of tets only refuses them.
    return set_status(fn, anitet::write_volume_mesh(written_cells(*mesh), std::string(path), mesh->patch_names,
                                                    mesh->patch_types));
  });
}

int anitet_mesh_sample_metric(anitet_mesh* mesh, const anitet_metric* metric) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (metric == nullptr) return null_argument(fn, "metric");
    const CallerSizing sizing(*metric, 1.0);
    anitet::VolumeMesh& m = mesh->mesh;
    std::vector<double> before = std::move(m.vertex_metric);
    anitet::metric::sample_sizes_or_tensors(sizing, m);
    if (sizing.failed()) {
      m.vertex_metric = std::move(before);
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": " + sizing.failure());
    }
    return ok();
  });
}

int anitet_mesh_set_patch_name(anitet_mesh* mesh, int32_t label, const char* name) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (!has_patch(*mesh, label)) return no_patch(fn, label);
    if (name == nullptr) {
      mesh->patch_names.erase(label);
      return ok();
    }
    std::string n(name);
    if (anitet::Status s = anitet::check_patch_name(n); !s.ok()) return set_status(fn, s);
    mesh->patch_names[label] = std::move(n);
    return ok();
  });
}

int anitet_mesh_set_patch_type(anitet_mesh* mesh, int32_t label, int32_t type) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (type < ANITET_PATCH_TYPE_FROM_NAME || type > ANITET_PATCH_TYPE_PATCH)
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": type is " + std::to_string(type) +
                                                        ", not an ANITET_PATCH_TYPE_* value (-1..5)");
    if (!has_patch(*mesh, label)) return no_patch(fn, label);
    if (type == ANITET_PATCH_TYPE_FROM_NAME) mesh->patch_types.erase(label);
    else mesh->patch_types[label] = static_cast<anitet::PatchKind>(type);
    return ok();
  });
}

int anitet_mesh_get_patch_type(const anitet_mesh* mesh, int32_t label, int32_t* type) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (type == nullptr) return null_argument(fn, "type");
    if (!has_patch(*mesh, label)) return no_patch(fn, label);
    *type = static_cast<int32_t>(
        anitet::patch_kind(mesh->patch_types, label, anitet::patch_name(mesh->patch_names, label)));
    return ok();
  });
}

int anitet_mesh_write_metric(const anitet_mesh* mesh, const char* path) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (path == nullptr) return null_argument(fn, "path");
    if (mesh->mesh.vertex_metric.empty()) {
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": the mesh has no per-vertex metric");
    }
    return set_status(fn, anitet::write_sol(mesh->mesh, std::string(path)));
  });
}

int anitet_mesh_get_counts(const anitet_mesh* mesh, int64_t* num_points, int64_t* num_tets,
                           int64_t* num_boundary_triangles) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (num_points) *num_points = static_cast<int64_t>(mesh->mesh.num_vertices());
    if (num_tets) *num_tets = static_cast<int64_t>(mesh->mesh.num_tets());
    if (num_boundary_triangles) {
      *num_boundary_triangles = static_cast<int64_t>(mesh->mesh.num_boundary_triangles());
    }
    return ok();
  });
}

int anitet_mesh_get_points(const anitet_mesh* mesh, double* xyz, int64_t xyz_len) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    return fill(fn, "xyz", mesh->mesh.xyz, xyz, xyz_len, kSame);
  });
}

int anitet_mesh_get_tets(const anitet_mesh* mesh, int32_t* tets, int64_t tets_len,
                         int32_t index_base) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (index_base != 0 && index_base != 1) return bad_index_base(fn, index_base);
    return fill(fn, "tets", mesh->mesh.tet, tets, tets_len,
                [&](uint32_t v) { return static_cast<int32_t>(v) + index_base; });
  });
}

int anitet_mesh_get_regions(const anitet_mesh* mesh, int32_t* regions, int64_t regions_len) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    return fill(fn, "regions", mesh->mesh.region, regions, regions_len, kSame);
  });
}

int anitet_mesh_get_boundary_triangles(const anitet_mesh* mesh, int32_t* tri, int64_t tri_len,
                                       int32_t index_base) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (index_base != 0 && index_base != 1) return bad_index_base(fn, index_base);
    return fill(fn, "tri", mesh->mesh.bnd_tri, tri, tri_len,
                [&](uint32_t v) { return static_cast<int32_t>(v) + index_base; });
  });
}

int anitet_mesh_get_boundary_patches(const anitet_mesh* mesh, int32_t* patch, int64_t patch_len) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    return fill(fn, "patch", mesh->mesh.bnd_patch, patch, patch_len, kSame);
  });
}

int anitet_mesh_get_metric_components(const anitet_mesh* mesh, int32_t* components) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (components == nullptr) return null_argument(fn, "components");
    const size_t n = mesh->mesh.num_vertices();
    *components = n == 0 ? 0 : static_cast<int32_t>(mesh->mesh.vertex_metric.size() / n);
    return ok();
  });
}

int anitet_mesh_get_metric(const anitet_mesh* mesh, double* values, int64_t values_len) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    return fill(fn, "values", mesh->mesh.vertex_metric, values, values_len, kSame);
  });
}

int anitet_mesh_set_metric(anitet_mesh* mesh, const double* values, int64_t values_len,
                           int32_t components) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (components == 0) {
      mesh->mesh.vertex_metric.clear();
      return ok();
    }
    if (components != 1 && components != 6) {
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": components is " +
                                                        std::to_string(components) + ", not 0, 1 or 6");
    }
    if (values == nullptr) return null_argument(fn, "values");
    const uint64_t needed = uint64_t(components) * mesh->mesh.num_vertices();
    if (values_len < 0 || uint64_t(values_len) != needed) {
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": values_len is " +
                                                        std::to_string(values_len) + ", " +
                                                        std::to_string(needed) + " expected");
    }
    for (uint64_t i = 0; i < needed; ++i) {
      if (!std::isfinite(values[i]) || (components == 1 && !(values[i] > 0.0))) {
        return set_error(ANITET_ERR_INVALID_ARGUMENT,
                         std::string(fn) + ": value " + std::to_string(i) + " of point " +
                             std::to_string(i / uint64_t(components)) + " is " +
                             std::to_string(values[i]) +
                             (components == 1 ? " (sizes must be finite and positive)" : " (not finite)"));
      }
    }
    mesh->mesh.vertex_metric.assign(values, values + needed);
    return ok();
  });
}

int anitet_mesh_quality(const anitet_mesh* mesh, const anitet_surface* input, anitet_quality* out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (out == nullptr) return null_argument(fn, "out");
    const int32_t version = out->version;
    if (version < 1 || version > ANITET_QUALITY_VERSION) {
      return set_error(ANITET_ERR_INVALID_ARGUMENT,
                       std::string(fn) + ": quality struct version " + std::to_string(version) +
                           " is not supported (1.." + std::to_string(ANITET_QUALITY_VERSION) +
                           "); initialise with ANITET_QUALITY_INIT");
    }
    anitet::Result<anitet::QualityReport> report = measure(mesh, input);
    if (!report.ok()) return set_status(fn, report.status());
    const anitet::QualityReport& r = report.value();
    // Version 1 fields (all there are today).
    anitet_quality q = ANITET_QUALITY_INIT;
    q.version = version;
    q.valid = r.valid ? 1 : 0;
    q.boundary_constrained = r.surface.boundary_constrained ? 1 : 0;
    q.vertices = static_cast<int64_t>(r.vertices);
    q.tets = static_cast<int64_t>(r.tets);
    q.nonpositive_tets = static_cast<int64_t>(r.nonpositive_tets);
    q.radius_ratio_mean = r.radius_ratio.mean;
    q.radius_ratio_min = r.radius_ratio.min;
    q.mean_ratio_mean = r.mean_ratio.mean;
    q.mean_ratio_min = r.mean_ratio.min;
    q.min_dihedral_deg = r.min_dihedral_deg;
    q.max_dihedral_deg = r.max_dihedral_deg;
    q.good_fraction = r.good_fraction;
    q.bad_fraction = r.bad_fraction;
    // Write only the caller's version of the struct: a v1 caller's struct is smaller than a later
    // one (today v1 is the whole struct).
    *out = q;
    return ok();
  });
}

int anitet_mesh_quality_json(const anitet_mesh* mesh, const anitet_surface* input, char* buf,
                             int64_t buf_len, int64_t* needed) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (needed) *needed = 0;
    if (mesh == nullptr) return null_argument(fn, "mesh");
    anitet::Result<anitet::QualityReport> report = measure(mesh, input);
    if (!report.ok()) return set_status(fn, report.status());
    // The size query and the fill must produce the same text: leave the timing out.
    report->seconds = 0.0;
    return copy_text(fn, anitet::quality_report_json(report.value()), buf, buf_len, needed);
  });
}

}  // extern "C"
