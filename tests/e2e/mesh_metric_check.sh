#!/usr/bin/env bash
# mesh_metric_check.sh ANITET IN OUTSTEM MODE [ARG] [-- mesh options...]
# Two runs of `anitet mesh IN`, the reference (default sizing) and one with a metric option; the
# second's tet count must move as the option says, and its mesh pass `anitet quality --strict`.
#   hmax H   reference, then --hmax H: at least 2x the tets (H well below the default sizes)
#   size S   reference, then --size S (S < 1): at least 2x the tets
#   sol      reference with --write-metric REF.sol, then --metric REF.sol --background REF.mesh
#            (the same field through a per-vertex .sol): tet count within 20% of the reference
#   solb     the same as sol in the binary formats: REF.meshb, REF.solb, the mesh written .meshb
#   vdb      reference with --write-sizing REF.vdb, then --metric REF.vdb (the same grid read
#            back): tet count within 5% of the reference
set -u
anitet=$1; in=$2; stem=$3; mode=$4; shift 4
arg=""
if [[ $mode == hmax || $mode == size ]]; then arg=$1; shift; fi
[[ ${1:-} == "--" ]] && shift
ref="$stem.ref.mesh"; out="$stem.mesh"
[[ $mode == solb ]] && { ref="$stem.ref.meshb"; out="$stem.meshb"; }
rm -f "$ref" "$out" "$stem.ref.sol" "$stem.ref.solb" "$stem.ref.vdb"
tets() { grep -Eo '[0-9]+ tets in' <<<"$1" | head -1 | awk '{print $1}'; }
case $mode in
  hmax|size) ref_opts=(); opts=("--$mode" "$arg") ;;
  sol|solb) ref_opts=(--write-metric "$stem.ref.$mode"); opts=(--metric "$stem.ref.$mode" --background "$ref") ;;
  vdb) ref_opts=(--write-sizing "$stem.ref.vdb"); opts=(--metric "$stem.ref.vdb") ;;
  *) echo "unknown mode $mode"; exit 2 ;;
esac
a=$("$anitet" mesh "$in" -o "$ref" "${ref_opts[@]}" "$@" 2>&1) || { echo "FAIL: reference run: $a"; exit 1; }
b=$("$anitet" mesh "$in" -o "$out" "${opts[@]}" "$@" 2>&1) || { echo "FAIL: run with ${opts[*]}: $b"; exit 1; }
ta=$(tets "$a"); tb=$(tets "$b")
echo "reference: $ta tets; with ${opts[*]}: $tb tets"
case $mode in
  hmax|size) awk -v a="$ta" -v b="$tb" 'BEGIN { exit !(a > 0 && b >= 2 * a) }' ;;
  sol|solb) awk -v a="$ta" -v b="$tb" 'BEGIN { r = b / a; exit !(a > 0 && r > 0.8 && r < 1.2) }' ;;
  vdb) awk -v a="$ta" -v b="$tb" 'BEGIN { r = b / a; exit !(a > 0 && r > 0.95 && r < 1.05) }' ;;
esac || { echo "FAIL: tet counts $ta -> $tb do not move as $mode says"; exit 1; }
"$anitet" quality "$out" --surface "$in" --strict > /dev/null || { echo "FAIL: quality --strict on $out"; exit 1; }
echo "PASS"
