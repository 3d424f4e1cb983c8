#!/usr/bin/env python3
"""Sum the shards of a Table 1 run (scripts/audit_shards.sh) into one table.

    scripts/audit_merge.py DIR [--json]

Each DIR/<seed>.json is one `kintsugi audit --json` run; the shards are independent samples,
so the cells' counts, threshold flips, judged and skipped trials add up. Prints the 11x11
table (created type by pass, the paper's Yes/No beside each count) as Markdown, then the
findings of every shard (counterexamples first). Exit 1 if any shard found a
counterexample, 2 if DIR holds no shard."""
import glob, json, os, sys

SHORT = {"face_gap": "fgap", "edge_gap": "egap", "multi_face_gap": "mgap", "pinched_face": "pinch",
         "small_face_chain": "sfch", "sliver_face": "sliv", "short_edge_chain": "sech",
         "same_geometry_faces": "same", "small_face": "smf", "mergeable_edges": "merg", "short_edge": "sed"}


def main():
    if len(sys.argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    d = sys.argv[1]
    shards = sorted(glob.glob(os.path.join(d, "*.json")), key=lambda p: os.path.basename(p))
    runs = []
    for p in shards:
        try:
            with open(p) as f:
                runs.append((os.path.basename(p)[:-5], json.load(f)))
        except (OSError, ValueError) as e:
            print(f"audit_merge: {p}: not a complete shard ({e})", file=sys.stderr)
            return 2
    if not runs:
        print(f"audit_merge: no shard in {d}", file=sys.stderr)
        return 2
    order = []
    cells = {}
    per_pass = {}
    for _, j in runs:
        for c in j["cells"]:
            key = (c["created"], c["fixing"])
            if c["fixing"] not in order:
                order.append(c["fixing"])
            m = cells.setdefault(key, {"count": 0, "threshold_flips": 0, "paper": c["paper"], "if_found": c["if_found"]})
            m["count"] += c["count"]
            m["threshold_flips"] += c.get("threshold_flips", 0)
            pp = per_pass.setdefault(c["fixing"], {"trials": 0, "skipped": 0, "unsolved": 0, "seen": set()})
        for col in order:
            c = next(c for c in j["cells"] if c["fixing"] == col)
            per_pass[col]["trials"] += c["trials"]
            per_pass[col]["skipped"] += c["skipped"]
            per_pass[col]["unsolved"] += c.get("skipped_unsolved", 0)  # since 2026-12-05
    seconds = sum(j.get("seconds", 0) for _, j in runs)
    per_shard = {j.get("trials_per_pass") for _, j in runs}
    findings = {k: [(s, f) for s, j in runs for f in j.get(k, [])]
                for k in ("counterexamples", "threshold_flips", "disagreements", "witnesses")}
    if "--json" in sys.argv:
        print(json.dumps({"shards": [s for s, _ in runs], "trials_per_pass_per_shard": sorted(per_shard),
                          "seconds": seconds,
                          "cells": [dict(created=r, fixing=c, **v) for (r, c), v in cells.items()],
                          "passes": {c: {"trials": v["trials"], "skipped": v["skipped"], "unsolved": v["unsolved"]}
                                     for c, v in per_pass.items()},
                          **{k: [dict(shard=s, **f) for s, f in v] for k, v in findings.items()}}, indent=1))
    else:
        print(f"{len(runs)} shards (seeds {runs[0][0]}..{runs[-1][0]}), {sorted(per_shard)} trials per pass each, "
              f"{seconds / 3600:.2f} CPU-hours\n")
        print("| created \\ fixing | " + " | ".join(SHORT[c] for c in order) + " |")
        print("|---|" + "---:|" * len(order))
        for row in order:
            out = []
            for col in order:
                m = cells[(row, col)]
                mark = ""
                if m["count"]:
                    if m["if_found"] == "counterexample":
                        mark = "**\\***" if m["count"] > m["threshold_flips"] else "~"
                    elif m["if_found"] == "disagreement":
                        mark = "!"
                flips = f" ({m['threshold_flips']} flips)" if m["threshold_flips"] else ""
                out.append(f"{m['count']}{mark}{flips} {m['paper'][0]}")
            print(f"| {SHORT[row]} | " + " | ".join(out) + " |")
        print("| trials judged | " + " | ".join(str(per_pass[c]["trials"]) for c in order) + " |")
        print("| skipped | " + " | ".join(str(per_pass[c]["skipped"]) for c in order) + " |")
        if any(v["unsolved"] for v in per_pass.values()):
            print("| of which unsolved | " + " | ".join(str(per_pass[c]["unsolved"]) for c in order) + " |")
        for k in ("counterexamples", "threshold_flips", "disagreements"):
            for s, f in findings[k]:
                print(f"\n{k[:-1]} (shard {s}): {f['recipe']['pass']} created {f['created']}: {json.dumps(f['recipe'])}")
        reached = sorted({(f["created"], f["recipe"]["pass"]) for _, f in findings["witnesses"]})
        print(f"\nwitnessed Yes cells: {len(reached)}")
    return 1 if findings["counterexamples"] else 0


if __name__ == "__main__":
    sys.exit(main())
