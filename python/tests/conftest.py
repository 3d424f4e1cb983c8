"""Fixtures for the Python package's tests. Run from the repository root after a build:
    PYTHONPATH=build/python python3 -m pytest -q python/tests
"""
import json
import subprocess

import pytest

import kintsugi


@pytest.fixture(scope="session")
def exe():
    return kintsugi.executable()


@pytest.fixture(scope="session")
def cli(exe):
    """cli(*args) runs the kintsugi program; returns (exit code, stdout, stderr)."""

    def run(*args, env=None):
        p = subprocess.run([exe, *map(str, args)], capture_output=True, text=True, env=env)
        return p.returncode, p.stdout, p.stderr

    return run


def without_timings(doc):
    """A report or manifest entry without its wall-clock fields, which differ run to run."""
    doc = json.loads(json.dumps(doc))
    if isinstance(doc, dict):
        doc.pop("seconds", None)
    return doc


def canonical_manifest(path):
    """A manifest's entries sorted by input, without timings."""
    with open(path) as f:
        return sorted((without_timings(json.loads(line)) for line in f), key=lambda e: e["input"])
