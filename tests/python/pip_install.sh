#!/bin/sh
# pip_install.sh PYTHON PACKAGE_DIR WORK_DIR: `pip install` of bindings/python (offline, from a
# copy, so that the build leaves nothing in the source tree), then an import from the result.
set -eu
python=$1
package=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
cp -r "$package" "$work/src"
rm -rf "$work/src/anitet/__pycache__"
"$python" -m pip install --quiet --no-index --no-deps --no-build-isolation \
  --target "$work/site" "$work/src"
cd "$work"
PYTHONPATH="$work/site" PYTHONDONTWRITEBYTECODE=1 "$python" -c '
import os, sys, anitet
assert os.path.dirname(anitet.__file__) == os.path.join(sys.argv[1], "anitet"), anitet.__file__
s = anitet.Surface.from_arrays([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)],
                               [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)])
s.validate()
print("pip-installed anitet", anitet.version(), "from", anitet.__file__)
' "$work/site"
