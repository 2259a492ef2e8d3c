// The structs behind the opaque C handles.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "anitet.h"
#include "core/bl_prisms.hpp"
#include "core/sizing.hpp"
#include "core/surface_mesh.hpp"
#include "core/volume_mesh.hpp"
#include "core/vertex_fields.hpp"
#include "geo/geodetic.hpp"
#include "io/patch_names.hpp"
#include "metric/field_transfer.hpp"
#include "partition/partition.hpp"
#include "pipeline/mesher.hpp"
#include "mesh2d/mesher2.hpp"
#include "mesh2d/pslg.hpp"
#include "mesh2d/quality2.hpp"
#include "validate/validate.hpp"

struct anitet_surface {
  anitet::SurfaceMesh mesh;
  std::optional<anitet::ValidationReport> report;  // of the last anitet_surface_validate
};

struct anitet_mesh {
  anitet::VolumeMesh mesh;
  anitet::PatchNames patch_names;              // anitet_mesh_set_patch_name; used by anitet_mesh_write
  anitet::PatchTypes patch_types;              // anitet_mesh_set_patch_type; used by anitet_mesh_write
  std::unique_ptr<anitet::MesherResult> run;   // anitet_mesher_run's figures (its mesh moved out)
  // options->bl_cells ANITET_BL_CELLS_PRISMS: the boundary layer's prism cells (VolumeMesh::prism
  // order) and their regions, and per tet its prism or -1; `mesh` keeps every tet, and
  // anitet_mesh_write writes the prisms in place of their tets (capi_prisms.cpp).
  std::vector<uint32_t> prism;
  std::vector<int32_t> prism_region;
  std::vector<int32_t> tet_prism;
  anitet::PrismMergeStats prism_stats;  // the merge's figures (anitet_run_stats version 3)
  // A run with boundary-layer walls: their labels and the surface that was meshed, for
  // anitet_mesh_write_bl_columns (the slide patches' re-triangulated surface is run->slide's).
  std::vector<int32_t> bl_walls;
  anitet::SurfaceMesh bl_surface;
};

struct anitet_metric {
  enum class Kind { Uniform, Analytic, Field };
  Kind kind = Kind::Uniform;
  double size = 0.0;                  // Uniform
  anitet_metric_fn fn = nullptr;      // Analytic
  void* user_data = nullptr;
  // Field: a metric/ field read from a file or built on a background mesh (immutable, its
  // metric() may be called from several threads at once).
  std::shared_ptr<const anitet::SizingField> field;
};

struct anitet_fields {
  anitet::VertexFields fields;
  std::unique_ptr<anitet::metric::TransferReport> transfer;  // anitet_mesh_transfer_fields' findings
};

struct anitet_geo_frame {
  anitet::geo::GeoFrame frame;
};

struct anitet_part {
  anitet::partition::Part part;
  bool lent = false;  // one of a partition's parts: anitet_part_destroy leaves it alone
};

struct anitet_partition {
  std::vector<int32_t> tet_part;
  anitet::partition::PartitionQuality quality;
  int32_t ghost_layers = 0;
  std::vector<anitet_part> parts;
};

struct anitet_pslg {
  anitet::mesh2d::Pslg pslg;
};

struct anitet_mesh2d {
  anitet::mesh2d::TriMesh2 mesh;
  anitet::mesh2d::Quality2 quality;  // measured in the planar frame (before a geodetic mesh goes back to lon/lat)
};
