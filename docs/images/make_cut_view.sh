#!/usr/bin/env bash
# Redraws docs/images/fandisk-cut-view.png, the README's picture: a cut view of the HTML report
# of `anitet mesh fandisk.off`, rendered by headless Chromium (Debian `chromium`, which
# scripts/setup.sh leaves out: nothing else needs it).
# Usage: docs/images/make_cut_view.sh [ANITET [SURFACE]]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
anitet=${1:-$root/build/app/anitet}
surface=${2:-$root/../shared/data/surfaces/fandisk.off}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$anitet" mesh "$surface" -o "$work/f.mesh" --report "$work/f.html" > /dev/null
# The report's style, its colour legend and one of its three cut views (the plane through the
# middle of the box in y): the three together make a PNG of 500 KB.
/usr/bin/python3 - "$work/f.html" "$work/cut.html" <<'PY'
import sys
page = open(sys.argv[1], encoding="utf-8").read()
style = page[page.index("<style"):page.index("</style>") + len("</style>")]
start = page.index('<p class="legend">')
legend = page[start:page.index("</p>", start) + len("</p>")]
axis = page.index('data-axis="y"')
view = page[page.rindex("<figure", 0, axis):page.index("</figure>", axis) + len("</figure>")]
with open(sys.argv[2], "w", encoding="utf-8") as out:
    out.write('<!DOCTYPE html><html><head><meta charset="utf-8">' + style +
              "<style>body{margin:8px 10px}.legend{white-space:nowrap}"
              ".legend span{padding:2px 3px}</style></head><body>" + legend + view +
              "</body></html>")
PY
chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=456,392 \
    --screenshot="$work/cut.png" "file://$work/cut.html" 2> /dev/null
cp "$work/cut.png" "$root/docs/images/fandisk-cut-view.png"
ls -l "$root/docs/images/fandisk-cut-view.png"
