// Longitude/latitude input for the 2D mesher: a PSLG's coordinates to a local frame in metres
// (geo/: ENU or UTM, GeographicLib), and the mesh back, the input's points copied exactly (the
// round trip alone is not exact).
#pragma once

#include <vector>

#include "core/status.hpp"
#include "geo/geodetic.hpp"
#include "mesh2d/mesher2.hpp"
#include "mesh2d/pslg.hpp"

namespace anitet::mesh2d {

// (lon, lat) pairs to the frame's (x, y), or back (heights 0), in place.
Status convert_pairs(const geo::GeoFrame& frame, std::vector<double>& xy, bool to_local);

// The frame (centred on the input's points, or at lat, lon when `origin` holds two values) and
// the PSLG's points, holes and region points converted to it.
Result<geo::GeoFrame> pslg_to_local(Pslg& pslg, geo::FrameKind kind, const std::vector<double>& origin = {});

// The mesh's vertices back to (lon, lat); its first input_xy.size() / 2 vertices (the input's
// points) take input_xy's values exactly.
Status mesh_to_geodetic(const geo::GeoFrame& frame, TriMesh2& mesh, const std::vector<double>& input_xy);

}  // namespace anitet::mesh2d
