#!/usr/bin/env bash
# Installs everything anitet needs from Debian's packages. Idempotent: does nothing when all are
# present. Works as root, or through sudo for a normal user.
set -euo pipefail

packages=(
  cmake ninja-build g++ gfortran pkg-config
  libeigen3-dev libopenvdb-dev libboost-iostreams-dev libtbb-dev libgeographiclib-dev
  libgmp-dev libcli11-dev nlohmann-json3-dev
  zlib1g-dev  # compressed binary arrays in .vtu input (src/io/vtk_xml.cpp)
  libgtest-dev libgmock-dev libcmocka-dev libbenchmark-dev
  python3 python3-numpy python3-meshio
  python3-geographiclib  # geodesic edge lengths in the 2D checker (tests/tools/check2d.py)
  libcgns-dev libexodusii-dev  # the .cgns and Exodus II writers (optional at build time)
  cgns-convert openfoam python3-h5py python3-netcdf4  # their consumers in the `solver` tests
  doxygen  # renders the C API reference; its test fails on an undocumented declaration
  clang  # libFuzzer, for the fuzz targets of fuzz/ (scripts/fuzz.sh)
  libopenmpi-dev openmpi-bin  # anitet-mpi (mpi/) and its test under mpirun
  libptscotch-dev  # PT-Scotch: anitet-mpi partitions the coarse mesh with it (mpi/scotch_partition.cpp)
  libmetis-dev  # the partitioner of anitet_mesh_partition (src/partition)
)
packages+=("$@")  # extra packages a caller wants (bench/ adds gmsh, tetgen, libcgal-dev)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

if [[ $(id -u) -eq 0 ]]; then sudo=(); else sudo=(sudo); fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
