#!/usr/bin/env bash
# Usage: package_test.sh BUILD_DIR SOURCE_DIR KINTSUGI_EXE CXX
# Installs the build into a temporary prefix, configures and builds examples/consumer
# against it (find_package(kintsugi), kintsugi::kintsugi), and runs it.
set -euo pipefail
build=$1 src=$2 K=$3 cxx=$4
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cmake --install "$build" --prefix "$dir/prefix" >"$dir/install.log"
test -f "$dir/prefix/lib/cmake/kintsugi/kintsugiConfig.cmake" || test -f "$dir"/prefix/lib/*/cmake/kintsugi/kintsugiConfig.cmake
test -f "$dir/prefix/include/kintsugi/apps/api.h"
test -x "$dir/prefix/bin/kintsugi"
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S "$src/examples/consumer" -B "$dir/consumer" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER="$cxx" "${launcher[@]}" -DCMAKE_PREFIX_PATH="$dir/prefix" >"$dir/configure.log" ||
  { cat "$dir/configure.log"; exit 1; }
cmake --build "$dir/consumer" -j 2 >"$dir/build.log" || { tail -n 40 "$dir/build.log"; exit 1; }
"$K" generate paper-6 -o "$dir/p6.json" >/dev/null
"$dir/consumer/heal" "$dir/p6.json" "$dir/p6-healed.json" | tee "$dir/heal.out"
grep -q "repaired" "$dir/heal.out"
grep -q "a built box has 6 faces" "$dir/heal.out"
"$dir/prefix/bin/kintsugi" check "$dir/p6-healed.json"
# The library's result is the CLI's: same output bytes.
"$K" beautify "$dir/p6.json" -o "$dir/p6-cli.json" >/dev/null 2>&1
cmp "$dir/p6-healed.json" "$dir/p6-cli.json"
echo "package: installed, consumer built and ran"
