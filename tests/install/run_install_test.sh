#!/bin/sh
# run_install_test.sh: install the `capi` component into a fresh prefix, then build and run
# separate projects against it with nothing but the installed files:
#   C with find_package(anitet) (CMake), C with pkg-config, Fortran with the installed module
#   source and pkg-config (when FORTRAN_COMPILER is set), Python from the installed package
#   without ANITET_LIBRARY (when PYTHON is set).
# Environment: BUILD_DIR WORK_DIR CONSUMER_DIR SPHERE_DIR LIBDIR DATADIR C_COMPILER CMAKE
#   SANITIZE_FLAGS (an instrumented library needs instrumented programs), FORTRAN_COMPILER,
#   PYTHON, PYTHON_DIR (the package's install directory, relative to the prefix).
set -eu
rm -rf "$WORK_DIR"
mkdir -p "$WORK_DIR"
prefix=$WORK_DIR/prefix
step() { echo "== $*"; }

step "install into $prefix"
"$CMAKE" --install "$BUILD_DIR" --component capi --prefix "$prefix" >"$WORK_DIR/install.log"
for f in "include/anitet.h" "$LIBDIR/libanitet.so" "$LIBDIR/pkgconfig/anitet.pc" \
         "$LIBDIR/cmake/anitet/anitetConfig.cmake" "$DATADIR/anitet/fortran/anitet.f90" \
         "$LIBDIR/anitet/libanitet_vdb.so"; do
  [ -e "$prefix/$f" ] || { echo "not installed: $f" >&2; exit 1; }
done

step "C consumer with find_package(anitet)"
"$CMAKE" -S "$CONSUMER_DIR" -B "$WORK_DIR/cmake-build" -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_C_COMPILER="$C_COMPILER" -DSPHERE_DIR="$SPHERE_DIR" \
  -DCMAKE_C_FLAGS="$SANITIZE_FLAGS" -DCMAKE_EXE_LINKER_FLAGS="$SANITIZE_FLAGS" >"$WORK_DIR/configure.log"
"$CMAKE" --build "$WORK_DIR/cmake-build" >"$WORK_DIR/build.log"
"$WORK_DIR/cmake-build/consumer"

step "C consumer with pkg-config"
export PKG_CONFIG_PATH="$prefix/$LIBDIR/pkgconfig"
cflags=$(pkg-config --cflags anitet)
libs=$(pkg-config --libs anitet)
# shellcheck disable=SC2086 # flag lists
"$C_COMPILER" -std=c99 -Wall -Wextra -pedantic -Werror $SANITIZE_FLAGS $cflags -I"$SPHERE_DIR" \
  "$CONSUMER_DIR/consumer.c" $libs -lm -Wl,-rpath,"$prefix/$LIBDIR" -o "$WORK_DIR/consumer-pc"

step "the OpenVDB module opened is the installed one (found from libanitet.so)"
LD_DEBUG=libs "$WORK_DIR/consumer-pc" >"$WORK_DIR/consumer-pc.libs" 2>&1
grep -q "calling init: $prefix/.*anitet/libanitet_vdb.so" "$WORK_DIR/consumer-pc.libs" ||
  { echo "the consumer did not open $prefix's libanitet_vdb.so:" >&2;
    grep "libanitet_vdb\|libopenvdb" "$WORK_DIR/consumer-pc.libs" >&2; exit 1; }
"$WORK_DIR/consumer-pc"

if [ -n "${FORTRAN_COMPILER:-}" ]; then
  step "Fortran consumer with the installed module source and pkg-config"
  mkdir -p "$WORK_DIR/fortran"
  # shellcheck disable=SC2086
  (cd "$WORK_DIR/fortran" &&
    "$FORTRAN_COMPILER" -std=f2008 $SANITIZE_FLAGS "$prefix/$DATADIR/anitet/fortran/anitet.f90" \
      "$CONSUMER_DIR/consumer.f90" $libs -Wl,-rpath,"$prefix/$LIBDIR" -o consumer-fortran)
  "$WORK_DIR/fortran/consumer-fortran"
fi

if [ -n "${PYTHON:-}" ]; then
  step "Python from the installed package (library found through its _installed.py)"
  (cd "$WORK_DIR" && env -u ANITET_LIBRARY PYTHONPATH="$prefix/$PYTHON_DIR" PYTHONDONTWRITEBYTECODE=1 \
    "$PYTHON" -c '
import sys, anitet
assert anitet.__file__.startswith(sys.argv[1]), anitet.__file__
s = anitet.Surface.from_arrays([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)],
                               [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)])
s.validate()
print("installed Python package: anitet", anitet.version())
' "$prefix")
fi
echo "installed package: all consumers ran"
