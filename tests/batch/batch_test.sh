#!/usr/bin/env bash
# End-to-end checks of `kintsugi batch`. Usage: batch_test.sh path/to/kintsugi
# The bad children are made by the test-only switches KINTSUGI_TEST_HANG, _CRASH and
# _ALLOCATE (apps/batch_child.cpp): the child whose input file has that name hangs,
# aborts, or asks for 1 TiB of address space.
set -u
K="$1"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
# check DESCRIPTION -- command...: the command succeeds
check() {
  local what=$1
  shift 2
  if "$@" >"$dir/out" 2>&1; then ok; else bad "$what"; sed 's/^/    /' "$dir/out" | head -5; fi
}

# --- the input folder: good files in three formats and nested folders, and bad ones
in="$dir/in"
mkdir -p "$in/paper" "$in/cad/deep" "$in/bad"
for n in 6 7 9; do "$K" generate "paper-$n" -o "$in/paper/p$n.json" >/dev/null || bad "generate paper-$n"; done
"$K" generate box -o "$in/box.json" >/dev/null
"$K" generate paper-8 -o "$dir/p8.json" >/dev/null && "$K" convert "$dir/p8.json" "$in/cad/p8.step" >/dev/null || bad "p8.step"
"$K" convert "$in/box.json" "$in/cad/deep/box.brep" >/dev/null || bad "box.brep"
"$K" generate prism -o "$dir/prism.json" >/dev/null && "$K" convert "$dir/prism.json" "$in/cad/prism.STP" >/dev/null || bad "prism.STP"
echo "not a model" >"$in/cad/notes.txt"                       # not an input
head -c "$(($(wc -c <"$in/cad/p8.step") / 2))" "$in/cad/p8.step" >"$in/bad/truncated.step"
cat >"$in/bad/no_shape.step" <<'STEP'
ISO-10303-21;
HEADER;
FILE_DESCRIPTION((''),'2;1');
FILE_NAME('no_shape.step','2024-01-01T00:00:00',(''),(''),'','','');
FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));
ENDSEC;
DATA;
#1=CARTESIAN_POINT('',(0.,0.,0.));
#2=DIRECTION('',(0.,0.,1.));
ENDSEC;
END-ISO-10303-21;
STEP
cp "$in/box.json" "$in/bad/hang.json"
cp "$in/box.json" "$in/bad/crash.json"
cp "$in/box.json" "$in/bad/allocate.json"
good=7
total=$((good + 5))
export KINTSUGI_TEST_HANG=hang.json KINTSUGI_TEST_CRASH=crash.json KINTSUGI_TEST_ALLOCATE=allocate.json
# The hanging child costs one timeout per run; good files must finish well within it
# even on a loaded machine.
timeout=${KINTSUGI_TEST_TIMEOUT:-20}
opts=(--jobs 2 --timeout "$timeout" --max-memory 2G)

# status FILE INPUT: the status the manifest FILE records for INPUT
status() { python3 -c 'import json,sys
for l in open(sys.argv[1]):
    e = json.loads(l)
    if e["input"] == sys.argv[2]: print(e["status"])' "$1" "$2"; }
# canonical FILE: the manifest sorted by input, without the timings
canonical() { python3 -c 'import json,sys
es = [json.loads(l) for l in open(sys.argv[1])]
for e in es: e.pop("seconds")
print("\n".join(json.dumps(e, sort_keys=True) for e in sorted(es, key=lambda e: e["input"])))' "$1"; }

# --- a whole run
out1="$dir/out1"
"$K" batch "$in" "$out1" "${opts[@]}" >"$dir/run1.out" 2>"$dir/run1.err"
code=$?
[ "$code" -eq 3 ] && ok || bad "a run with failures exits 3, got $code"
m1="$out1/kintsugi-batch.jsonl"
[ "$(wc -l <"$m1")" -eq "$total" ] && ok || bad "manifest has $total lines: $(wc -l <"$m1")"
for f in paper/p6.json paper/p7.json paper/p9.json box.json cad/p8.step cad/deep/box.brep cad/prism.STP; do
  s=$(status "$m1" "$f")
  case "$s" in repaired | partly_repaired | unchanged) ok ;; *) bad "$f: status '$s'" ;; esac
  [ -s "$out1/$f" ] && ok || bad "$f: no output"
