#!/usr/bin/env bash
# The built-in example: generate every built-in solid and check it.
set -euo pipefail
cd "$(dirname "$0")/.."
out=$(mktemp -d)
for name in box prism pyramid cylinder cone sphere torus grid; do
  ./build/bin/kintsugi generate "$name" -o "$out/$name.json"
  ./build/bin/kintsugi check "$out/$name.json"
done
echo "models are in $out"
