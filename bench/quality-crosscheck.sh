#!/usr/bin/env bash
# Cross-checks `anitet quality` against the independent checker meshcheck.py on meshes made by
# TetGen (-pq1.414Y, boundary kept) and Gmsh (-3 on a double-precision Medit surface) from shared
# surfaces. Pass criteria per mesh: same tet count, same boundary verdict, radius-ratio and
# mean-ratio means within 1e-6. Not run by CI (needs tetgen, gmsh, python3-numpy, python3-meshio).
#
# usage: bench/quality-crosscheck.sh [ANITET_BINARY] [SURFACE.off ...]
#   ANITET_BINARY defaults to build-quality/app/anitet beside this script's repository.
set -euo pipefail

here=$(cd "$(dirname "$0")/.." && pwd)
anitet=${1:-$here/build-quality/app/anitet}
shift || true
surfaces_dir=${ANITET_SURFACES_DIR:-$here/../shared/data/surfaces}
meshcheck=${MESHCHECK:-$here/../shared/tools/meshcheck.py}
py=/usr/bin/python3  # Debian's python: it has numpy and meshio
if [ $# -gt 0 ]; then
  surfaces=("$@")
else
  surfaces=("$surfaces_dir/decimated-knight.off" "$surfaces_dir/kitten.off" "$surfaces_dir/fandisk.off")
fi
for tool in tetgen gmsh "$anitet" "$py"; do
  command -v "$tool" > /dev/null || { echo "missing: $tool" >&2; exit 2; }
done

work=$(mktemp -d /tmp/anitet-crosscheck.XXXXXX)
trap 'rm -rf "$work"' EXIT

# OFF -> Medit .mesh surface with every coordinate written to round-trip (repr).
off_to_medit() {
  "$py" - "$1" "$2" <<'EOF'
import sys
rows = [l.split('#')[0].split() for l in open(sys.argv[1])]
rows = [r for r in rows if r]
head = rows[0][1:] or rows[1]
first = 1 if rows[0][1:] else 2
nv, nf = int(head[0]), int(head[1])
pts = [tuple(float(x) for x in r[:3]) for r in rows[first:first + nv]]
tris = []
for r in rows[first + nv:first + nv + nf]:
    v = list(map(int, r))
    tris += [(v[1], v[1 + i], v[2 + i]) for i in range(1, v[0] - 1)]
with open(sys.argv[2], 'w') as f:
    f.write('MeshVersionFormatted 2\nDimension 3\nVertices\n%d\n' % len(pts))
    f.writelines('%r %r %r 0\n' % p for p in pts)
    f.write('Triangles\n%d\n' % len(tris))
    f.writelines('%d %d %d 1\n' % (a + 1, b + 1, c + 1) for a, b, c in tris)
    f.write('End\n')
EOF
}

results=$work/results.jsonl
: > "$results"
for surf in "${surfaces[@]}"; do
  name=$(basename "$surf" .off)
  dir=$work/$name
  mkdir -p "$dir"
  cp "$surf" "$dir/$name.off"
  # TetGen: -p PLC, -q1.414 quality, -Y no Steiner points on the boundary.
  (cd "$dir" && tetgen -pq1.414Y "$name.off" > tetgen.log 2>&1)
  # Gmsh: the surface mesh merged as a discrete surface, the volume inside it.
  off_to_medit "$dir/$name.off" "$dir/${name}_surf.mesh"
  printf 'Merge "%s_surf.mesh";\nSurface Loop(1) = Surface{:};\nVolume(1) = {1};\n' "$name" > "$dir/$name.geo"
  (cd "$dir" && gmsh -3 "$name.geo" -o "${name}_gmsh.msh" -format msh41 > gmsh.log 2>&1)

  for pair in "tetgen:$dir/$name.1.ele" "gmsh:$dir/${name}_gmsh.msh"; do
    mesher=${pair%%:*}
    mesh=${pair#*:}
    start=$(date +%s.%N)
    "$anitet" quality "$mesh" --surface "$dir/$name.off" --json > "$dir/$mesher.anitet.json"
    mid=$(date +%s.%N)
    "$py" "$meshcheck" "$mesh" --surface "$dir/$name.off" > "$dir/$mesher.meshcheck.json"
    end=$(date +%s.%N)
    "$py" - "$name" "$mesher" "$dir/$mesher.anitet.json" "$dir/$mesher.meshcheck.json" \
      "$start" "$mid" "$end" >> "$results" <<'EOF'
import json, sys
name, mesher, a_path, m_path, t0, t1, t2 = sys.argv[1:]
a, m = json.load(open(a_path)), json.load(open(m_path))
row = {'surface': name, 'mesher': mesher, 'tets': [a['tets'], m['tets']],
       'bc': [a['boundary_constrained'], m['boundary_constrained']],
       'valid': [a['valid'], m['valid']],
       'match': a['vertex_match']['mode'],
       'on_surface': a['vertices_on_input_surface'],
       'd_rr': abs(a['quality']['radius_ratio']['mean'] - m['quality']['radius_ratio']['mean']),
       'd_mr': abs(a['quality']['mean_ratio']['mean'] - m['quality']['mean_ratio']['mean']),
       'd_rrmin': abs(a['quality']['radius_ratio']['min'] - m['quality']['radius_ratio']['min']),
       'd_dih': abs(a['quality']['min_dihedral_deg'] - m['quality']['min_dihedral_deg']),
       'rr_mean': a['quality']['radius_ratio']['mean'], 'mr_mean': a['quality']['mean_ratio']['mean'],
       'secs': [float(t1) - float(t0), float(t2) - float(t1)]}
same_counts = all(a[k] == m[k] for k in ('tets', 'boundary_faces', 'nonpositive_tets',
                  'faces_shared_by_more_than_two', 'steiner_points_on_boundary',
                  'input_triangles_missing', 'boundary_faces_not_in_input'))
row['ok'] = (same_counts and row['bc'][0] == row['bc'][1] and row['valid'][0] == row['valid'][1]
             and row['d_rr'] < 1e-6 and row['d_mr'] < 1e-6)
print(json.dumps(row))
EOF
  done
done

"$py" - "$results" <<'EOF'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
print('| surface | mesher | tets | valid | boundary constrained (anitet/meshcheck) | vertex match | rr mean | mr mean '
      '| |d rr mean| | |d mr mean| | |d rr min| | |d min dihedral| deg | anitet s | meshcheck s | ok |')
print('|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|')
for r in rows:
    print('| %s | %s | %d | %s | %s/%s | %s | %.6f | %.6f | %.1e | %.1e | %.1e | %.1e | %.2f | %.2f | %s |' % (
        r['surface'], r['mesher'], r['tets'][0], r['valid'][0], r['bc'][0], r['bc'][1], r['match'],
        r['rr_mean'], r['mr_mean'], r['d_rr'], r['d_mr'], r['d_rrmin'], r['d_dih'], r['secs'][0], r['secs'][1],
        'yes' if r['ok'] else 'NO'))
bad = [r for r in rows if not r['ok']]
print('%d passed, %d failed' % (len(rows) - len(bad), len(bad)))
sys.exit(1 if bad else 0)
EOF