done
[ "$(status "$m1" paper/p6.json)" = repaired ] && ok || bad "paper-6 is repaired"
[ "$(status "$m1" box.json)" = unchanged ] && ok || bad "the box is unchanged"
check "the repaired paper-6 is valid" -- "$K" check "$out1/paper/p6.json"
check "the repaired STEP reads back" -- "$K" check "$out1/cad/p8.step"
for f in bad/truncated.step bad/no_shape.step bad/allocate.json; do
  [ "$(status "$m1" "$f")" = failed ] && ok || bad "$f: status '$(status "$m1" "$f")', expected failed"
done
[ "$(status "$m1" bad/hang.json)" = timeout ] && ok || bad "hang.json: status '$(status "$m1" bad/hang.json)'"
[ "$(status "$m1" bad/crash.json)" = crashed ] && ok || bad "crash.json: status '$(status "$m1" bad/crash.json)'"
# error FILE INPUT: the error the manifest FILE records for INPUT
error() { python3 -c 'import json,sys
for l in open(sys.argv[1]):
    e = json.loads(l)
    if e["input"] == sys.argv[2]: print(e["error"])' "$1" "$2"; }
error "$m1" bad/allocate.json | grep -q "out of memory" && ok || bad "allocate.json: the error says out of memory"
error "$m1" bad/crash.json | grep -q "SIGABRT" && ok || bad "crash.json: the error names the signal"
error "$m1" bad/truncated.step | grep -q "truncated.step: .*truncated" && ok || bad "truncated.step: the error names the file"
error "$m1" bad/no_shape.step | grep -q "no_shape.step: .*no shape" && ok || bad "no_shape.step: the reader's error"
[ ! -e "$out1/cad/notes.txt" ] && ! grep -q notes "$m1" && ok || bad "non-model files are left alone"
python3 - "$m1" <<'PY' && ok || bad "manifest lines have every field, problem counts by type"
import json, sys
keys = {"input", "output", "status", "problems_before", "problems_after", "tolerance", "seconds", "error"}
for l in open(sys.argv[1]):
    e = json.loads(l)
    assert set(e) == keys, e
    assert isinstance(e["seconds"], float)
    if e["status"] in ("failed", "timeout", "crashed"):
        assert e["output"] is None and e["problems_before"] is None and e["error"], e
    else:
        assert e["output"] == e["input"] and len(e["problems_before"]) == 11 and e["error"] is None, e
PY
grep -q "^total *$total" "$dir/run1.out" && ok || bad "summary table has the total"
grep -q "^timeout *1" "$dir/run1.out" && ok || bad "summary table counts the timeout"
python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); assert s["files"]==12 and s["status"]["failed"]==3 and len(s["failures"])==5, s' \
  "$out1/kintsugi-batch-summary.json" && ok || bad "summary JSON"
grep -q "\[$total/$total\]" "$dir/run1.err" && ok || bad "plain progress lines when stderr is not a terminal"
pgrep -f "batch-file $in" >/dev/null && bad "a child is left running" || ok

# --- usage errors exit 2
"$K" batch "$in" "$out1" >/dev/null 2>&1; [ $? -eq 2 ] && ok || bad "an existing manifest without --resume exits 2"
"$K" batch "$in" >/dev/null 2>&1; [ $? -eq 2 ] && ok || bad "no OUT_DIR exits 2"
"$K" batch "$in" "$dir/o" --tol 1 --tol-from-meta >/dev/null 2>&1; [ $? -eq 2 ] && ok || bad "--tol with --tol-from-meta exits 2"
"$K" batch "$in" "$in/out" >/dev/null 2>&1; [ $? -eq 2 ] && ok || bad "OUT_DIR inside IN_DIR exits 2"
"$K" batch "$in" "$dir/o" --max-memory lots >/dev/null 2>&1; [ $? -eq 2 ] && ok || bad "bad --max-memory exits 2"
"$K" batch "$dir/nowhere" "$dir/o" >/dev/null 2>&1; [ $? -eq 2 ] && ok || bad "missing IN_DIR exits 2"

