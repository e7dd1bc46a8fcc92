#!/usr/bin/env python3
"""make refresh: re-makes, with this build, every committed figure that a change of behaviour
moves, then says what moved and by how much (for the commit message).

  scripts/refresh.py BUILD [--only STEP,...]

The steps, in order (each prints its time):
  settings  docs/shot.md and docs/render.md's settings tables (`shatter settings-doc`)
  pins      the determinism pins, tests/pins/scenes.txt (tests/cli/determinism_pins_test.cpp)
  figures   the figures tests pin from their runs, tests/pins/figures.tsv (every test file that
            calls expect_pinned: tests/support/pinned_figures.h)
  goldens   the render goldens and the scene strips' goldens (tests/golden/), re-made only where
            they no longer match at the tests' tolerance
  sweeps    each scene's sweep, assets/sweeps/<scene>.toml: docs/images/<scene>-strip.png and
            -energy.png, and the tables in docs/results/scenes.md
  cracks    the cracks before and after fairing (build/bench/crack_look): docs/images/cracks-*.png
            and the crease table docs/results/cracks.md
  pages     the results pages made from committed data (docs/results/): the study's, the
            benchmarks', the corpus's, where their scripts are present

The study (`make study`), the benchmarks (`make bench`) and the corpus (`make corpus-run`) are
their own commands and write their own data: this only re-renders their pages from it. A clean
tree stays clean: every step writes the same bytes when nothing moved.
"""
import argparse
import filecmp
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STEPS = ["settings", "pins", "figures", "goldens", "sweeps", "cracks", "pages"]
CRACKS_PAGE = "docs/results/cracks.md"
SCENES_PAGE = "docs/results/scenes.md"


def run(cmd, env=None, check=True, quiet=True):
    """Runs cmd in the project's folder; its output is shown only when it fails (or not quiet)."""
    full_env = dict(os.environ)
    full_env.update(env or {})
    r = subprocess.run(cmd, cwd=ROOT, env=full_env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if (r.returncode != 0 and check) or not quiet:
        sys.stdout.write(r.stdout)
    if r.returncode != 0 and check:
        sys.exit(f"refresh: `{' '.join(cmd)}` failed (exit {r.returncode})")
    return r


def tracked(patterns):
    """The files git tracks (and untracked ones not ignored) under these patterns, relative to ROOT."""
    out = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard", "--"] + patterns,
                         cwd=ROOT, stdout=subprocess.PIPE, text=True, check=True).stdout
    return sorted(set(out.split()))


WATCHED = ["docs/shot.md", "docs/render.md", "tests/pins", "tests/golden", "docs/images", "docs/results"]


def snapshot(folder):
    """Copies every watched file into folder; returns their paths."""
    files = tracked(WATCHED)
    for f in files:
        dst = os.path.join(folder, f)
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        shutil.copy2(os.path.join(ROOT, f), dst)
    return files


def gtest(build, binary, filt, env):
    exe = os.path.join(build, "tests", binary)
    if not os.path.exists(exe):
        sys.exit(f"refresh: {exe} is missing: build everything first (make build)")
    return run([exe, f"--gtest_filter={filt}", "--gtest_brief=1"], env=env)


def step_settings(build):
    run([os.path.join(build, "bin", "shatter"), "settings-doc", "docs/shot.md", "docs/render.md"])


def step_pins(build):
    gtest(build, "cli_tests", "DeterminismPins.*", {"SHATTER_UPDATE_PINS": "1"})


def pinned_suites():
    """(stage binary, suite) for every test suite in a file that pins figures."""
    suites = set()
    for path in sorted(glob.glob(os.path.join(ROOT, "tests", "*", "*_test.cpp"))):
        text = open(path, encoding="utf-8").read()
        if "expect_pinned(" not in text:
            continue
        stage = os.path.basename(os.path.dirname(path))
        for suite in re.findall(r"^TEST(?:_F)?\((\w+),", text, re.M):
            suites.add((f"{stage}_tests", suite))
    return sorted(suites)


def step_figures(build):
    by_binary = {}
    for binary, suite in pinned_suites():
        by_binary.setdefault(binary, []).append(suite + ".*")
    for binary, suites in by_binary.items():
        gtest(build, binary, ":".join(suites), {"SHATTER_UPDATE_FIGURES": "1"})


def step_goldens(build):
    env = {"SHATTER_UPDATE_GOLDEN": "1"}
    gtest(build, "render_tests", "Golden.*", env)
    gtest(build, "cli_tests", "SceneStrips.*:Scenes/PaperSceneStrips.*", env)


# The render goldens' tolerance (tests/render/golden_test.cpp): a strip drawn by another build of
# Mesa's llvmpipe, or on another processor, differs by a level here and there.
GOLDEN_TOLERANCE = ["--max-rmse", "1.5", "--min-ssim", "0.98", "--threshold", "24", "--max-fraction", "0.005"]


