#!/usr/bin/env bash
# End-to-end checks of the kintsugi program. Usage: cli_test.sh path/to/kintsugi
set -u
K="$1"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
pass=0
fail=0

# expect CODE DESCRIPTION -- command...   (stdout+stderr kept in $dir/out)
expect() {
  local code=$1 what=$2
  shift 3
  "$@" >"$dir/out" 2>&1
  local got=$?
  if [ "$got" -eq "$code" ]; then pass=$((pass + 1)); else
    fail=$((fail + 1)); echo "FAIL: $what: exit $got, expected $code"; sed 's/^/    /' "$dir/out" | head -5
  fi
}
# contains TEXT DESCRIPTION: the last command's output contains TEXT
contains() {
  if grep -qF -- "$1" "$dir/out"; then pass=$((pass + 1)); else
    fail=$((fail + 1)); echo "FAIL: $2: output lacks '$1'"; sed 's/^/    /' "$dir/out" | head -5
  fi
}

expect 0 "top-level help" -- "$K" --help
contains "generate" "help lists verbs"
expect 2 "no verb" -- "$K"
expect 2 "unknown verb" -- "$K" frobnicate
contains "unknown verb" "unknown verb is named"
for verb in generate check measure detect; do
  expect 0 "$verb --help" -- "$K" "$verb" --help
  contains "usage: kintsugi $verb" "$verb --help shows usage"
done
expect 0 "generate --list" -- "$K" generate --list
for m in box prism pyramid cylinder cone sphere torus grid; do contains "$m" "--list names $m"; done
for n in 1 2 3 4 5 6 7 8 9 10; do
  expect 0 "generate paper-$n" -- "$K" generate "paper-$n" -o "$dir/paper$n.json"
  expect 0 "check paper-$n" -- "$K" check "$dir/paper$n.json"
  expect 0 "detect paper-$n" -- "$K" detect "$dir/paper$n.json"
  contains "from meta.tolerance" "detect paper-$n takes meta.tolerance and says so"
  expect 0 "generate paper-$n --clean" -- "$K" generate "paper-$n" --clean -o "$dir/paper${n}c.json"
  expect 0 "detect paper-$n --clean" -- "$K" detect "$dir/paper${n}c.json"
  contains ": 0 problem(s)" "the clean paper-$n has no problems"
done
expect 2 "family over a million faces is refused" -- "$K" generate family --faces 2000000 -o "$dir/big.json"
contains "from 10 to 1000000" "the refusal says the range"
for m in box prism pyramid cylinder cone sphere torus grid; do
  expect 0 "generate $m" -- "$K" generate "$m" -o "$dir/$m.json"
  expect 0 "check $m" -- "$K" check "$dir/$m.json"
  contains "valid" "check $m says valid"
done
expect 2 "generate unknown model" -- "$K" generate dodecahedron -o "$dir/x.json"
expect 2 "generate bad option" -- "$K" generate box --sx -1 -o "$dir/x.json"
contains "positive" "bad size is explained"
expect 2 "generate unknown option" -- "$K" generate box --colour red -o "$dir/x.json"
contains "unknown option --colour" "unknown option is named"
expect 2 "generate without -o" -- "$K" generate box
expect 2 "generate to unknown extension" -- "$K" generate box -o "$dir/x.obj"
expect 2 "generate non-numeric" -- "$K" generate box --sx abc -o "$dir/x.json"
contains "--sx" "bad number names the option"

# check --json document shape
expect 0 "check --json" -- "$K" check "$dir/torus.json" --json
for key in '"valid": true' '"counts"' '"border_cycles"' '"violations"' '"max_deviation"'; do contains "$key" "check --json has $key"; done

# unreadable input
expect 2 "check missing file" -- "$K" check "$dir/nope.json"
printf '{"format": "kintsugi-brep", "version": 1, "vertices": [' >"$dir/trunc.json"
expect 2 "check truncated file" -- "$K" check "$dir/trunc.json"
printf '' >"$dir/empty.json"
expect 2 "check empty file" -- "$K" check "$dir/empty.json"

# an invalid body: valid JSON, references fine, Euler-Poincare broken -> refused on read (exit 2)
python3 - "$dir/box.json" "$dir/bad.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
d["shells"][0]["genus"] = 1
json.dump(d, open(sys.argv[2], "w"))
PY
expect 2 "check topologically invalid file" -- "$K" check "$dir/bad.json"
contains "euler_poincare" "the broken invariant is named"

# geometry off by far more than the precision -> invalid (exit 1), the vertex named
python3 - "$dir/box.json" "$dir/moved.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
d["vertices"][0]["point"][2] += 0.01
json.dump(d, open(sys.argv[2], "w"))
PY
expect 1 "check geometrically inconsistent file" -- "$K" check "$dir/moved.json"
contains "v0" "the moved vertex is named"

# measure and detect
expect 0 "measure --json" -- "$K" measure "$dir/cylinder.json" --json
for key in '"area"' '"faces"' '"edges"' '"bbox_diagonal"' '"length"'; do contains "$key" "measure --json has $key"; done
expect 0 "detect --json" -- "$K" detect "$dir/box.json" --tol 0.01 --json
for t in face_gap edge_gap multi_face_gap pinched_face small_face_chain sliver_face short_edge_chain same_geometry_faces small_face mergeable_edges short_edge; do
  contains "\"$t\": 0" "detect counts $t"
done
expect 2 "detect bad tolerance" -- "$K" detect "$dir/box.json" --tol -3
expect 2 "detect zero tolerance" -- "$K" detect "$dir/box.json" --tol 0
expect 2 "detect nan tolerance" -- "$K" detect "$dir/box.json" --tol nan
expect 0 "detect default tolerance" -- "$K" detect "$dir/box.json"
contains "tolerance" "the default tolerance is said"

# generate never writes over an input; outputs are complete files
cp "$dir/box.json" "$dir/keep.json"
before=$(md5sum <"$dir/keep.json")
expect 0 "generate overwrites an ordinary output" -- "$K" generate cone -o "$dir/box.json"
expect 0 "check the replaced output" -- "$K" check "$dir/box.json"
[ "$(md5sum <"$dir/keep.json")" = "$before" ] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL: keep.json changed"; }
ls "$dir"/.*tmp* >/dev/null 2>&1 && { fail=$((fail + 1)); echo "FAIL: temporary files left behind"; } || pass=$((pass + 1))

# convert: JSON to JSON always; STEP and BREP when this build has OpenCASCADE
expect 0 "convert json to json" -- "$K" convert "$dir/torus.json" "$dir/torus2.json"
expect 0 "check the converted file" -- "$K" check "$dir/torus2.json"
expect 2 "convert onto its input" -- "$K" convert "$dir/torus.json" "$dir/torus.json"
contains "input" "refusing to overwrite the input is explained"
if "$K" convert --help | grep -q "STEP"; then
  for ext in step brep; do
    expect 0 "convert to $ext" -- "$K" convert "$dir/cylinder.json" "$dir/cylinder.$ext"
    expect 0 "check $ext with OpenCASCADE's verdict" -- "$K" check "$dir/cylinder.$ext" --occt
    contains "OpenCASCADE" "check --occt reports OpenCASCADE's verdict"
  done
  printf 'ISO-10303-21;\nHEADER;' >"$dir/trunc.step"
  expect 2 "convert a truncated STEP file" -- "$K" convert "$dir/trunc.step" "$dir/x.json"
fi

echo "cli: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
