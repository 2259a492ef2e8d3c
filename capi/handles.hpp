// The structs behind the opaque C handles.
#pragma once

#include <optional>

#include "anitet.h"
#include "core/surface_mesh.hpp"
#include "core/volume_mesh.hpp"
#include "validate/validate.hpp"

struct anitet_surface {
  anitet::SurfaceMesh mesh;
  std::optional<anitet::ValidationReport> report;  // of the last anitet_surface_validate
};

struct anitet_mesh {
  anitet::VolumeMesh mesh;
};

struct anitet_metric {
  enum class Kind { Uniform, Analytic };
  Kind kind = Kind::Uniform;
  double size = 0.0;                  // Uniform
  anitet_metric_fn fn = nullptr;      // Analytic
  void* user_data = nullptr;
};
