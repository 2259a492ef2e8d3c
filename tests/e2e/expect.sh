#!/usr/bin/env bash
# expect.sh EXPECT REGEX [--absent FILE] -- COMMAND...
# Runs COMMAND; passes when its exit status matches EXPECT (a number: exactly that status; "fail":
# non-zero but not a crash or a signal), its combined output matches the extended REGEX (empty: anything), and
# FILE (if given) does not exist afterwards.
set -u
expect=$1; regex=$2; shift 2
absent=""
if [[ $1 == "--absent" ]]; then absent=$2; shift 2; rm -f "$absent"; fi
[[ $1 == "--" ]] && shift
out=$("$@" 2>&1); rc=$?
printf '%s\n' "$out" | head -c 4000
if [[ $expect =~ ^[0-9]+$ && $rc != "$expect" ]]; then echo "FAIL: exit status $rc, expected $expect"; exit 1; fi
if [[ $expect == fail ]] && (( rc == 0 || rc >= 124 )); then
  echo "FAIL: exit status $rc, expected a clean failure (1..123)"; exit 1
fi
if [[ -n $regex ]] && ! grep -Eq -- "$regex" <<<"$out"; then echo "FAIL: output does not match /$regex/"; exit 1; fi
if [[ -n $absent && -e $absent ]]; then echo "FAIL: $absent was written"; exit 1; fi
echo "PASS (exit $rc)"
