"""The Dask runner and `python -m kintsugi batch` give the manifest `kintsugi batch` gives."""
import os
import shutil
import subprocess
import sys

import pytest

from conftest import canonical_manifest
from kintsugi import dask as kdask

# The hanging child costs one timeout per run; good files finish well within it even
# on a loaded machine.
TIMEOUT = "10"


@pytest.fixture(scope="module")
def folder(tmp_path_factory, exe):
    """Good files (native and STEP), a truncated STEP, a hanging and a crashing child
    (the test-only switches, which the children of either runner read)."""
    root = tmp_path_factory.mktemp("batch")
    src = root / "in"
    (src / "sub").mkdir(parents=True)
    run = lambda *a: subprocess.run([exe, *map(str, a)], check=True, capture_output=True)  # noqa: E731
    for n in (6, 7, 9):
        run("generate", f"paper-{n}", "-o", src / f"p{n}.json")
    run("generate", "box", "-o", src / "box.json")
    run("generate", "paper-8", "-o", root / "p8.json")
    run("convert", root / "p8.json", src / "sub" / "p8.step")
    data = (src / "sub" / "p8.step").read_bytes()
    (src / "sub" / "truncated.step").write_bytes(data[: len(data) // 2])
    shutil.copy(src / "box.json", src / "sub" / "hang.json")
    shutil.copy(src / "box.json", src / "sub" / "crash.json")
    return root


@pytest.fixture(autouse=True)
def switches(monkeypatch):
    monkeypatch.setenv("KINTSUGI_TEST_HANG", "hang.json")
    monkeypatch.setenv("KINTSUGI_TEST_CRASH", "crash.json")


@pytest.fixture(scope="module")
def cli_manifest(folder, exe):
    out = folder / "out-cli"
    env = dict(os.environ, KINTSUGI_TEST_HANG="hang.json", KINTSUGI_TEST_CRASH="crash.json")
    p = subprocess.run([exe, "batch", folder / "in", out, "--jobs", "2", "--timeout", TIMEOUT], env=env,
                       capture_output=True, text=True)
    assert p.returncode == 3, p.stderr
    return out / "kintsugi-batch.jsonl"


def test_dask_local_cluster_gives_the_cli_manifest(folder, cli_manifest, capsys):
    out = folder / "out-dask"
    code = kdask.run(folder / "in", out, workers=2, timeout=float(TIMEOUT))
    assert code == 3
    got = canonical_manifest(out / "kintsugi-batch.jsonl")
    assert got == canonical_manifest(cli_manifest)
    statuses = {e["input"]: e["status"] for e in got}
    assert statuses["sub/hang.json"] == "timeout"
    assert statuses["sub/crash.json"] == "crashed"
    assert statuses["sub/truncated.step"] == "failed"
    assert statuses["p6.json"] == "repaired"
    assert (out / "sub" / "p8.step").exists() and (out / "kintsugi-batch-summary.json").exists()
    assert "total" in capsys.readouterr().out
    # the repaired files are the CLI's, byte for byte
    assert (out / "p6.json").read_bytes() == (cli_manifest.parent / "p6.json").read_bytes()


def test_dask_resumes_a_cli_run(folder, cli_manifest):
    out = folder / "out-resume"
    out.mkdir()
    lines = cli_manifest.read_text().splitlines(keepends=True)
    (out / "kintsugi-batch.jsonl").write_text("".join(lines[:3]))
    code = kdask.run(folder / "in", out, workers=2, timeout=float(TIMEOUT), resume=True)
    assert code == 3
    text = (out / "kintsugi-batch.jsonl").read_text()
    assert text.startswith("".join(lines[:3]))
    assert canonical_manifest(out / "kintsugi-batch.jsonl") == canonical_manifest(cli_manifest)


def test_dask_usage_errors(folder):
    with pytest.raises(kdask.UsageError, match="exists"):
        kdask.run(folder / "in", folder / "out-dask", workers=1)
    with pytest.raises(kdask.UsageError, match="inside"):
        kdask.run(folder / "in", folder / "in" / "o", workers=1)
    assert kdask.main([str(folder / "in"), str(folder / "o2"), "--max-memory", "lots"]) == 2


def test_python_m_kintsugi_batch_is_the_cli(folder, cli_manifest):
    out = folder / "out-pym"
    env = dict(os.environ, KINTSUGI_TEST_HANG="hang.json", KINTSUGI_TEST_CRASH="crash.json")
    p = subprocess.run([sys.executable, "-m", "kintsugi", "batch", folder / "in", out, "--jobs", "2", "--timeout",
                        TIMEOUT], env=env, capture_output=True, text=True)
    assert p.returncode == 3, p.stderr
    assert canonical_manifest(out / "kintsugi-batch.jsonl") == canonical_manifest(cli_manifest)
    assert subprocess.run([sys.executable, "-m", "kintsugi", "frobnicate"], capture_output=True).returncode == 2
