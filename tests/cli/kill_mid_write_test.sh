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
# then kills it with SIGKILL. Prints "killed" or "finished". The watching is Python's
# (a stat every half millisecond, no process per look): a shell loop forking `stat` was
# too slow to see the write on a loaded machine (ctest -j2), and beautify finished first.
kill_while_writing() {
  python3 - "$K" "$dir" "$1" <<'PY'
import glob, os, signal, subprocess, sys, time
k, d, min_bytes = sys.argv[1], sys.argv[2], int(sys.argv[3])
p = subprocess.Popen([k, "beautify", d + "/in.json", "-o", d + "/out.json"],
                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
while p.poll() is None:
    for f in glob.glob(d + "/.out.json.tmp-*"):
        try:
            size = os.stat(f).st_size
        except FileNotFoundError:
            continue
        if size >= min_bytes:
            p.send_signal(signal.SIGKILL)
            p.wait()
            print("killed")
            sys.exit(0)
    time.sleep(0.0005)
print("finished")
PY
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