# --- all good: exit 0; --resume over a finished run does nothing and says so
mkdir -p "$dir/goodin" && cp -r "$in/paper" "$in/cad" "$dir/goodin/"
"$K" batch "$dir/goodin" "$dir/goodout" --jobs 2 >/dev/null 2>&1; code=$?
[ "$code" -eq 0 ] && ok || bad "a run without failures exits 0, got $code"
"$K" batch "$dir/goodin" "$dir/goodout" --resume >"$dir/out" 2>&1; code=$?
[ "$code" -eq 0 ] && grep -q "6 file(s) already in" "$dir/out" && grep -q "^0 file(s)" "$dir/out" && ok || bad "resume of a finished run ($code)"

# --- on a terminal: a progress bar redrawn in place, no per-file lines
if command -v script >/dev/null; then
  script -qec "'$K' batch '$dir/goodin' '$dir/ttyout' --jobs 2" /dev/null >"$dir/tty.out" 2>&1
  grep -q $'\r\[#*\.*\] [0-9]*/6' "$dir/tty.out" && ok || bad "a progress bar on a terminal"
  grep -q "files/s" "$dir/tty.out" && ok || bad "the bar shows the rate"
  ! grep -q "\[1/6\] " "$dir/tty.out" && ok || bad "no per-file lines on a terminal"
fi

# --- shards: two shards cover the files once
"$K" batch "$in" "$dir/shards" --shard 0/2 --manifest "$dir/shards/a.jsonl" "${opts[@]}" >/dev/null 2>&1
"$K" batch "$in" "$dir/shards" --shard 1/2 --manifest "$dir/shards/b.jsonl" "${opts[@]}" >/dev/null 2>&1
cat "$dir/shards/a.jsonl" "$dir/shards/b.jsonl" >"$dir/shards/all.jsonl"
[ "$(canonical "$dir/shards/all.jsonl")" = "$(canonical "$m1")" ] && ok || bad "two shards give the manifest of one run"

# --- killed halfway, then --resume: finished files are not redone, same manifest
out2="$dir/out2"
m2="$out2/kintsugi-batch.jsonl"
"$K" batch "$in" "$out2" --jobs 1 --timeout "$timeout" --max-memory 2G >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1 300); do
  [ -f "$m2" ] && [ "$(wc -l <"$m2")" -ge 4 ] && break
  sleep 0.1
done
kill -KILL "$pid"
wait "$pid" 2>/dev/null
cp "$m2" "$dir/halfway.jsonl"
n_half=$(wc -l <"$dir/halfway.jsonl")
[ "$n_half" -ge 4 ] && [ "$n_half" -lt "$total" ] && ok || bad "the run was killed halfway ($n_half lines)"
"$K" batch "$in" "$out2" --resume "${opts[@]}" >/dev/null 2>"$dir/resume.err"
code=$?
[ "$code" -eq 3 ] && ok || bad "the resumed run exits 3, got $code"
grep -q "$n_half file(s) already in" "$dir/resume.err" && ok || bad "resume says what it skips"
[ "$(head -n "$n_half" "$m2")" = "$(cat "$dir/halfway.jsonl")" ] && ok || bad "resume keeps the finished lines"
for f in $(python3 -c 'import json,sys; [print(json.loads(l)["input"]) for l in open(sys.argv[1])]' "$dir/halfway.jsonl"); do
  ! grep -q "\[.*\] $f:" "$dir/resume.err" && ok || bad "resume redid $f"
done
[ "$(canonical "$m2")" = "$(canonical "$m1")" ] && ok || { bad "resumed manifest differs from the whole run's"; diff <(canonical "$m2") <(canonical "$m1") | head; }

# --- a torn last line (the parent killed mid-write) is cut and its file redone
out3="$dir/out3"
mkdir -p "$out3"
head -n 2 "$m1" >"$out3/kintsugi-batch.jsonl"
printf '{"input":"box.js' >>"$out3/kintsugi-batch.jsonl"
"$K" batch "$in" "$out3" --resume "${opts[@]}" >/dev/null 2>&1
[ "$(canonical "$out3/kintsugi-batch.jsonl")" = "$(canonical "$m1")" ] && ok || bad "a torn last line is redone"

echo "batch: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
