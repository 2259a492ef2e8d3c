#!/bin/sh
# usage: vdb_module.sh ANITET SURFACE WORKSTEM
# OpenVDB is loaded when the first metric field is built (metric/vdb_backend.hpp), not when the
# tool starts: `anitet --version` must not initialise libopenvdb, and a mesh run must load the
# module libanitet_vdb.so (which also shows that the dynamic loader's log names what it loads).
anitet=$1 surface=$2 work=$3
LD_DEBUG=libs "$anitet" --version > "$work.version.log" 2>&1 || { echo "anitet --version failed"; exit 1; }
if grep -q 'calling init: .*libopenvdb' "$work.version.log"; then
  echo "libopenvdb is loaded at start-up"; exit 1
fi
LD_DEBUG=libs "$anitet" mesh "$surface" -o "$work.mesh" -q > "$work.mesh.log" 2>&1 ||
  { echo "anitet mesh failed"; tail -5 "$work.mesh.log"; exit 1; }
grep -q 'calling init: .*libanitet_vdb' "$work.mesh.log" ||
  { echo "a mesh run did not load libanitet_vdb"; exit 1; }
grep -q 'calling init: .*libopenvdb' "$work.mesh.log" ||
  { echo "a mesh run did not load libopenvdb"; exit 1; }
# $ANITET_VDB_MODULE alone is tried when set: a missing file, or a library that is not the module,
# refuses the field (NotImplemented, exit 5) naming it, instead of crashing or meshing without it.
for bad in "$work.missing.so" "$(ldd "$anitet" | awk '/libm\.so/ {print $3}')"; do
  ANITET_VDB_MODULE=$bad "$anitet" mesh "$surface" -o "$work.bad.mesh" -q > "$work.bad.log" 2>&1
  rc=$?
  [ "$rc" = 5 ] || { echo "ANITET_VDB_MODULE=$bad: exit $rc, expected 5"; cat "$work.bad.log"; exit 1; }
  grep -q "OpenVDB module" "$work.bad.log" || { echo "no clear error for $bad"; cat "$work.bad.log"; exit 1; }
done
echo "libopenvdb not loaded at start-up; loaded with libanitet_vdb by a mesh run; a wrong module refused"
