#!/usr/bin/env bash
# report_check.sh ANITET IN OUTDIR [mesh options...]
# Meshes IN (with `mesh --report`: the page with the run's stage timers, checked too, as is
# `anitet report MESH`'s default name), writes the HTML quality report of the mesh (`anitet quality --report`), checks its
# structure with report_check.py (self-contained; histogram bars = bins, adding up to the tet /
# angle / edge counts; cut views with > 0 polygons), and, when chromium is installed, renders it
# headless to OUTDIR/report.png and checks the screenshot too. A second report with --cut-max 50
# checks the cap on the cut views, a third with --metric (the mesher's --write-metric) the edge
# lengths in the metric. Without chromium the screenshot
# part is skipped and said so (the structure is still checked).
set -u
anitet=$1; in=$2; dir=$3; shift 3
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$dir"
mesh=$dir/mesh.mesh; html=$dir/report.html; png=$dir/report.png
rm -f "$mesh" "$html" "$png"
rm -f "$dir/run.html" "$dir/mesh.html"
"$anitet" mesh "$in" -o "$mesh" -q --write-metric "$dir/mesh.sol" --report "$dir/run.html" "$@" || { echo "FAIL: anitet mesh exited $?"; exit 1; }
# `mesh --report`: the same page, with the run's stage timers.
/usr/bin/python3 "$here/report_check.py" "$dir/run.html" > "$dir/run.log" || { cat "$dir/run.log"; exit 1; }
grep -q "Meshing run" "$dir/run.html" && grep -q "stage layers" "$dir/run.html" && grep -q "stage optimize" "$dir/run.html" ||
  { echo "FAIL: mesh --report has no 'Meshing run' table with the stage timers"; exit 1; }
# `anitet report MESH` writes MESHSTEM.html by default.
"$anitet" report "$mesh" --surface "$in" > /dev/null || { echo "FAIL: anitet report exited $?"; exit 1; }
[ -s "$dir/mesh.html" ] || { echo "FAIL: anitet report wrote no $dir/mesh.html"; exit 1; }
"$anitet" quality "$mesh" --surface "$in" --report "$html" || { echo "FAIL: anitet quality --report exited $?"; exit 1; }
[ -s "$html" ] || { echo "FAIL: no report written"; exit 1; }
# The cap on the cut views: at most 50 cross-sections each, the caption says so.
"$anitet" report "$mesh" -o "$dir/capped.html" --cut 0.4,0.5,0.6 --cut-max 50 > /dev/null ||
  { echo "FAIL: anitet report --cut-max exited $?"; exit 1; }
/usr/bin/python3 "$here/report_check.py" "$dir/capped.html" --cut-max 50 > "$dir/capped.log" ||
  { cat "$dir/capped.log"; exit 1; }
# Edge lengths in the mesher's own metric: their mean near 1 (the refinement aims at [1/sqrt2, sqrt2]).
"$anitet" quality "$mesh" --report "$dir/metric.html" --metric "$dir/mesh.sol" > /dev/null ||
  { echo "FAIL: anitet quality --metric exited $?"; exit 1; }
/usr/bin/python3 "$here/report_check.py" "$dir/metric.html" --metric-mean 0.8,1.25 > "$dir/metric.log" ||
  { cat "$dir/metric.log"; exit 1; }
browser=""
for b in /usr/bin/chromium /usr/bin/chromium-browser; do [ -x "$b" ] && { browser=$b; break; }; done
if [ -z "$browser" ]; then
  echo "SKIP screenshot: chromium is not installed (apt-get install chromium); checking the HTML only"
  exec /usr/bin/python3 "$here/report_check.py" "$html"
fi
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
HOME=$profile timeout 120 "$browser" --headless --no-sandbox --disable-gpu --hide-scrollbars \
  --user-data-dir="$profile" --screenshot="$png" --window-size=1400,2000 "file://$html" > "$dir/chromium.log" 2>&1
[ -s "$png" ] || { echo "FAIL: chromium wrote no screenshot"; cat "$dir/chromium.log"; exit 1; }
exec /usr/bin/python3 "$here/report_check.py" "$html" "$png"
