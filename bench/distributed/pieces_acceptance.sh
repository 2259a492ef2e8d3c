#!/bin/sh
# Issue 51's acceptance runs of the pieces path: armadillo at about 10^7 tets (--size 0.63) in one
# process, then on 4 and 2 ranks (mpirun --oversubscribe, -o NAME.pvtu), one at a time; each
# rank prints its peak RSS (ANITET_RANK_STATS=1) and its memory after each phase
# (ANITET_RANK_MEMORY=1). Then the interface figure
# (interface_quality.py) and anitet merge of the 4-rank pieces. About 25 min on 2 cores.
# Usage: bench/distributed/pieces_acceptance.sh BUILD_DIR OUT_DIR
set -eu
B=$(cd "$1" && pwd); mkdir -p "$2"; cd "$2"
here=$(dirname "$0")
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ANITET_RANK_STATS=1 ANITET_RANK_MEMORY=1
S=${ANITET_SURFACES_DIR:-/work/shared/data/surfaces}/armadillo.obj
uptime > machine.txt; free -g >> machine.txt
/usr/bin/time -f "serial: wall %e s, peak RSS %M KB" "$B/app/anitet" mesh "$S" --size 0.63 -o serial.mesh > serial.log 2>&1
for np in 4 2; do
  /usr/bin/time -f "mpirun np $np: wall %e s" mpirun -x ANITET_RANK_STATS -x ANITET_RANK_MEMORY --oversubscribe -np $np \
    "$B/mpi/anitet-mpi" mesh "$S" --size 0.63 -o r$np.pvtu > r$np.log 2>&1
  /usr/bin/python3 "$OLDPWD/$here/interface_quality.py" r$np.pvtu > r$np.interfaces.json
done
"$B/app/anitet" merge r4.pvtu -o r4.meshb
