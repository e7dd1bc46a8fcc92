#!/usr/bin/python3
"""Checks that the folders depend on each other only as docs/architecture.md says.

  scripts/check_layout.py SOURCE_DIR

The rule is the table ALLOWED below: which project folders each library folder may use. Three
things must follow it, and the check fails naming the file and line of each that does not:
  - every `#include "FOLDER/..."` in a folder's .h and .cpp files;
  - every project library (shatter_FOLDER) in the folder's CMakeLists.txt target_link_libraries;
  - the project folders named in the "depends on" column of docs/architecture.md's folder table.
bench/ may use every library folder but nothing from tests/. Runs in `make test` (ctest
Layout.Dependencies). Exits 1 when something breaks the rule.
"""
import os
import re
import sys

LIBRARIES = ["core", "meshio", "scenes", "prescore", "simulate", "render", "pipeline"]
# Project folders each library folder may use (besides itself).
ALLOWED = {
    "core": set(),
    "meshio": {"core"},
    "scenes": {"core"},
    "prescore": {"core", "meshio", "scenes"},
    "simulate": {"core", "meshio"},
    "render": {"core", "meshio"},
    "pipeline": {"core", "meshio", "scenes", "prescore", "simulate", "render"},
    "cmd": {"core", "meshio", "scenes", "prescore", "simulate", "render", "pipeline"},
}
# scenes/render_test_scene.h is a header for render's tests and benchmarks, compiled only into
# targets that link render; the scenes library does not include it.
EXCEPTIONS = {("scenes/render_test_scene.h", "render")}

INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/[^"]+"')
LINK = re.compile(r"target_link_libraries\(\s*(\S+)([^)]*)\)", re.S)


def check_includes(root, folder, allowed, problems):
    base = os.path.join(root, folder)
    for dirpath, _, files in os.walk(base):
        for name in sorted(files):
            if not name.endswith((".h", ".cpp")):
                continue
            path = os.path.join(dirpath, name)
            rel = os.path.relpath(path, root)
            for number, line in enumerate(open(path, encoding="utf-8", errors="replace"), 1):
                m = INCLUDE.match(line)
                if not m:
                    continue
                used = m.group(1)
                if used == folder or used in allowed or (rel, used) in EXCEPTIONS:
                    continue
                if used in LIBRARIES or used == "tests":
                    problems.append(f"{rel}:{number}: includes {used}/, which {folder}/ must not use "
                                    f"(allowed: {', '.join(sorted(allowed)) or 'nothing'}; scripts/check_layout.py)")


def check_links(root, folder, allowed, problems):
    path = os.path.join(root, folder, "CMakeLists.txt")
    if not os.path.exists(path):
        return
    text = open(path, encoding="utf-8").read()
    for m in LINK.finditer(text):
        target, args = m.group(1), m.group(2)
        if target not in (f"shatter_{folder}", "shatter"):
            continue
        line = text[: m.start()].count("\n") + 1
        for lib in re.findall(r"\bshatter_([a-z]+)\b", args):
            if lib != folder and lib not in allowed:
                problems.append(f"{folder}/CMakeLists.txt:{line}: {target} links shatter_{lib}, which {folder}/ "
                                f"must not use (allowed: {', '.join(sorted(allowed)) or 'nothing'})")


def check_docs(root, problems):
    path = os.path.join(root, "docs", "architecture.md")
    seen = set()
    for number, line in enumerate(open(path, encoding="utf-8"), 1):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) != 3 or not cells[0].endswith("/"):
            continue
        folder = cells[0].rstrip("/")
        if folder not in ALLOWED:
            continue
        seen.add(folder)
        named = set()
        for word in re.split(r"[,;]", cells[2]):
            first = word.strip().split(" ")[0] if word.strip() else ""
            if first == "every":  # "every stage, ..."
                named |= ALLOWED[folder]
            elif first in LIBRARIES:
                named.add(first)
        if named != ALLOWED[folder]:
            problems.append(f"docs/architecture.md:{number}: {folder}/ depends on "
                            f"{', '.join(sorted(named)) or 'nothing'} by the table, "
                            f"{', '.join(sorted(ALLOWED[folder])) or 'nothing'} by scripts/check_layout.py")
    for folder in ALLOWED:
        if folder not in seen:
            problems.append(f"docs/architecture.md: no row for {folder}/ in the folder table")


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    problems = []
    for folder, allowed in ALLOWED.items():
        check_includes(root, folder, allowed, problems)
        check_links(root, folder, allowed, problems)
    check_includes(root, "bench", set(ALLOWED) - {"cmd"}, problems)
    check_docs(root, problems)
    for p in problems:
        print(p)
    print(f"check_layout: {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
