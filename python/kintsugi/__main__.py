"""python -m kintsugi batch IN_DIR OUT_DIR [options]: the CLI's `kintsugi batch`, the
same program with the same options, manifest and exit codes (0, 3 some files failed,
2 bad usage). `python -m kintsugi.dask` runs the same jobs on a Dask cluster."""
import os
import sys

import kintsugi

USAGE = """usage: python -m kintsugi batch IN_DIR OUT_DIR [options]   (options: python -m kintsugi batch --help)
       python -m kintsugi.dask IN_DIR OUT_DIR [--scheduler ADDRESS] [options]
"""


def main(argv):
    if not argv or argv[0] in ("-h", "--help"):
        sys.stdout.write(USAGE) if argv else sys.stderr.write(USAGE)
        return 0 if argv else 2
    if argv[0] != "batch":
        sys.stderr.write(f"python -m kintsugi: unknown verb '{argv[0]}'\n" + USAGE)
        return 2
    exe = kintsugi.executable()
    sys.stdout.flush()
    os.execv(exe, [exe, "batch", *argv[1:]])


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
