// Geographic coordinates: frames on WGS84 (src/geo) and the moves of surfaces and meshes between
// (lon, lat, h) and a frame's metres.
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "geo/geodetic.hpp"
#include "handles.hpp"
#include "shim.hpp"

using namespace anitet::capi;

namespace {

int frame_kind(const char* fn, int32_t kind, anitet::geo::FrameKind& out) {
  if (kind != ANITET_GEO_ENU && kind != ANITET_GEO_UTM)
    return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": kind is " + std::to_string(kind) +
                                                      ", not ANITET_GEO_ENU (0) or ANITET_GEO_UTM (1)");
  out = kind == ANITET_GEO_UTM ? anitet::geo::FrameKind::Utm : anitet::geo::FrameKind::Enu;
  return ANITET_OK;
}

int new_frame(const char* fn, const anitet::Result<anitet::geo::GeoFrame>& frame, anitet_geo_frame** out) {
  if (!frame.ok()) return set_status(fn, frame.status());
  *out = new anitet_geo_frame{frame.value()};
  return ok();
}

}  // namespace

extern "C" {

int anitet_geo_frame_create(int32_t kind, double lat, double lon, double height, anitet_geo_frame** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    anitet::geo::FrameKind k;
    if (const int code = frame_kind(fn, kind, k); code != ANITET_OK) return code;
    return new_frame(fn, anitet::geo::make_frame(k, lat, lon, height), out);
  });
}

int anitet_geo_frame_create_centred(int32_t kind, const anitet_surface* surface, anitet_geo_frame** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (surface == nullptr) return null_argument(fn, "surface");
    anitet::geo::FrameKind k;
    if (const int code = frame_kind(fn, kind, k); code != ANITET_OK) return code;
    return new_frame(fn, anitet::geo::centred_frame(k, surface->mesh.xyz), out);
  });
}

void anitet_geo_frame_destroy(anitet_geo_frame* frame) { delete frame; }

int anitet_geo_frame_get(const anitet_geo_frame* frame, double* lat, double* lon, double* height,
                         int32_t* utm_zone, int32_t* utm_north) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (frame == nullptr) return null_argument(fn, "frame");
    const anitet::geo::GeoFrame& f = frame->frame;
    if (lat) *lat = f.origin_lat;
    if (lon) *lon = f.origin_lon;
    if (height) *height = f.origin_height;
    const bool utm = f.kind == anitet::geo::FrameKind::Utm;
    if (utm_zone) *utm_zone = utm ? f.zone : 0;
    if (utm_north) *utm_north = utm && f.north ? 1 : 0;
    return ok();
  });
}

int anitet_surface_to_local(anitet_surface* surface, const anitet_geo_frame* frame) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (surface == nullptr) return null_argument(fn, "surface");
    if (frame == nullptr) return null_argument(fn, "frame");
    if (anitet::Status st = anitet::geo::to_local(frame->frame, surface->mesh.xyz); !st.ok()) return set_status(fn, st);
    surface->report.reset();  // of the coordinates before the move
    return ok();
  });
}

int anitet_mesh_to_local(anitet_mesh* mesh, const anitet_geo_frame* frame) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (frame == nullptr) return null_argument(fn, "frame");
    return set_status(fn, anitet::geo::to_local(frame->frame, mesh->mesh.xyz));
  });
}

int anitet_mesh_to_geodetic(anitet_mesh* mesh, const anitet_geo_frame* frame, const anitet_surface* geodetic_surface) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (frame == nullptr) return null_argument(fn, "frame");
    const std::vector<uint32_t>* input_vertex = mesh->run ? &mesh->run->input_vertex : nullptr;
    if (geodetic_surface != nullptr) {
      const size_t n = geodetic_surface->mesh.num_vertices();
      if (input_vertex == nullptr || input_vertex->empty())
        return set_error(ANITET_ERR_INVALID_ARGUMENT,
                         std::string(fn) + ": geodetic_surface given, but the mesh was not made by anitet_mesher_run");
      if (input_vertex->size() != n)
        return set_error(ANITET_ERR_INVALID_ARGUMENT,
                         std::string(fn) + ": geodetic_surface has " + std::to_string(n) +
                             " points, the surface the mesh was made from " + std::to_string(input_vertex->size()) +
                             " (a repair merged points, or another surface)");
    }
    std::vector<double>& xyz = mesh->mesh.xyz;
    if (anitet::Status st = anitet::geo::to_geodetic(frame->frame, xyz); !st.ok()) return set_status(fn, st);
    if (geodetic_surface != nullptr) {
      const std::vector<double>& exact = geodetic_surface->mesh.xyz;
      for (size_t v = 0; v < input_vertex->size(); ++v) {
        const uint32_t to = (*input_vertex)[v];
        if (to != anitet::TetMesh::kNone) std::copy_n(&exact[3 * v], 3, &xyz[3 * size_t(to)]);
      }
    }
    return ok();
  });
}

}  // extern "C"
