// Test fixture of the C ABI's metric tests: writes small .vdb metric files into the directory
// given as argv[1] with the metric/ library (the C ABI reads .vdb files but does not write them):
//   size_linear.vdb  grid "size": h = 0.2 + 0.1 x on [-0.5, 1.5]^3 (spacing 0.25)
//   size_fine.vdb    grid "size": h = 0.25 everywhere on the same box
//   size_coarse.vdb  grid "size": h = 0.5
//   tensor.vdb       six "log_metric_*" grids: M = diag(1/0.1^2, 1/0.2^2, 1/0.4^2)
#include <cstdio>
#include <string>

#include "metric/lattice.hpp"
#include "metric/metric_field.hpp"

namespace {

anitet::metric::Lattice size_lattice(double h0, double slope) {
  anitet::metric::Lattice lat;
  lat.spacing = 0.25;
  lat.components = 1;
  for (int k = 0; k < 3; ++k) {
    lat.origin[k] = -0.5;
    lat.dims[k] = 9;
  }
  lat.values.resize(lat.num_nodes());
  for (int k = 0; k < lat.dims[2]; ++k)
    for (int j = 0; j < lat.dims[1]; ++j)
      for (int i = 0; i < lat.dims[0]; ++i) {
        double p[3];
        lat.position(i, j, k, p);
        lat.values[lat.node(i, j, k)] = h0 + slope * p[0];
      }
  return lat;
}

bool write(const anitet::Result<anitet::metric::MetricField>& field, const std::string& path) {
  if (!field.ok()) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), field.status().message().c_str());
    return false;
  }
  const anitet::Status st = anitet::metric::write_metric_vdb(field.value(), path, true);
  if (!st.ok()) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), st.message().c_str());
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIR\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  using anitet::metric::MetricField;
  bool ok = write(MetricField::from_lattice(size_lattice(0.2, 0.1)), dir + "/size_linear.vdb");
  ok = write(MetricField::from_lattice(size_lattice(0.25, 0.0)), dir + "/size_fine.vdb") && ok;
  ok = write(MetricField::from_lattice(size_lattice(0.5, 0.0)), dir + "/size_coarse.vdb") && ok;
  const double lo[3] = {-0.5, -0.5, -0.5}, hi[3] = {1.5, 1.5, 1.5};
  ok = write(MetricField::from_function(
                 [](const double*, double m[6]) {
                   const double tensor[6] = {100.0, 0.0, 25.0, 0.0, 0.0, 6.25};
                   for (int c = 0; c < 6; ++c) m[c] = tensor[c];
                 },
                 lo, hi, 0.5),
             dir + "/tensor.vdb") &&
       ok;
  return ok ? 0 : 1;
}
