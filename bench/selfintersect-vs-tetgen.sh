#!/bin/bash
# Self-intersection check on skull.obj: `tetgen -d` against `anitet check-surface` (full
# validation: topology, exact self-intersection search, shells), same machine, same script,
# best of 5 runs each (the machine is shared and noisy).
# Usage: bench/selfintersect-vs-tetgen.sh ANITET_BINARY [SURFACE.obj]
set -euo pipefail
ANITET=${1:?anitet binary}
SURF=${2:-$(cd "$(dirname "$0")/.." && pwd)/../shared/data/surfaces/skull.obj}
W=$(mktemp -d); trap 'rm -rf "$W"' EXIT
python3 - "$SURF" "$W/s.off" <<'PY'
import sys
vs, fs = [], []
for line in open(sys.argv[1]):
    p = line.split()
    if p and p[0] == 'v': vs.append(' '.join(p[1:4]))
    elif p and p[0] == 'f': fs.append([int(x.split('/')[0]) - 1 for x in p[1:]])
with open(sys.argv[2], 'w') as o:
    o.write('OFF\n%d %d 0\n' % (len(vs), len(fs)))
    o.write('\n'.join(vs) + '\n')
    o.write(''.join('%d %s\n' % (len(f), ' '.join(map(str, f))) for f in fs))
PY
best() { sort -g | head -1; }
run_tetgen() { /usr/bin/time -f %e tetgen -d "$W/s.off" 2>&1 >"$W/tetgen.log" | tail -1; }
run_anitet() { /usr/bin/time -f %e "$ANITET" check-surface "$W/s.off" 2>&1 >"$W/anitet.log" | tail -1; }
tg=$(for i in 1 2 3 4 5; do run_tetgen; done | best)
an=$(for i in 1 2 3 4 5; do run_anitet; done | best)
grep -i "intersect" "$W/tetgen.log" | head -2
grep "result" "$W/anitet.log"
echo "tetgen -d:            ${tg} s"
echo "anitet check-surface: ${an} s"
python3 -c "print('ratio tetgen/anitet: %.1fx' % ($tg / max($an, 0.01)))"
