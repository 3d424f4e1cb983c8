#!/usr/bin/env python3
"""Checks that includes between top-level folders follow the layers (docs/design.md).

For every `#include "x/..."` in a source file of top-level folder `f`, where `x` is another
top-level folder of the repository:
  * `x` must not be above `f` in the layer order below (peers of one library layer, such as
    zoo/ and io/, may not include each other either; the folders on top may);
  * `x` must be a declared link dependency of `f`: one of the library targets that `x`'s
    CMakeLists.txt defines (add_library) must be reachable from the targets `f`'s CMakeLists
    files link (target_link_libraries, and kintsugi_add_test's LIBS), following the link
    dependencies of libraries transitively; or `f` compiles `x`'s sources itself
    (`${PROJECT_SOURCE_DIR}/x/...` in its CMakeLists.txt).
A layer that does not exist yet is skipped. A folder with sources that is not in the layer
order is an error: give it a place here and in docs/design.md first. A folder with no
library target (header-only) is checked by layer only.

Prints one line per problem, `file:line: ...`, and exits 1 if there is any. No dependencies
beyond Python 3.

  python3 scripts/check_layers.py [repository root]
"""
import os
import re
import sys

# Lowest first; folders in one tuple are one layer.
LAYERS = [
    ("geometry",),
    ("kernel",),
    ("invariants",),
    ("problems",),
    ("zoo", "io", "view"),
    ("repair",),
    ("audit",),
    ("apps",),
    ("tests", "bench", "fuzz", "examples", "python"),
]
TOP = len(LAYERS) - 1  # folders on top may include each other (fuzz builds tests/support)

SOURCE_EXT = (".h", ".hpp", ".hh", ".cpp", ".cc", ".cxx", ".ipp", ".inl")
SKIP_DIRS = {".git", ".ci", "docs", "spec", "scripts"}
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"/]+)/[^"]*"')
CALL = re.compile(r"\b(add_library|target_link_libraries|kintsugi_add_test|foreach)\s*\(([^)]*)\)", re.S)
KEYWORDS = {"PUBLIC", "PRIVATE", "INTERFACE", "STATIC", "SHARED", "OBJECT", "ALIAS", "IMPORTED",
            "SOURCES", "LIBS", "IN", "LISTS", "ITEMS"}


def rank_of(folder):
    for i, layer in enumerate(LAYERS):
        if folder in layer:
            return i
    return None


def cmake_files(folder_path):
    for root, dirs, files in os.walk(folder_path):
        dirs[:] = [d for d in dirs if not d.startswith("build")]
        if "CMakeLists.txt" in files:
            yield os.path.join(root, "CMakeLists.txt")


def strip_comments(text):
    return "\n".join(line.split("#", 1)[0] if not line.lstrip().startswith("#") else "" for line in text.splitlines())


def parse_cmake(root, folders):
    """Returns (owner: target -> folder, links: target -> set of targets,
    used: folder -> set of targets its CMakeLists link, direct_src: folder -> set of folders)."""
    owner, links, used, direct_src = {}, {}, {}, {}
    for folder in folders:
        used[folder] = set()
        direct_src[folder] = set()
        for path in cmake_files(os.path.join(root, folder)):
            text = strip_comments(open(path, encoding="utf-8").read())
            for m in re.finditer(r"\$\{PROJECT_SOURCE_DIR\}/([A-Za-z0-9_.-]+)/", text):
                if m.group(1) != folder:
                    direct_src[folder].add(m.group(1))
            loops = {}  # foreach(var items...) so that ${var} in a link line expands
            for m in CALL.finditer(text):
                kind, args = m.group(1), m.group(2).split()
                if not args:
                    continue
                if kind == "foreach":
                    loops[args[0]] = [a for a in args[1:] if a not in KEYWORDS]
                    continue
                if kind == "add_library":
                    owner[args[0]] = folder
                    continue
                deps = set()
                rest = args[1:]
                if kind == "kintsugi_add_test":
                    rest = args[args.index("LIBS") + 1:] if "LIBS" in args else []
                for a in rest:
                    var = re.fullmatch(r"\$\{(\w+)\}", a)
                    for item in loops.get(var.group(1), []) if var else [a]:
                        if item not in KEYWORDS and not item.startswith("$"):
                            deps.add(item)
                if kind == "target_link_libraries":
                    links.setdefault(args[0], set()).update(deps)
                used[folder].update(deps)
    return owner, links, used, direct_src


def closure(start, links):
    seen, todo = set(), list(start)
    while todo:
        t = todo.pop()
        if t in seen:
            continue
        seen.add(t)
        todo.extend(links.get(t, ()))
    return seen


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    folders = []
    for name in sorted(os.listdir(root)):
        path = os.path.join(root, name)
        if not os.path.isdir(path) or name in SKIP_DIRS or name.startswith((".", "build")):
            continue
        has_source = any(f.endswith(SOURCE_EXT) for _, _, fs in os.walk(path) for f in fs)
        if has_source:
            folders.append(name)

    problems = []
    for f in folders:
        if rank_of(f) is None:
            problems.append(f"{f}/: folder is not in the layer order; add it to LAYERS in "
                            f"scripts/check_layers.py and to docs/design.md")

    owner, links, used, direct_src = parse_cmake(root, folders)
    libraries_of = {}
    for target, folder in owner.items():
        libraries_of.setdefault(folder, set()).add(target)
    reachable = {}
    for f in folders:
        start = set(used[f]) | libraries_of.get(f, set())
        reachable[f] = closure(start, links)

    for f in folders:
        rf = rank_of(f)
        for dirpath, dirs, files in os.walk(os.path.join(root, f)):
            dirs[:] = [d for d in dirs if not d.startswith("build")]
            for name in sorted(files):
                if not name.endswith(SOURCE_EXT):
                    continue
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, root)
                with open(path, encoding="utf-8", errors="replace") as fh:
                    for lineno, line in enumerate(fh, 1):
                        m = INCLUDE.match(line)
                        if not m:
                            continue
                        x = m.group(1)
                        if x == f or not os.path.isdir(os.path.join(root, x)) or x not in folders:
                            continue
                        rx = rank_of(x)
                        where = f"{rel}:{lineno}"
                        if rx is None:
                            problems.append(f"{where}: includes {x}/, which is not in the layer order")
                            continue
                        if rf is not None and (rx > rf or (rx == rf and rf != TOP)):
                            how = "above" if rx > rf else "beside"
                            problems.append(f"{where}: {f}/ includes {x}/, which is {how} it "
                                            f"(layers: docs/design.md)")
                            continue
                        libs = libraries_of.get(x)
                        if not libs:
                            continue  # header-only: the layer rule is all there is to check
                        if libs & reachable[f] or x in direct_src[f]:
                            continue
                        problems.append(f"{where}: {f}/ includes {x}/ but does not link "
                                        f"{' or '.join(sorted(libs))} (declare it in {f}/CMakeLists.txt)")

    for p in problems:
        print(p)
    if problems:
        print(f"check_layers: {len(problems)} problem(s)")
        return 1
    print(f"check_layers: {len(folders)} folders, includes follow the layers")
    return 0


if __name__ == "__main__":
    sys.exit(main())
