#!/bin/sh
# mpirun_oversubscribed.sh MPIEXEC RANKS PROGRAM [ARGS...]: PROGRAM on RANKS ranks, oversubscribed
# (CI has 2 cores). Open MPI refuses to start as root unless told (CI machines and containers run
# as root). Under AddressSanitizer leaks are not checked, the caller's other ASAN_OPTIONS kept:
# Open MPI keeps allocations until exit in components it has unloaded by then (unknown modules to
# LeakSanitizer, so they cannot be suppressed by name; tests/e2e/mesh_mpi_check.sh). The library
# code these runs use is leak-checked without MPI by test_capi_partition.
set -eu
mpiexec=$1
ranks=$2
shift 2
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
export ASAN_OPTIONS
exec "$mpiexec" --oversubscribe -np "$ranks" "$@"
