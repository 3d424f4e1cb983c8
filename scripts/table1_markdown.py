#!/usr/bin/env python3
"""Renders `kintsugi audit --json` output as the Markdown table of docs/table1-audit.md.

  python3 scripts/table1_markdown.py AUDIT.json [MORE.json ...]

Several files (one `--pass P` run each, same --trials and --seed) are merged column by
column: each pass's trials depend only on the seed and the pass, so the merged table is
the one a single run of all passes prints. Cell: count and the paper's Y/N; "✗" marks a
counterexample to the order, "!" a disagreement with the paper. Below the table: the
paper's "Yes" cells no trial reached, and the findings.
"""
import json
import sys

ORDER = ["face_gap", "edge_gap", "multi_face_gap", "pinched_face", "small_face_chain", "sliver_face",
         "short_edge_chain", "same_geometry_faces", "small_face", "mergeable_edges", "short_edge"]
SHORT = ["fgap", "egap", "mgap", "pinch", "sfch", "sliv", "sech", "same", "smf", "merg", "sed"]


def main(paths):
    cell, seconds, findings = {}, 0.0, {"counterexamples": [], "disagreements": [], "witnesses": []}
    for path in paths:
        with open(path) as f:
            j = json.load(f)
        ran = {c["fixing"] for c in j["cells"] if c["trials"] or c["skipped"]}
        for c in j["cells"]:
            if c["fixing"] in ran or (c["created"], c["fixing"]) not in cell:
                cell[(c["created"], c["fixing"])] = c
        seconds += j.get("seconds", 0.0)
        for k in findings:
            findings[k] += j.get(k, [])
    print("| created ↓ / fixing → | " + " | ".join(SHORT) + " |")
    print("| --- | " + " | ".join(["---:"] * 11) + " |")
    for r, rs in zip(ORDER, SHORT):
        row = []
        for c in ORDER:
            x = cell[(r, c)]
            mark = ""
            if x["count"] > 0:
                mark = {"counterexample": " ✗", "disagreement": " !"}.get(x["if_found"], "")
            row.append(f'{x["count"]} {x["paper"][0]}{mark}')
        print(f"| {rs} | " + " | ".join(row) + " |")
    print("| trials judged | " + " | ".join(str(cell[(ORDER[0], c)]["trials"]) for c in ORDER) + " |")
    print("| skipped | " + " | ".join(str(cell[(ORDER[0], c)]["skipped"]) for c in ORDER) + " |")
    print()
    missing = [(r, c) for c in ORDER for r in ORDER if cell[(r, c)]["paper"] == "Yes" and cell[(r, c)]["count"] == 0]
    print(f"Paper's \"Yes\" cells no trial reached ({len(missing)}):")
    for r, c in missing:
        print(f"- fixing {c} → {r}")
    print()
    print(", ".join(f"{k}: {len(v)}" for k, v in findings.items()) + f"; {seconds:.0f} s of audit time in all")
    for k in ("counterexamples", "disagreements"):
        for f in findings[k]:
            print(f"- {k[:-1]}: {f['recipe'].get('pass')} created {f['created']}: {json.dumps(f['recipe'])}")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