def looks_alike(build, committed, made):
    """The committed image and the one made are the same, or alike within the goldens' tolerance."""
    if not os.path.exists(committed):
        return False
    if filecmp.cmp(committed, made, shallow=False):
        return True
    with tempfile.TemporaryDirectory() as tmp:
        r = run([os.path.join(build, "bin", "shatter"), "diff", committed, made, "--report", tmp] + GOLDEN_TOLERANCE,
                check=False)
    return r.returncode == 0


def batch_table(out_dir, scene):
    """The sweep's table as Markdown, from the batch's own table file."""
    for name in (f"{scene}.table.md", "table.md"):
        path = os.path.join(out_dir, scene, name)
        if os.path.exists(path):
            return open(path, encoding="utf-8").read().strip() + "\n"
    return None


def step_sweeps(build):
    shatter = os.path.join(build, "bin", "shatter")
    work = os.path.join(build, "refresh-sweeps")
    shutil.rmtree(work, ignore_errors=True)
    sections = []
    for shot in sorted(glob.glob(os.path.join(ROOT, "assets", "sweeps", "*.toml"))):
        scene = os.path.splitext(os.path.basename(shot))[0]
        start = time.time()
        run([shatter, "batch", shot, "-o", work, "--quiet"])
        made = os.path.join(work, scene)
        for kind in ("strip", "energy"):
            src = os.path.join(made, f"{scene}.{kind}.png")
            if not os.path.exists(src):
                sys.exit(f"refresh: the sweep of {scene} wrote no {src}")
            dst = os.path.join(ROOT, "docs", "images", f"{scene}-{kind}.png")
            if not looks_alike(build, dst, src):
                shutil.copyfile(src, dst)
        table = batch_table(work, scene)
        if table is None:
            sys.exit(f"refresh: the sweep of {scene} wrote no table in {made}")
        sections.append(f"## {scene}\n\n`shatter batch assets/sweeps/{scene}.toml` "
                        f"(strip: docs/images/{scene}-strip.png, energy: docs/images/{scene}-energy.png)\n\n{table}")
        print(f"  sweep {scene}: {time.time() - start:.0f} s")
    page = ("# The scenes' sweeps\n\n"
            "Generated by `make refresh` (scripts/refresh.py) from `shatter batch assets/sweeps/<scene>.toml`: do "
            "not edit. docs/scenes.md says what each scene shows and how to read the columns.\n\n"
            + "\n".join(sections))
    os.makedirs(os.path.dirname(os.path.join(ROOT, SCENES_PAGE)), exist_ok=True)
    write_if_changed(os.path.join(ROOT, SCENES_PAGE), page)


# The crack looks' meshes: the demo, and a corpus mesh (Debian's glmark2-data) when installed.
CRACK_MESHES = [("bunny", "assets/bunny.toml"), ("cat", "/usr/share/glmark2/models/cat.3ds")]


def step_cracks(build):
    """docs/images/cracks-NAME.png (tet faces, faired cracks, faired on split tets) and their crease table."""
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, mesh in CRACK_MESHES:
            path = mesh if os.path.isabs(mesh) else os.path.join(ROOT, mesh)
            if not os.path.exists(path):
                print(f"  cracks {name}: {path} is not installed; its image and rows are kept")
                continue
            made = os.path.join(tmp, f"cracks-{name}.png")
            r = run([os.path.join(build, "bench", "crack_look"), made, path])
            rows += [line.split(",") for line in r.stdout.splitlines()
                     if line.count(",") == 5 and not line.startswith("mesh,")]
            dst = os.path.join(ROOT, "docs", "images", f"cracks-{name}.png")
            if not looks_alike(build, dst, made):
                shutil.copyfile(made, dst)
    if not rows:
        return
    table = ["| mesh | cracks | pieces | crack area (m^2, both sides) | crease density | creased edges |",
             "|---|---|---:|---:|---:|---:|"]
    table += [f"| {m} | {c} | {p} | {a} | {d} | {float(s):.1%} |" for m, c, p, a, d, s in rows]
    page = ("# Crack creases\n\n"
            "Generated by `make refresh` (scripts/refresh.py) from `build/bench/crack_look`: do not edit. Each mesh "
            "at the default shot, prescored with `crack_fairing = false` (the tet faces between the pieces), "
            "with the default (faired) and with `crack_split = true` (faired on the crack tets split in eight); "
            "crease density as prescore/crack_creases.h defines it (the length of crack edges sharper than 30 "
            "degrees per unit of crack area, times the diagonal). Images: docs/images/cracks-*.png (left to "
            "right: tet faces, faired, faired on split tets).\n\n" + "\n".join(table) + "\n")
    write_if_changed(os.path.join(ROOT, CRACKS_PAGE), page)


