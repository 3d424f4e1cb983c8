"""Run `kintsugi batch` on a Dask distributed cluster.

    python -m kintsugi.dask IN_DIR OUT_DIR [--scheduler ADDRESS] [--workers N]
        [--tol T | --tol-from-meta] [--timeout S] [--max-memory M] [--resume] [--manifest FILE]

Each file is one task; the task runs the file in a child process (`kintsugi batch-file`)
with the timeout and memory limit, exactly as `kintsugi batch` does (the same C++ code,
through kintsugi._kintsugi.batch), so a crash in one file never kills a worker, and the
manifest lines are the same, so a run can be resumed by either runner. The client
writes the manifest as results arrive, one flushed line each.

Without --scheduler a LocalCluster runs on this machine (N worker processes, one thread
each, listening on 127.0.0.1 only). With --scheduler tcp://HOST:8786 the tasks go to an
existing cluster: there IN_DIR and OUT_DIR must be the same paths on every worker (a
shared file system) and the kintsugi program must be at the same path ($KINTSUGI_EXE).
"""
import argparse
import json
import logging
import os
import sys
import tempfile
import time

import kintsugi
from kintsugi import _batch


def run_file(input, exe, in_dir, out_dir, tol, timeout, max_memory):
    """The task: one file in its own child process; returns its manifest line."""
    from kintsugi import _batch as batch

    return batch.run_job(exe, in_dir, out_dir, input, tol, timeout, max_memory)


class UsageError(Exception):
    pass


def run(in_dir, out_dir, *, scheduler=None, workers=2, tol=None, timeout=600.0, max_memory=0, resume=False,
        manifest=None, out=None, err=None):
    """Beautify every model under in_dir into out_dir on a Dask cluster. Returns the exit
    code of `kintsugi batch`: 0, or 3 when some file failed, timed out or crashed.
    Raises UsageError where the CLI exits with 2."""
    from distributed import Client, LocalCluster, as_completed

    out = out or sys.stdout
    err = err or sys.stderr
    in_dir, out_dir = os.path.abspath(in_dir), os.path.abspath(out_dir)
    if not os.path.isdir(in_dir):
        raise UsageError(f"{in_dir}: not a folder")
    rel = os.path.relpath(out_dir, in_dir)
    if rel == "." or not rel.startswith(".."):
        raise UsageError("OUT_DIR must not be IN_DIR or inside it (outputs would be read as inputs)")
    os.makedirs(out_dir, exist_ok=True)
    manifest = os.path.abspath(manifest or os.path.join(out_dir, "kintsugi-batch.jsonl"))
    if os.path.exists(manifest) and not resume:
        raise UsageError(f"{manifest} exists: --resume to go on with it, or remove it")
    try:
        files = _batch.find_inputs(in_dir)
        recorded = _batch.recorded_inputs(manifest, True)
    except kintsugi.Error as e:
        raise UsageError(str(e))
    todo = [f for f in files if f not in recorded]
    if recorded:
        err.write(f"kintsugi.dask: {len(files) - len(todo)} file(s) already in {manifest}\n")
    exe = kintsugi.executable()

    cluster = None
    scratch = None
    start = time.monotonic()
    if scheduler:
        client = Client(scheduler)
    else:
        scratch = tempfile.TemporaryDirectory(prefix="kintsugi-dask-")
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                               dashboard_address=None, local_directory=scratch.name, silence_logs=logging.ERROR)
        client = Client(cluster)
    try:
        jobs = sum(client.nthreads().values())
        futures = client.map(run_file, todo, exe=exe, in_dir=in_dir, out_dir=out_dir, tol=tol, timeout=timeout,
                             max_memory=max_memory, pure=False)
        done = failed = 0
        with open(manifest, "a", encoding="utf-8") as f:
            for future in as_completed(futures):
                line = future.result()
                f.write(line + "\n")
                f.flush()
                done += 1
                entry = json.loads(line)
                status = entry["status"]
                failed += status in ("failed", "timeout", "crashed")
                message = f"kintsugi.dask: [{done}/{len(todo)}] {entry['input']}: {status}"
                if entry.get("error"):
                    message += f": {entry['error']}"
                err.write(message + "\n")
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
        if scratch is not None:
            scratch.cleanup()
    table, _summary, code = _batch.finish_run(manifest, time.monotonic() - start, jobs, len(todo))
    out.write(table)
    return code


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m kintsugi.dask", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("in_dir")
    p.add_argument("out_dir")
    p.add_argument("--scheduler", metavar="ADDRESS", help="an existing scheduler (tcp://host:8786); default: a LocalCluster")
    p.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes (default 2)")
    tols = p.add_mutually_exclusive_group()
    tols.add_argument("--tol", type=float, help="one length tolerance for every file")
    tols.add_argument("--tol-from-meta", action="store_true", help="each file's meta.tolerance (the default)")
    p.add_argument("--timeout", type=float, default=600.0, help="seconds per file (default 600; 0: none)")
    p.add_argument("--max-memory", metavar="M", help="address space per child, e.g. 2G")
    p.add_argument("--resume", action="store_true", help="skip the files the manifest already records")
    p.add_argument("--manifest", metavar="FILE", help="default OUT_DIR/kintsugi-batch.jsonl")
    a = p.parse_args(argv)  # exits with 2 on bad usage, as the CLI does
    try:
        if a.tol is not None and not a.tol > 0:
            raise UsageError("--tol must be a positive number")
        if a.timeout < 0:
            raise UsageError("--timeout must be 0 or more seconds")
        if a.workers < 1:
            raise UsageError("--workers must be at least 1")
        max_memory = 0
        if a.max_memory:
            try:
                max_memory = _batch.parse_size(a.max_memory)
            except ValueError as e:
                raise UsageError(f"--max-memory: {e}")
        return run(a.in_dir, a.out_dir, scheduler=a.scheduler, workers=a.workers, tol=a.tol, timeout=a.timeout,
                   max_memory=max_memory, resume=a.resume, manifest=a.manifest)
    except UsageError as e:
        sys.stderr.write(f"kintsugi.dask: {e}\n")
        return 2


if __name__ == "__main__":
    # Run as kintsugi.dask (not __main__), so the tasks pickle by reference to this module.
    from kintsugi import dask as _self

    sys.exit(_self.main())
