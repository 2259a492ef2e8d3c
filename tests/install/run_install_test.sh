#!/bin/sh
# run_install_test.sh: `cmake --install` into a fresh prefix, then, in a clean environment (no
# LD_LIBRARY_PATH; only the variables docs/building.md tells a user to set for a prefix outside
# the system's: PKG_CONFIG_PATH, CMAKE_PREFIX_PATH, PYTHONPATH), build and run programs with
# nothing but the installed files:
#   C with pkg-config, C with find_package(anitet) (CMake), Fortran with the installed module
#   through pkg-config and through find_package (when FORTRAN_COMPILER is set), Python meshing a
#   cube from the installed package (when PYTHON is set), the installed `anitet` tool meshing a
#   cube with the installed OpenVDB module;
# every installed ELF file and built program resolves its libraries, the programs through the
# RUNPATH pkg-config and CMake gave them. Then the same C and Fortran programs against the build
# tree: its pkg-config files (<build>/pkgconfig/*-uninstalled.pc) and CMake package (<build>/capi).
# Environment: BUILD_DIR WORK_DIR CONSUMER_DIR SPHERE_DIR LIBDIR DATADIR C_COMPILER CMAKE
#   SANITIZE_FLAGS (an instrumented library needs instrumented programs), FORTRAN_COMPILER,
#   PYTHON, PYTHON_DIR (the package's install directory, relative to the prefix).
set -eu
rm -rf "$WORK_DIR"
mkdir -p "$WORK_DIR"
prefix=$WORK_DIR/prefix
step() { echo "== $*"; }
# A clean environment: the sanitizers' options pass (ctest may set them), nothing else.
clean() {
  env -i PATH=/usr/bin:/bin HOME="$WORK_DIR" LANG=C.UTF-8 ${ASAN_OPTIONS+"ASAN_OPTIONS=$ASAN_OPTIONS"} \
    ${UBSAN_OPTIONS+"UBSAN_OPTIONS=$UBSAN_OPTIONS"} "$@"
}
user_env="PKG_CONFIG_PATH=$prefix/$LIBDIR/pkgconfig CMAKE_PREFIX_PATH=$prefix PYTHONPATH=$prefix/$PYTHON_DIR"
# The libraries an ELF file needs that the loader cannot find (ldd's "not found" lines).
unresolved() { clean ldd "$1" | grep "not found" || true; }
# Its RUNPATH must hold the installed libdir.
expect_runpath() {
  readelf -d "$1" | grep -q "(RUNPATH).*\[\(.*:\)\?$prefix/$LIBDIR\(:.*\)\?\]" ||
    { echo "$1: no RUNPATH $prefix/$LIBDIR:" >&2; readelf -d "$1" | grep PATH >&2; exit 1; }
}

# cc_pc ENV OUT / fortran_pc ENV OUT: the C / Fortran program built as a user would with
# pkg-config, in the clean environment plus ENV (assignments).
cc_pc() {
  # shellcheck disable=SC2086 # ENV and the flag lists
  (cd "$WORK_DIR" && clean $1 sh -c "\"$C_COMPILER\" -std=c99 -Wall -Wextra -pedantic -Werror $SANITIZE_FLAGS \
    -I\"$SPHERE_DIR\" \"$CONSUMER_DIR/consumer.c\" \$(pkg-config --cflags --libs anitet) -lm -o $2")
}
fortran_pc() {
  # shellcheck disable=SC2086
  (cd "$WORK_DIR" && clean $1 sh -c "\"$FORTRAN_COMPILER\" -std=f2008 $SANITIZE_FLAGS \
    \"$CONSUMER_DIR/consumer.f90\" \$(pkg-config --cflags --libs anitet-fortran) -o $2")
}
# cmake_consumer ENV DIR ARGS...: the consumer project configured (ARGS) and built in DIR.
cmake_consumer() {
  env_=$1 dir=$2
  shift 2
  # shellcheck disable=SC2086
  clean $env_ "$CMAKE" -S "$CONSUMER_DIR" -B "$dir" -DSPHERE_DIR="$SPHERE_DIR" -DCMAKE_C_COMPILER="$C_COMPILER" \
    -DWITH_FORTRAN=$fortran -DCMAKE_Fortran_COMPILER="${FORTRAN_COMPILER:-}" -DCMAKE_C_FLAGS="$SANITIZE_FLAGS" \
    -DCMAKE_Fortran_FLAGS="$SANITIZE_FLAGS" -DCMAKE_EXE_LINKER_FLAGS="$SANITIZE_FLAGS" "$@" >"$dir.configure.log"
  clean "$CMAKE" --build "$dir" >"$dir.build.log"
}
fortran=OFF
if [ -n "${FORTRAN_COMPILER:-}" ]; then fortran=ON; fi

step "cmake --install $BUILD_DIR --prefix $prefix"
clean "$CMAKE" --install "$BUILD_DIR" --prefix "$prefix" >"$WORK_DIR/install.log"
for f in "include/anitet.h" "$LIBDIR/libanitet.so" "$LIBDIR/pkgconfig/anitet.pc" \
         "$LIBDIR/cmake/anitet/anitetConfig.cmake" "$DATADIR/anitet/fortran/anitet.f90" \
         "$LIBDIR/anitet/libanitet_vdb.so" "$PYTHON_DIR/anitet/__init__.py" "bin/anitet"; do
  [ -e "$prefix/$f" ] || { echo "not installed: $f" >&2; exit 1; }
