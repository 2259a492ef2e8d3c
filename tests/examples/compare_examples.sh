#!/bin/sh
# compare_examples.sh WORK_DIR "EXTENSIONS" NAME=COMMAND...: runs each example COMMAND with the
# output prefix WORK_DIR/NAME, then checks that every one printed the same text and wrote the same
# files WORK_DIR/NAME.EXT, for each EXT of EXTENSIONS ("mesh sol"), as the first: the same mesh
# (counts, reports, coordinates, metric, patch names) bit for bit.
set -eu
work=$1
extensions=$2
shift 2
rm -rf "$work"
mkdir -p "$work"
first=""
for spec in "$@"; do
  name=${spec%%=*}
  command=${spec#*=}
  # shellcheck disable=SC2086 # the command is a program and its arguments
  if ! $command "$work/$name" >"$work/$name.txt"; then
    echo "example $name failed: $command" >&2
    exit 1
  fi
  if [ -z "$first" ]; then
    first=$name
    grep -q '^mesh: [0-9]* vertices, [0-9]* tets' "$work/$name.txt" || {
      echo "example $name printed no mesh counts" >&2
      exit 1
    }
    continue
  fi
  for ext in txt $extensions; do
    if ! cmp -s "$work/$first.$ext" "$work/$name.$ext"; then
      echo "examples $first and $name differ in their .$ext output:" >&2
      diff "$work/$first.$ext" "$work/$name.$ext" | head -20 >&2 || true
      exit 1
    fi
  done
  echo "$name: same output as $first"
done
head -2 "$work/$first.txt"
