"""scripts/audit_shards.sh and scripts/audit_merge.py: a Table 1 run in shards sums to the
table its shards make, a finished shard is not run again, and a shard made by another
build is refused."""
import json
import os
import pathlib
import shutil
import subprocess

ROOT = pathlib.Path(__file__).resolve().parents[2]


def run(*args):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, cwd=ROOT)


def test_shards_sum_to_their_cells(exe, tmp_path):
    runs = tmp_path / "t1"
    p = run(ROOT / "scripts/audit_shards.sh", exe, runs, 41, 2, 3, 2)
    assert p.returncode == 0, p.stderr
    shards = [json.loads((runs / f"{s}.json").read_text()) for s in (41, 42)]
    m = run("python3", ROOT / "scripts/audit_merge.py", runs, "--json")
    assert m.returncode == 0, m.stderr
    merged = json.loads(m.stdout)
    assert merged["shards"] == ["41", "42"]
    cells = {(c["created"], c["fixing"]): c for c in merged["cells"]}
    assert len(cells) == 121
    for c in shards[0]["cells"]:
        other = next(d for d in shards[1]["cells"] if d["created"] == c["created"] and d["fixing"] == c["fixing"])
        got = cells[(c["created"], c["fixing"])]
        assert got["count"] == c["count"] + other["count"]
        assert got["threshold_flips"] == c["threshold_flips"] + other["threshold_flips"]
        assert merged["passes"][c["fixing"]]["trials"] == c["trials"] + other["trials"]
    # Finished shards are kept: the same command runs nothing again.
    before = (runs / "41.json").stat().st_mtime_ns
    p = run(ROOT / "scripts/audit_shards.sh", exe, runs, 41, 2, 3, 2)
    assert p.returncode == 0, p.stderr
    assert (runs / "41.json").stat().st_mtime_ns == before
    # Another binary is refused: its shards would not be one run.
    other = tmp_path / "kintsugi-copy"
    shutil.copy(exe, other)
    with open(other, "ab") as f:
        f.write(b"\0")
    os.chmod(other, 0o755)
    p = run(ROOT / "scripts/audit_shards.sh", other, runs, 43, 1, 3)
    assert p.returncode == 2
    assert "another build" in p.stderr


def test_merge_of_nothing_is_an_error(tmp_path):
    p = run("python3", ROOT / "scripts/audit_merge.py", tmp_path)
    assert p.returncode == 2
    assert "no shard" in p.stderr