done
grep -q "^prefix=$prefix\$" "$prefix/$LIBDIR/pkgconfig/anitet.pc" ||
  { echo "anitet.pc does not name the prefix $prefix:" >&2; cat "$prefix/$LIBDIR/pkgconfig/anitet.pc" >&2; exit 1; }
step "every installed program and library finds its libraries"
for f in "$prefix"/bin/* "$prefix/$LIBDIR"/libanitet*.so* "$prefix/$LIBDIR"/anitet/*.so; do
  if [ -n "$(unresolved "$f")" ]; then echo "$f:" >&2; unresolved "$f" >&2; exit 1; fi
done
step "the installed anitet meshes a cube with the installed OpenVDB module"
printf '%s\n' OFF '8 12 0' '0 0 0' '1 0 0' '0 1 0' '1 1 0' '0 0 1' '1 0 1' '0 1 1' '1 1 1' '3 0 2 3' \
  '3 0 3 1' '3 4 5 7' '3 4 7 6' '3 0 1 5' '3 0 5 4' '3 2 6 7' '3 2 7 3' '3 0 4 6' '3 0 6 2' '3 1 3 7' \
  '3 1 7 5' >"$WORK_DIR/cube.off"
clean LD_DEBUG=libs "$prefix/bin/anitet" mesh "$WORK_DIR/cube.off" -o "$WORK_DIR/cube.mesh" >"$WORK_DIR/anitet.libs" 2>&1
grep -q "calling init: $prefix/bin/.*anitet/libanitet_vdb.so" "$WORK_DIR/anitet.libs" ||
  { echo "the installed anitet did not open $prefix's libanitet_vdb.so:" >&2;
    grep "libanitet_vdb\|anitet mesh" "$WORK_DIR/anitet.libs" >&2; exit 1; }

step "C with pkg-config: cc consumer.c \$(pkg-config --cflags --libs anitet)"
cc_pc "$user_env" consumer-pc
expect_runpath "$WORK_DIR/consumer-pc"
step "the OpenVDB module opened is the installed one (found from libanitet.so)"
clean LD_DEBUG=libs "$WORK_DIR/consumer-pc" >"$WORK_DIR/consumer-pc.libs" 2>&1
grep -q "calling init: $prefix/.*anitet/libanitet_vdb.so" "$WORK_DIR/consumer-pc.libs" ||
  { echo "the consumer did not open $prefix's libanitet_vdb.so:" >&2;
    grep "libanitet_vdb\|libopenvdb" "$WORK_DIR/consumer-pc.libs" >&2; exit 1; }
clean "$WORK_DIR/consumer-pc"

step "C (and Fortran: $fortran) with find_package(anitet), CMAKE_PREFIX_PATH=$prefix"
cmake_consumer "$user_env" "$WORK_DIR/cmake-build"
expect_runpath "$WORK_DIR/cmake-build/consumer"
clean "$WORK_DIR/cmake-build/consumer"

if [ $fortran = ON ]; then
  clean "$WORK_DIR/cmake-build/consumer_fortran"
  step "Fortran with pkg-config: gfortran consumer.f90 \$(pkg-config --cflags --libs anitet-fortran)"
  fortran_pc "$user_env" consumer-fortran
  expect_runpath "$WORK_DIR/consumer-fortran"
  clean "$WORK_DIR/consumer-fortran"
fi

if [ -n "${PYTHON:-}" ]; then
  step "Python: PYTHONPATH=$prefix/$PYTHON_DIR $PYTHON -c 'import anitet; ...'"
  # shellcheck disable=SC2086
  (cd "$WORK_DIR" && clean $user_env PYTHONDONTWRITEBYTECODE=1 "$PYTHON" -c '
import sys, anitet
assert anitet.__file__.startswith(sys.argv[1]), anitet.__file__
corners = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
faces = [(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4),
         (2, 6, 7), (2, 7, 3), (0, 4, 6), (0, 6, 2), (1, 3, 7), (1, 7, 5)]
cube = anitet.Surface.from_arrays(corners, faces)
mesh = cube.mesh(anitet.Metric.uniform(0.25))
q = mesh.quality(cube)
assert q.valid and q.boundary_constrained and q.tets > 12, q
print("installed Python package: anitet %s, a cube meshed into %d tets" % (anitet.version(), q.tets))
' "$prefix")
fi

step "the build tree's pkg-config files: PKG_CONFIG_PATH=$BUILD_DIR/pkgconfig"
cc_pc "PKG_CONFIG_PATH=$BUILD_DIR/pkgconfig" consumer-build-tree
clean "$WORK_DIR/consumer-build-tree"
if [ $fortran = ON ]; then
  fortran_pc "PKG_CONFIG_PATH=$BUILD_DIR/pkgconfig" consumer-fortran-build-tree
  clean "$WORK_DIR/consumer-fortran-build-tree"
fi
step "the build tree's CMake package: -Danitet_DIR=$BUILD_DIR/capi"
cmake_consumer "" "$WORK_DIR/cmake-build-tree" -Danitet_DIR="$BUILD_DIR/capi"
clean "$WORK_DIR/cmake-build-tree/consumer"
if [ $fortran = ON ]; then clean "$WORK_DIR/cmake-build-tree/consumer_fortran"; fi
echo "installed package: all consumers ran"
