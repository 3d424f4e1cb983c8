#!/usr/bin/env bash
# Sorts a fuzz run's artifacts by where they fail: replays each crash-, timeout- and oom-
# file under the target (one at a time, bounded) and prints one line per artifact with its
# kind, the sanitizer's or libFuzzer's error line and the top frames that are not the
# sanitizer runtime's or the C library's. The verdict is "opencascade" when the top such
# frame is in an OpenCASCADE library (libTK*: its own bug, which the CLI's bounded child
# reports as an error naming the file), otherwise "ours". Then a count per verdict and
# error/top frame.
#
#   scripts/fuzz_sort_artifacts.sh TARGET ARTIFACT_DIR [SECONDS_PER_REPLAY]
#
# TARGET is a fuzz_<name> built in build-fuzz (docs/fuzzing.md). Exit status: 0 when no
# artifact is ours, 1 otherwise.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
target=${1:?usage: fuzz_sort_artifacts.sh TARGET ARTIFACT_DIR [SECONDS]}
dir=${2:?usage: fuzz_sort_artifacts.sh TARGET ARTIFACT_DIR [SECONDS]}
limit=${3:-120}
bin=$root/build-fuzz/bin/$target
[ -x "$bin" ] || { echo "fuzz_sort_artifacts: $bin is not built" >&2; exit 2; }
export LSAN_OPTIONS="suppressions=$root/.ci/lsan-suppressions.txt:print_suppressions=0"
export ASAN_OPTIONS="${ASAN_OPTIONS:-}:symbolize=1"
ours=0
summary=$(mktemp)
for f in "$dir"/crash-* "$dir"/timeout-* "$dir"/oom-*; do
  [ -e "$f" ] || continue
  kind=$(basename "$f" | cut -d- -f1)
  out=$(timeout $((limit + 30)) "$bin" -runs=1 -timeout="$limit" -rss_limit_mb=4096 "$f" 2>&1)
  error=$(printf '%s\n' "$out" | grep -m1 -E 'ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer)|runtime error:' |
    sed -E 's/^==[0-9]+==//; s/ \(pc 0x[0-9a-f]+.*//; s/ on address 0x[0-9a-f]+.*//; s/ on unknown address 0x[0-9a-f]+/ on unknown address/')
  [ -n "$error" ] || error="no error on replay (exit ${PIPESTATUS[0]:-?})"
  frames=$(printf '%s\n' "$out" | grep -E '^ +#[0-9]+ 0x' |
    grep -v -E 'libclang_rt|compiler-rt|sanitizer_common|/asan/|libc\.so|libstdc\+\+|__libc_|libFuzzer|fuzzer::|__sanitizer_' | head -4 |
    sed -E 's/^ +#[0-9]+ 0x[0-9a-f]+ in //; s/ \/.*//; s/\(.*//' | cut -c1-70 | paste -sd'<' -)
  top=$(printf '%s\n' "$out" | grep -E '^ +#[0-9]+ 0x' |
    grep -v -E 'libclang_rt|compiler-rt|sanitizer_common|/asan/|libc\.so|libstdc\+\+|__libc_|libFuzzer|fuzzer::|__sanitizer_' | head -1)
  # Our first frame, for the record: the call of ours that reached OpenCASCADE.
  mine=$(printf '%s\n' "$out" | grep -E '^ +#[0-9]+ 0x.* in kintsugi::' | head -1 | sed -E 's/^ +#[0-9]+ 0x[0-9a-f]+ in //; s/\(anonymous namespace\)/anon/g; s/\(.*//' | cut -c1-80)
  verdict=ours
  case "$top" in *libTK*|*opencascade*|*" in Standard_"*|*" in BRep"*|*" in Step"*|*" in STEP"*|*" in Geom"*|*" in IGES"*|*" in TopoDS"*|*" in BSpl"*|*" in Extrema"*) verdict=opencascade ;; esac
  [ "$verdict" = ours ] && ours=$((ours + 1))
  printf '%s %s %s: %s | %s | from %s\n' "$verdict" "$kind" "$(basename "$f")" "$error" "${frames:-no frames}" "${mine:-none of ours}"
  printf '%s %s: %s | %s\n' "$verdict" "$kind" "$error" "$(printf '%s' "$frames" | cut -d'<' -f1)" >>"$summary"
done
echo "--- by verdict, kind, error and top frame:"
sort "$summary" | uniq -c | sort -rn
rm -f "$summary"
[ "$ours" -eq 0 ]
