#!/bin/sh
# The documented Table 1 run in shards: shard k is `kintsugi audit --seed FIRST+k --trials N
# --json --save`, each an independent sample (its own seed), so a run of 10^6 trials per
# pass can be made over several sittings and several machines and summed
# (scripts/audit_merge.py). A shard whose JSON is already in DIR is skipped: run the same
# command again to go on where it stopped. All shards of one run must come from one build
# (the script records the binary's checksum, and the commit checked out where it runs,
# beside the shards, and refuses another binary).
#   scripts/audit_shards.sh KINTSUGI DIR FIRST_SEED SHARDS TRIALS_PER_PASS [PARALLEL]
# e.g. the session-23 run: scripts/audit_shards.sh build/bin/kintsugi runs/t1 3001 20 50000 2
set -eu
if [ $# -lt 5 ]; then sed -n '2,10p' "$0" >&2; exit 2; fi
bin=$1 dir=$2 first=$3 shards=$4 trials=$5 parallel=${6:-1}
mkdir -p "$dir"
sum=$(sha256sum "$bin" | cut -d' ' -f1)
if [ -f "$dir/binary.sha256" ]; then
  if [ "$(cat "$dir/binary.sha256")" != "$sum" ]; then
    echo "audit_shards: $dir was made by another build of kintsugi (binary.sha256 differs)" >&2
    exit 2
  fi
else
  echo "$sum" > "$dir/binary.sha256"
  git rev-parse HEAD > "$dir/commit.txt" 2>/dev/null || echo unknown > "$dir/commit.txt"
fi
run_shard() {
  seed=$1
  [ -s "$dir/$seed.json" ] && return 0
  start=$(date +%s)
  # Exit 1 (a counterexample) still leaves a complete table: keep it, the merge reports it.
  "$bin" audit --trials "$trials" --seed "$seed" --json --save "$dir/found-$seed" > "$dir/$seed.json.part" 2> "$dir/$seed.err" || [ $? -eq 1 ]
  mv "$dir/$seed.json.part" "$dir/$seed.json"
  echo "shard $seed: $(( $(date +%s) - start )) s" >&2
}
seed=$first
last=$((first + shards - 1))
while [ "$seed" -le "$last" ]; do
  n=0
  while [ "$n" -lt "$parallel" ] && [ "$seed" -le "$last" ]; do
    run_shard "$seed" &
    seed=$((seed + 1)) n=$((n + 1))
  done
  wait
done
