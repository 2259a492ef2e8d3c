#include "mesh2d/geodetic2.hpp"

#include <algorithm>

namespace anitet::mesh2d {

Status convert_pairs(const geo::GeoFrame& frame, std::vector<double>& xy, bool to_local) {
  std::vector<double> xyz(xy.size() / 2 * 3, 0.0);
  for (size_t i = 0; i < xy.size() / 2; ++i) xyz[3 * i] = xy[2 * i], xyz[3 * i + 1] = xy[2 * i + 1];
  Status s = to_local ? geo::to_local(frame, xyz) : geo::to_geodetic(frame, xyz);
  if (!s.ok()) return s;
  for (size_t i = 0; i < xy.size() / 2; ++i) xy[2 * i] = xyz[3 * i], xy[2 * i + 1] = xyz[3 * i + 1];
  return Status::success();
}

Result<geo::GeoFrame> pslg_to_local(Pslg& p, geo::FrameKind kind, const std::vector<double>& origin) {
  Result<geo::GeoFrame> frame = Status(Error::Internal, "");
  if (origin.size() == 2) {
    frame = geo::make_frame(kind, origin[0], origin[1]);
  } else {
    std::vector<double> xyz(p.num_points() * 3, 0.0);
    for (size_t i = 0; i < p.num_points(); ++i) xyz[3 * i] = p.xy[2 * i], xyz[3 * i + 1] = p.xy[2 * i + 1];
    frame = geo::centred_frame(kind, xyz);
  }
  if (!frame.ok()) return frame.status();
  if (Status s = convert_pairs(frame.value(), p.xy, true); !s.ok()) return s;
  if (Status s = convert_pairs(frame.value(), p.holes, true); !s.ok()) return s;
  std::vector<double> r;
  for (const Region& g : p.regions) r.insert(r.end(), {g.x, g.y});
  if (Status s = convert_pairs(frame.value(), r, true); !s.ok()) return s;
  for (size_t i = 0; i < p.regions.size(); ++i) p.regions[i].x = r[2 * i], p.regions[i].y = r[2 * i + 1];
  return frame;
}

Status mesh_to_geodetic(const geo::GeoFrame& frame, TriMesh2& mesh, const std::vector<double>& input_xy) {
  if (input_xy.size() > mesh.xy.size()) return Status(Error::InvalidArgument, "more input points than mesh vertices");
  if (Status s = convert_pairs(frame, mesh.xy, false); !s.ok()) return s;
  std::copy(input_xy.begin(), input_xy.end(), mesh.xy.begin());
  return Status::success();
}

}  // namespace anitet::mesh2d
