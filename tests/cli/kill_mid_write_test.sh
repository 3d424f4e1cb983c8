#!/usr/bin/env bash
# SIGKILL `kintsugi beautify` while it writes a large output: the output path must be
# absent or a whole model (the old one or the new one), and the input unchanged.
# Usage: kill_mid_write_test.sh path/to/kintsugi
set -u
K="$1"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $1"; }

# A clean model of ~8 MB: beautify repairs nothing and spends its time reading,
# detecting and writing.
"$K" generate family --faces 10000 --defect-rate 0 -o "$dir/in.json" >/dev/null 2>&1 || { echo "cannot generate"; exit 1; }
before=$(md5sum <"$dir/in.json")

# Starts beautify, waits for its temporary output to appear and grow past `min_bytes`,
# then kills it with SIGKILL. Prints "killed" or "finished".
kill_while_writing() {
  local min_bytes=$1
  "$K" beautify "$dir/in.json" -o "$dir/out.json" >/dev/null 2>&1 &
  local pid=$!
  while kill -0 "$pid" 2>/dev/null; do
    for f in "$dir"/.out.json.tmp-*; do
      if [ -e "$f" ] && [ "$(stat -c %s "$f" 2>/dev/null || echo 0)" -ge "$min_bytes" ]; then
        kill -KILL "$pid" 2>/dev/null
        wait "$pid" 2>/dev/null
        echo killed
        return
      fi
    done
    sleep 0.002
  done
  wait "$pid" 2>/dev/null
  echo finished
}

# 1. No output yet: killed at the first bytes, and again after about 2 MB.
for min in 1 2000000; do
  rm -f "$dir/out.json" "$dir"/.out.json.tmp-*
  how=$(kill_while_writing $min)
  echo "kill after $min bytes: $how"
  [ "$how" = killed ] && ok || bad "beautify finished before it could be killed (after $min bytes)"
  if [ -e "$dir/out.json" ]; then
    "$K" check "$dir/out.json" >/dev/null 2>&1 && ok || bad "a partial output was left at out.json (after $min bytes)"
  else ok; fi
  [ "$(md5sum <"$dir/in.json")" = "$before" ] && ok || bad "the input changed"
done

# 2. An output from before: killed mid-write, the old one stays whole.
"$K" generate box -o "$dir/out.json" >/dev/null 2>&1
old=$(md5sum <"$dir/out.json")
how=$(kill_while_writing 1000000)
echo "kill over an existing output: $how"
[ "$how" = killed ] && ok || bad "beautify finished before it could be killed (existing output)"
[ "$(md5sum <"$dir/out.json")" = "$old" ] && ok || bad "the previous output changed"
[ "$(md5sum <"$dir/in.json")" = "$before" ] && ok || bad "the input changed"

echo "kill mid-write: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
