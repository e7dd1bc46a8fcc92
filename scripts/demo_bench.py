#!/usr/bin/python3
"""The demo job timed, and the same job in Blender beside it (make bench; docs/benchmarks.md).

  scripts/demo_bench.py [BUILD] [--runs N] [--no-blender] > bench/results/demo.csv

Runs `BUILD/bin/shatter run assets/bunny.toml -o FRESH --no-progress` N times (default 3), each into
a new folder (nothing up to date, no cache), and, when `blender` is on PATH, bench/blender_demo.py
in Blender as many times, alternating the two (shatter, Blender, shatter, ...) so that the load of
a shared machine falls on both alike; each Blender run draws as many frames as the shatter run
before it (the demo's movie ends when its pieces rest). Prints CSV to standard output, a row per run as it ends:
the wall time of the whole command (total_s), shatter's time per stage as its summary gives it
(stages that run beside render overlap it, so they do not add up to the total), and Blender's time
per phase as the script prints it. Progress goes to standard error.
"""
import argparse
import csv
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import tomllib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHOT = "assets/bunny.toml"
STAGES = ["prescore", "simulate", "render", "encode", "sheet", "plot", "export", "report"]
BLENDER_PHASES = ["import", "fracture", "constraints", "bake", "render"]
COLUMNS = (["tool", "run", "total_s"] + [s + "_s" for s in STAGES] + ["blender_%s_s" % p for p in BLENDER_PHASES] +
           ["frames"])


def run_shatter(build, run, scratch):
    out = os.path.join(scratch, "shatter-%d" % run)
    start = time.monotonic()
    r = subprocess.run([os.path.join(build, "bin", "shatter"), "run", SHOT, "-o", out, "--no-progress"], cwd=ROOT,
                       capture_output=True, text=True)
    total = time.monotonic() - start
    if r.returncode != 0:
        sys.exit("demo_bench: shatter failed (exit %d):\n%s" % (r.returncode, r.stderr[-2000:]))
    row = {"tool": "shatter", "run": run, "total_s": "%.2f" % total}
    line = next((l for l in r.stdout.splitlines() if l.startswith("stages:")), "")
    for stage, seconds in re.findall(r"(\w+) ([0-9.]+)s", line):
        if stage in STAGES:
            row[stage + "_s"] = seconds
    row["frames"] = len([f for f in os.listdir(os.path.join(out, "frames")) if f.endswith(".png")])
    shutil.rmtree(out, ignore_errors=True)
    return row


def run_blender(blender, mesh, run, scratch, frames):
    out = os.path.join(scratch, "blender-%d" % run)
    start = time.monotonic()
    r = subprocess.run([blender, "-b", "--factory-startup", "--python", os.path.join(ROOT, "bench", "blender_demo.py"),
                        "--", mesh, out, str(frames)], cwd=ROOT, capture_output=True, text=True)
    total = time.monotonic() - start
    line = next((l for l in r.stdout.splitlines() if l.startswith("blender_demo:")), None)
    if r.returncode != 0 or line is None:
        sys.exit("demo_bench: Blender failed (exit %d):\n%s" % (r.returncode, (r.stdout + r.stderr)[-2000:]))
    row = {"tool": "blender", "run": run, "total_s": "%.2f" % total}
    for phase, seconds in re.findall(r"(\w+) ([0-9.]+)", line.split("(")[0]):
        if phase in BLENDER_PHASES:
            row["blender_%s_s" % phase] = seconds
    row["frames"] = re.search(r"(\d+) frames", line).group(1)
    shutil.rmtree(out, ignore_errors=True)
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("build", nargs="?", default="build", help="the build folder (default: build)")
    ap.add_argument("--runs", type=int, default=3, help="runs of each (default: 3)")
    ap.add_argument("--no-blender", action="store_true", help="time shatter alone")
    args = ap.parse_args()
    build = os.path.abspath(args.build)
    with open(os.path.join(ROOT, SHOT), "rb") as f:
        mesh = tomllib.load(f)["mesh"]["path"]
    blender = None if args.no_blender else shutil.which("blender")
    if blender is None:
        print("demo_bench: %s: shatter alone" % ("--no-blender" if args.no_blender else
                                               "blender is not on PATH (apt-get install blender)"), file=sys.stderr)
    writer = csv.DictWriter(sys.stdout, fieldnames=COLUMNS, restval="", lineterminator="\n")
    writer.writeheader()
    sys.stdout.flush()
    with tempfile.TemporaryDirectory(prefix="shatter-demo-bench-") as scratch:
        for run in range(1, args.runs + 1):
            print("demo_bench: shatter, run %d of %d" % (run, args.runs), file=sys.stderr, flush=True)
            ours = run_shatter(build, run, scratch)
            writer.writerow(ours)
            sys.stdout.flush()
            if blender:
                print("demo_bench: blender, run %d of %d (%d frames)" % (run, args.runs, ours["frames"]),
                      file=sys.stderr, flush=True)
                writer.writerow(run_blender(blender, mesh, run, scratch, ours["frames"]))
                sys.stdout.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
