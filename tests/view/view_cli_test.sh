#!/usr/bin/env bash
# kintsugi view and beautify --html/--png: usage, bad input, and the message when no
# browser is installed (needs no browser). Usage: view_cli_test.sh path/to/kintsugi
set -u
K="$1"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
pass=0
fail=0
expect() {
  local code=$1 what=$2
  shift 3
  "$@" >"$dir/out" 2>&1
  local got=$?
  if [ "$got" -eq "$code" ]; then pass=$((pass + 1)); else
    fail=$((fail + 1)); echo "FAIL: $what: exit $got, expected $code"; sed 's/^/    /' "$dir/out" | head -5
  fi
}
contains() {
  if grep -qF -- "$1" "$dir/out"; then pass=$((pass + 1)); else
    fail=$((fail + 1)); echo "FAIL: $2: output lacks '$1'"; sed 's/^/    /' "$dir/out" | head -5
  fi
}
ok() { if eval "$1"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $2"; fi; }

"$K" generate paper-6 -o "$dir/p6.json" >/dev/null 2>&1
expect 0 "view --help" -- "$K" view --help
contains "usage: kintsugi view" "view --help shows usage"
contains "Chromium" "view --help says --png needs Chromium"
expect 0 "beautify --help" -- "$K" beautify --help
contains "--html PAGE.html" "beautify --help lists --html"
contains "Chromium" "beautify --help says --png needs Chromium"
expect 2 "view without an output" -- "$K" view "$dir/p6.json"
contains "expected MODEL and -o" "the missing output is explained"
expect 2 "view of a missing file" -- "$K" view "$dir/nothing.json" -o "$dir/x.html"
expect 2 "view with a bad chordal tolerance" -- "$K" view "$dir/p6.json" --chordal -1 -o "$dir/x.html"
contains "--chordal" "the bad option is named"
expect 2 "view onto its input" -- "$K" view "$dir/p6.json" -o "$dir/p6.json"
contains "input" "refusing to overwrite the input is explained"
expect 0 "view writes a page" -- "$K" view "$dir/p6.json" -o "$dir/p6.html"
ok "head -c 15 '$dir/p6.html' | grep -q '<!DOCTYPE html>'" "the page is HTML"
ok "grep -q 'REVISION=\"111\"' '$dir/p6.html'" "three.js r111 is inlined"
expect 2 "view --png without a browser" -- env KINTSUGI_CHROMIUM=/nonexistent/chromium "$K" view "$dir/p6.json" --png "$dir/p6.png"
contains "needs Chromium" "the missing browser is named"
ok "[ ! -e '$dir/p6.png' ]" "no picture is left behind"
expect 2 "beautify --png without a browser" -- env KINTSUGI_CHROMIUM=/nonexistent/chromium "$K" beautify "$dir/p6.json" -o "$dir/f.json" --png "$dir/f.png"
contains "needs Chromium" "beautify names the missing browser"
expect 0 "beautify --html" -- "$K" beautify "$dir/p6.json" -o "$dir/f.json" --html "$dir/f.html"
ok "grep -q '\"name\":\"after\"' '$dir/f.html'" "the beautify page has the model after"

echo "view cli: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
