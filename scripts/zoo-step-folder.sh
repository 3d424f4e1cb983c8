#!/usr/bin/env bash
# Writes a folder of zoo models as STEP files, for benchmarking `kintsugi batch` and the
# Dask runner (docs/benchmarks.md): the ten paper objects, then scalable-family models
# (defect rate 0.1) of 100 to 1000 faces with different seeds, N files in all.
# Usage: scripts/zoo-step-folder.sh OUT_DIR [N (default 200)] [kintsugi program]
set -euo pipefail
out=$1
n=${2:-200}
K=${3:-$(dirname "$0")/../build/bin/kintsugi}
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
i=0
for p in 1 2 3 4 5 6 7 8 9 10; do
  [ "$i" -lt "$n" ] || break
  "$K" generate "paper-$p" -o "$tmp/m.json" >/dev/null
  "$K" convert "$tmp/m.json" "$out/paper-$p.step" >/dev/null
  i=$((i + 1))
done
seed=1
while [ "$i" -lt "$n" ]; do
  faces=$((100 + (seed * 97) % 900))
  "$K" generate family --faces "$faces" --seed "$seed" -o "$tmp/m.json" >/dev/null
  "$K" convert "$tmp/m.json" "$out/family-$faces-s$seed.step" >/dev/null
  i=$((i + 1))
  seed=$((seed + 1))
done
echo "$i STEP files in $out"