def write_if_changed(path, text):
    if os.path.exists(path) and open(path, encoding="utf-8").read() == text:
        return
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(path + ".tmp", path)


# The results pages' own scripts, each re-rendering its page from committed data when present.
PAGE_SCRIPTS = [
    ["scripts/study_tables.py"],
    ["scripts/bench_tables.py"],
    ["scripts/corpus.py", "--render-only", "docs/results/corpus.md", "docs/results/corpus-run.md"],
]


def step_pages(build):
    for cmd in PAGE_SCRIPTS:
        if os.path.exists(os.path.join(ROOT, cmd[0])):
            run(["/usr/bin/python3"] + cmd)


def read_tsv_figures(path):
    rows = {}
    if os.path.exists(path):
        for line in open(path, encoding="utf-8"):
            parts = line.rstrip("\n").split("\t")
            if len(parts) >= 2 and not line.startswith("#"):
                rows[parts[0]] = float(parts[1])
    return rows


def read_pins(path):
    rows = {}
    if os.path.exists(path):
        for line in open(path, encoding="utf-8"):
            if line.startswith("#") or " " not in line:
                continue
            name, value = line.rstrip("\n").split(" ", 1)
            rows[name] = value
    return rows


def image_change(build, old, new):
    """How far an image moved: `shatter diff`'s RMSE and share of pixels off by more than 24 levels."""
    with tempfile.TemporaryDirectory() as tmp:
        run([os.path.join(build, "bin", "shatter"), "diff", old, new, "--report", tmp], check=False)
        try:
            d = json.load(open(os.path.join(tmp, "summary.json")))["results"][0]
            return f"RMSE {d['rmse']:.2f} levels, {100 * d['fraction_over_threshold']:.2f}% of pixels off"
        except (OSError, ValueError, KeyError, IndexError):
            return "changed (size or format)"


def what_moved(build, before, files_before):
    """Lines that say what moved, file by file."""
    lines = []
    now = tracked(WATCHED)
    for f in sorted(set(now) | set(files_before)):
        old, new = os.path.join(before, f), os.path.join(ROOT, f)
        if not os.path.exists(new):
            lines.append(f"{f}: removed")
            continue
        if not os.path.exists(old):
            lines.append(f"{f}: new")
            continue
        if filecmp.cmp(old, new, shallow=False):
            continue
        if f == "tests/pins/figures.tsv":
            a, b = read_tsv_figures(old), read_tsv_figures(new)
            for name in sorted(set(a) | set(b)):
                if a.get(name) == b.get(name):
                    continue
                if name not in a or name not in b:
                    lines.append(f"figure {name}: {a.get(name, '-')} -> {b.get(name, '-')}")
                    continue
                rel = (b[name] - a[name]) / abs(a[name]) if a[name] else float("inf")
                lines.append(f"figure {name}: {a[name]:.6g} -> {b[name]:.6g} ({100 * rel:+.1f}%)")
        elif f.startswith("tests/pins/"):
            a, b = read_pins(old), read_pins(new)
            moved = [n for n in sorted(set(a) | set(b)) if a.get(n) != b.get(n)]
            lines.append(f"{f}: {', '.join(moved)}")
        elif f.endswith(".png"):
            lines.append(f"{f}: {image_change(build, old, new)}")
        else:
            a = open(old, encoding="utf-8").read().splitlines()
            b = open(new, encoding="utf-8").read().splitlines()
            changed = sum(1 for x, y in zip(a, b) if x != y) + abs(len(a) - len(b))
            lines.append(f"{f}: {changed} lines changed")
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("build", help="the build folder (make build's)")
    ap.add_argument("--only", help="comma-separated steps: " + ",".join(STEPS))
    args = ap.parse_args()
    build = os.path.abspath(args.build)
    steps = args.only.split(",") if args.only else STEPS
    for s in steps:
        if s not in STEPS:
            sys.exit(f"refresh: --only {s}: no such step (steps: {', '.join(STEPS)})")
    total = time.time()
    with tempfile.TemporaryDirectory() as before:
        files_before = snapshot(before)
        for s in steps:
            start = time.time()
            print(f"refresh: {s} ...", flush=True)
            globals()["step_" + s](build)
            print(f"refresh: {s} done in {time.time() - start:.0f} s", flush=True)
        moved = what_moved(build, before, files_before)
    print(f"\nrefresh: {len(steps)} steps in {time.time() - total:.0f} s.", end=" ")
    if not moved:
        print("Nothing moved.")
    else:
        print("What moved:")
        for line in moved:
            print("  " + line)


if __name__ == "__main__":
    main()
