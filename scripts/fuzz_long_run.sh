#!/usr/bin/env bash
# A long fuzz run on record: one target, two jobs, its corpus kept, a summary at the end.
#
#   scripts/fuzz_long_run.sh TARGET SECONDS [WORKDIR] [extra libFuzzer flags...]
#
# TARGET is a fuzz_<name> built in build-fuzz (docs/fuzzing.md, "Long runs"). The run
# starts from fuzz/corpus/<name> (copied; the repository's seeds are not written to) and
# keeps what it finds in WORKDIR/corpus (default /tmp/kintsugi-fuzz/<name>); artifacts
# (crash-, timeout-, oom-, slow-unit-) go to WORKDIR/artifacts. Two jobs run side by side
# (-jobs=2 -workers=2), each for SECONDS. At the end it prints per job the executions,
# coverage and features of its last status line, and the run's wall and CPU time — the
# figures docs/fuzzing.md records. Exit status: 0 when no artifact other than slow units
# was written, 1 otherwise.
#
# fuzz_occt_import and fuzz_from_occt meet OpenCASCADE's own crashes within minutes; run
# them in fork mode instead (pass: -fork=2 -ignore_crashes=1, and no -jobs is added then).
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
target=${1:?usage: fuzz_long_run.sh TARGET SECONDS [WORKDIR] [flags...]}
seconds=${2:?usage: fuzz_long_run.sh TARGET SECONDS [WORKDIR] [flags...]}
name=${target#fuzz_}
shift 2
work=/tmp/kintsugi-fuzz/$name
if [ $# -gt 0 ] && [ "${1#-}" = "$1" ]; then work=$1; shift; fi  # a WORKDIR, not a flag
bin=$root/build-fuzz/bin/$target
[ -x "$bin" ] || { echo "fuzz_long_run: $bin is not built (docs/fuzzing.md, \"Long runs\")" >&2; exit 2; }

mkdir -p "$work/corpus" "$work/artifacts"
work=$(cd "$work" && pwd)  # absolute: a target may change its working folder (fuzz_cli_args does)
[ -d "$root/fuzz/corpus/$name" ] && cp -rn "$root/fuzz/corpus/$name/." "$work/corpus/"
parallel=(-jobs=2 -workers=2)
for flag in "$@"; do case "$flag" in -fork=*) parallel=() ;; esac; done

export LSAN_OPTIONS="suppressions=$root/.ci/lsan-suppressions.txt:print_suppressions=0"
cd "$work" || exit 2
before=$(ls corpus | wc -l)
start=$(date -u +%FT%TZ)
/usr/bin/time -f "%e %U %S" -o time.txt "$bin" -max_total_time="$seconds" -rss_limit_mb=4096 -timeout=60 \
  -artifact_prefix="$work/artifacts/" "${parallel[@]}" "$@" "$work/corpus" >run.log 2>&1
# (time writes "Command exited with non-zero status N" first when the fuzzer found something)
read -r wall user sys < <(tail -n 1 time.txt)
{
  echo "$target: $start, ${seconds} s per job, wall ${wall} s, CPU ${user} s user + ${sys} s system"
  echo "corpus: $before inputs at the start, $(ls corpus | wc -l) at the end ($work/corpus)"
  logs=(fuzz-*.log)  # one per job; without jobs (fork mode) the run's own log
  [ -e "${logs[0]}" ] || logs=(run.log)
  for log in "${logs[@]}"; do
    last=$(grep -E '^#[0-9]+' "$log" | tail -n 1)
    [ -n "$last" ] && echo "$log: $last"
  done
  found=$(ls artifacts | grep -v '^slow-unit-' || true)
  if [ -n "$found" ]; then echo "findings:"; echo "$found" | sed 's/^/  /'; else echo "findings: none"; fi
  slow=$(ls artifacts | grep -c '^slow-unit-' || true)
  echo "slow units kept (not findings): $slow"
} | tee summary.txt
! ls artifacts | grep -qv '^slow-unit-'
