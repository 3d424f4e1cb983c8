#!/bin/sh
# The scan-parts score with many more cases than the ctest default: OpenCASCADE-built
# designer parts, one to three injected scan defects each, a random rigid motion, a STEP
# round trip, beautify, judged against the designer's part (tests/occt/scan_parts_test.cpp).
# Prints the table per problem type and every failed case.
#   scripts/scan_parts_score.sh [cases (default 240)] [seed base (default 1)] [build dir (default build)]
set -eu
cases=${1:-240}
seed=${2:-1}
build=${3:-build}
cmake --build "$build" --target scan_parts_tests >/dev/null
KINTSUGI_SCAN_CASES=$cases KINTSUGI_SCAN_SEED=$seed "$build/bin/scan_parts_tests" --gtest_filter=ScanParts.ScoreTable
