#!/usr/bin/env bash
# mesh_bl_check.sh ANITET IN OUT H0 BL_TETS [mesh options...]
# The whole pipeline with a boundary layer (the options name the walls, h0, growth, layers):
#  - `anitet quality --strict`: the mesh is valid and boundary constrained, the volume kept;
#  - the report's BL figures, measured on the output after refinement and optimization: every
#    wall vertex's column complete, first heights within 10% of H0, no BL vertex moved;
#  - every wall vertex reaches all layers (columns_reaching), and the quality report has the BL
#    region's quality on its own (quality_by_region, BL_TETS tets in region 1);
#  - the output file itself: BL_TETS tetrahedra carry the BL region (1 for one body), and the
#    same mesh written by --also-write as SU2 has as many elements.
set -u
anitet=$1; in=$2; out=$3; h0=$4; bl_tets=$5; shift 5
rm -f "$out" "$out.run.json" "$out.su2"
"$anitet" mesh "$in" -o "$out" --also-write "$out.su2" --json "$@" > "$out.run.json" || { echo "FAIL: anitet mesh exited $?"; head -c 2000 "$out.run.json"; exit 1; }
num() { sed -n '/"boundary_layer"/,/}/p' "$out.run.json" | grep -o "\"$1\": [^,}]*" | head -1 | awk '{print $2}'; }
walls=$(num wall_vertices); full=$(num full_columns); hmin=$(num first_height_min); hmax=$(num first_height_max)
moved=$(num max_displacement); tets=$(num tets); layers=$(num layers)
echo "BL: $layers layers, $walls wall vertices, $full full columns, first height $hmin .. $hmax (h0 $h0), $tets BL tets, BL vertices moved by $moved"
awk -v w="$walls" -v f="$full" -v a="$hmin" -v b="$hmax" -v h="$h0" -v m="$moved" \
  'BEGIN { exit !(w > 0 && f == w && a >= 0.9 * h && b <= 1.1 * h && m == 0) }' \
  || { echo "FAIL: boundary-layer figures"; exit 1; }
reaching=$(tr -d ' \n' < "$out.run.json" | grep -o '"columns_reaching":\[[^]]*\]' | head -1)
[[ "$reaching" =~ [,[]$walls\]$ ]] || { echo "FAIL: columns_reaching $reaching: not all $walls wall vertices reach the last layer"; exit 1; }
region1=$(tr -d ' \n' < "$out.run.json" | grep -o '"region":1,"tets":[0-9]*' | head -1 | cut -d: -f3)
[[ "$region1" == "$bl_tets" ]] || { echo "FAIL: quality_by_region region 1 has '$region1' tets, expected $bl_tets"; exit 1; }
su2=$(sed -n 's/^NELEM= *//p' "$out.su2")
tets_all=$(awk '/^Tetrahedra/ { getline; print $1; exit }' "$out")
[[ -n "$su2" && "$su2" == "$tets_all" ]] || { echo "FAIL: --also-write SU2 has NELEM '$su2', the .mesh $tets_all tets"; exit 1; }
# Tetrahedra of the output with reference 1 (Medit: "a b c d ref").
in_file=$(awk '/^Tetrahedra/ { getline; n = $1; c = 0; for (i = 0; i < n; ++i) { getline; if ($5 == 1) ++c } print c; exit }' "$out")
[[ "$in_file" == "$bl_tets" && "$tets" == "$bl_tets" ]] || { echo "FAIL: $in_file tets of region 1 in $out, report $tets, expected $bl_tets"; exit 1; }
"$anitet" quality "$out" --surface "$in" --strict --json > "$out.json" || { echo "FAIL: quality --strict exited $?"; cat "$out.json"; exit 1; }
err=$(grep -o '"volume_rel_error": [^,]*' "$out.json" | head -1 | awk '{print $2}')
awk -v e="$err" 'BEGIN { exit !(e != "" && e + 0 < 1e-9) }' || { echo "FAIL: volume_rel_error $err"; exit 1; }
echo "PASS: valid, boundary constrained, volume_rel_error $err, $in_file BL tets, first heights within 10% of $h0"
