"""kintsugi: repair the topology of reverse-engineered B-rep solid models.

The functions return plain Python objects: the same documents as the CLI's
``check --json``, ``detect --json`` and ``beautify --report``, as dicts.

    import kintsugi
    m = kintsugi.read("part.step")          # .json, .step/.stp, .brep
    kintsugi.detect(m)["counts"]            # problems by type
    report = kintsugi.beautify(m)           # repairs m in place
    kintsugi.write(m, "part-fixed.step")

Whole folders: ``python -m kintsugi batch IN OUT`` (the CLI's ``kintsugi batch``) or,
on a Dask cluster, ``python -m kintsugi.dask IN OUT [--scheduler ADDRESS]``.
"""
import os
import shutil

from ._kintsugi import Error, Model, beautify, beautify_file, check, detect, read, write
from ._kintsugi import batch as _batch  # noqa: F401  (used by kintsugi.dask)

__all__ = ["Error", "Model", "read", "write", "check", "detect", "beautify", "beautify_file", "executable"]


def executable():
    """The kintsugi program the batch runners start: $KINTSUGI_EXE, else the one this
    package was built with, else `kintsugi` on PATH."""
    exe = os.environ.get("KINTSUGI_EXE")
    if exe:
        return exe
    try:
        from ._build import KINTSUGI_EXE

        if os.path.exists(KINTSUGI_EXE):
            return KINTSUGI_EXE
    except ImportError:
        pass
    found = shutil.which("kintsugi")
    if not found:
        raise Error("cannot find the kintsugi program: set KINTSUGI_EXE")
    return found
