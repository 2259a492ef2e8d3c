// What a meshing run did, as JSON: the figures `anitet mesh --json` prints about the run (the
// quality report and the file names are the CLI's) and the C ABI's anitet_mesh_run_json returns.
#pragma once

#include <string>

#include "pipeline/mesher.hpp"

namespace anitet {

// An object: seconds, tets_per_second, estimated_tets, stages [{stage, seconds, tets, peak_bytes}], layers,
// recovery, coupling, refine, metric_quality, boundary_layer, optimize, notices [{kind, message}]
// (keys sorted).
std::string mesher_result_json(const MesherResult& r, int indent = 1);

}  // namespace anitet
