#!/usr/bin/env bash
# Replays fuzz artifacts of fuzz_occt_import (crash-, timeout-, oom- files) through the
# command line, the way a user meets such a file: `kintsugi check FILE`, which reads STEP
# and BREP in a child process bounded in time and memory (apps/bounded_read.h). What must
# hold for every file: exit 0, 1 or 2 (never a signal), and on exit 2 a message naming
# the file. Prints the count per exit code; exit status 1 if any file broke that.
#
#   scripts/replay_through_cli.sh ARTIFACT...      (KINTSUGI binary: build/bin/kintsugi)
#
# Each file is copied to a temporary folder under a .step name when it starts with
# "ISO-10303-21", else .brep (the fuzz target reads it the same way); the read is
# bounded to 30 s (KINTSUGI_READ_TIMEOUT) so that OpenCASCADE's endless loops end soon.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
K=${KINTSUGI:-$root/build/bin/kintsugi}
[ -x "$K" ] || { echo "replay_through_cli: $K is not built" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
declare -A codes
bad=0
for f in "$@"; do
  b=$(basename "$f")
  if head -c 12 "$f" | grep -q "ISO-10303-21"; then ext=step; else ext=brep; fi
  cp "$f" "$tmp/$b.$ext"
  KINTSUGI_READ_TIMEOUT=30 timeout 120 "$K" check "$tmp/$b.$ext" >"$tmp/out" 2>"$tmp/err"
  c=$?
  codes[$c]=$((${codes[$c]:-0} + 1))
  if [ "$c" -gt 2 ]; then
    bad=1
    echo "$b: exit $c: $(head -c 300 "$tmp/err")"
  elif [ "$c" = 2 ] && ! grep -qF "$tmp/$b.$ext" "$tmp/err"; then
    bad=1
    echo "$b: exit 2 without naming the file: $(head -c 300 "$tmp/err")"
  fi
  rm -f "$tmp/$b.$ext"
done
for c in "${!codes[@]}"; do echo "exit $c: ${codes[$c]} file(s)"; done
exit $bad
