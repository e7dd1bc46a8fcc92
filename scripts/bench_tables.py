#!/usr/bin/python3
"""Makes docs/results/benchmarks.md from the benchmarks' CSVs in bench/results/, and checks it.

  scripts/bench_tables.py           write the page from the CSVs (the end of `make bench`)
  scripts/bench_tables.py --check   exit 1 when the committed page differs from what the CSVs give

The page holds each CSV as a table, in the order the benchmark printed its rows, and each goal of
docs/benchmarks.md against the figures. It depends on the CSVs alone (no dates, no machine), so
the same CSVs always give the same bytes.
"""
import argparse
import csv
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PAGE = "docs/results/benchmarks.md"
RESULTS = "bench/results"

# The goals (docs/benchmarks.md says why).
PRESCORE_GOAL_S = 1.0  # the default bunny (resolution 20, solid), load to written file (unit: s)
RENDER_GOAL_FPS = 20.0  # frames per second of the benchmark's first row, the defaults, PNG writing included
ENERGIZE_GOAL_PERCENT = 2.0  # the share of a run spent energizing, every scene (unit: %)
DEMO_GOAL_RATIO = 25.0  # the demo job at least this many times faster than the same job in Blender (wall time)
STEPS_GOALS = {"bunny1000": 60.0, "plate32": 150.0, "plate100": 20.0}  # steps per second, wall time

# Each table: the CSV's columns to show, in order, with their headings; "int" groups digits by
# thousands, "text" shows the cell as the benchmark printed it. A column the CSV lacks (a CSV made
# by an older benchmark) is left out.
PRESCORE_COLUMNS = [("mesh", "mesh", "text"), ("resolution", "resolution", "text"), ("hollow", "hollow", "text"), ("tets", "tets", "int"),
                    ("pieces", "pieces", "int"), ("constraints", "constraints", "int"),
                    ("collision_parts", "collision parts", "int"), ("load_s", "load", "text"),
                    ("check_s", "check", "text"), ("tetrahedralize_s", "tetrahedralize", "text"),
                    ("hollow_s", "hollow", "text"), ("impact_s", "impact", "text"), ("partition_s", "partition", "text"),
                    ("constraints_s", "constraints", "text"), ("pieces_render_s", "pieces + render surfaces", "text"),
                    ("appearance_s", "appearance", "text"), ("other_s", "other", "text"),
                    ("write_s", "write", "text"), ("total_s", "total", "text")]
RENDER_COLUMNS = [("scene", "scene", "text"), ("width", "width", "text"), ("height", "height", "text"), ("shadows", "shadows", "text"),
                  ("shadow_map", "shadow map", "text"), ("msaa", "msaa", "text"), ("msaa_region", "msaa region", "text"),
                  ("edge_filter", "edge filter", "text"), ("png_writer", "PNG writer", "text"),
                  ("frames", "frames", "int"), ("triangles", "triangles", "int"), ("seconds", "seconds", "text"),
                  ("fps", "frames/s", "text"), ("draw_ms", "draw ms", "text"), ("readback_ms", "readback ms", "text"),
                  ("filter_ms", "filter ms", "text"), ("encode_ms", "encode ms", "text"), ("write_ms", "write ms", "text"),
                  ("mb_per_frame", "MB a frame", "text")]
SIMULATE_COLUMNS = [("scene", "scene", "text"), ("pieces", "pieces", "int"), ("constraints", "constraints", "int"),
                    ("iterations", "iterations", "text"), ("alpha", "alpha", "text"), ("steps", "steps", "int"),
                    ("breaks", "breaks", "int"), ("fragments", "fragments", "int"), ("wall_s", "wall s", "text"),
                    ("steps_per_s", "steps/s", "text"), ("steps_per_cpu_s", "steps per CPU s", "text"),
                    ("energize_s", "energizing s", "text"), ("energize_percent", "energizing %", "text"),
                    ("asleep", "asleep", "int"), ("iterations_per_step", "iterations a step", "text"),
                    ("stretch_over_stored", "stretch over stored", "text"), ("poses_hash", "poses_hash", "text")]
DEMO_STAGES = ["prescore", "simulate", "render", "encode", "sheet", "plot", "export", "report"]
DEMO_BLENDER_PHASES = ["import", "fracture", "constraints", "bake", "render"]


def read_csv(path):
    """The CSV's rows as dicts, or None when the file is not there."""
    if not os.path.exists(path):
        return None
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def cell(value, kind):
    if kind == "int" and value.lstrip("-").isdigit():
        return "{:,}".format(int(value))
    return value.replace("|", "\\|")


def table(rows, columns):
    shown = [c for c in columns if c[0] in rows[0]]
    lines = ["| " + " | ".join(heading for _, heading, _ in shown) + " |", "|" + " --- |" * len(shown)]
    lines += ["| " + " | ".join(cell(r[name], kind) for name, _, kind in shown) + " |" for r in rows]
    return lines


def met(ok):
    return "met" if ok else "not met"


def prescore_section(rows):
    lines = ["## prescore (bench/results/prescore.csv)", ""]
    default = [r for r in rows if r["resolution"] == "20" and r["hollow"] == "solid"]
    if default:
        total = float(default[0]["total_s"])
        lines += ["Goal: the default bunny (resolution 20, solid) from load to written file in under %g s: %.2f s, %s."
                  % (PRESCORE_GOAL_S, total, met(total < PRESCORE_GOAL_S))]
        largest = max((r for r in rows if r["hollow"] == "solid"), key=lambda r: int(r["tets"]))
        if largest is not default[0]:
            lines += ["", "From the default's %s tets to %s (%.0fx) the total grows %.1fx." % (
                cell(default[0]["tets"], "int"), cell(largest["tets"], "int"),
                int(largest["tets"]) / int(default[0]["tets"]), float(largest["total_s"]) / total)]
    return lines + ["", "Times in seconds."] + [""] + table(rows, PRESCORE_COLUMNS)


def render_section(rows):
    first = rows[0]
    fps = float(first["fps"])
    lines = ["## render (bench/results/render.csv)", "",
             "Goal: at least %g frames/s with the defaults (the first row), PNG writing included: %s frames/s, %s."
             % (RENDER_GOAL_FPS, first["fps"], met(fps >= RENDER_GOAL_FPS)), ""]
    return lines + table(rows, RENDER_COLUMNS)


def simulate_section(rows):
    lines = ["## simulate (bench/results/simulate.csv)", ""]
    worst = max(rows, key=lambda r: float(r["energize_percent"]))
    lines += ["Goal: energizing at most %g%% of a run's time: at most %s%% (%s, alpha %s), %s."
              % (ENERGIZE_GOAL_PERCENT, worst["energize_percent"], worst["scene"], worst["alpha"],
                 met(float(worst["energize_percent"]) <= ENERGIZE_GOAL_PERCENT)), ""]
    # A goal scene's rows: with the shipped joints (the name alone, or "+direct" where they solve
    # directly) and, beside them in the same run, with iterative joints ("+iterative").
    def base(r):
        return r["scene"].split("+")[0]

    def shipped(r):
        return not r["scene"].endswith("+iterative")

    goal_rows = [r for r in rows if base(r) in STEPS_GOALS]
    if goal_rows:
        lines += ["Goals in steps per second (wall time, every alpha), asked of the shipped joints; iterative "
                  "joints beside them where the run has them:", "",
                  "| scene | pieces | constraints | goal | shipped joints: steps/s, simulate s "
                  "| iterative joints: steps/s, simulate s | result |",
                  "| --- | --- | --- | --- | --- | --- | --- |"]

        def figures(of):
            return "; ".join("alpha %s: %s steps/s, %s s" % (r["alpha"], r["steps_per_s"], r["wall_s"]) for r in of) or "not run"

        for scene in STEPS_GOALS:
            ours = [r for r in goal_rows if base(r) == scene and shipped(r)]
            iterative = [r for r in goal_rows if base(r) == scene and not shipped(r)]
            if ours:
                goal = STEPS_GOALS[scene]
                lines.append("| %s | %s | %s | %g | %s | %s | %s |" % (
                    ours[0]["scene"], cell(ours[0]["pieces"], "int"), cell(ours[0]["constraints"], "int"), goal,
                    figures(ours), figures(iterative), met(all(float(r["steps_per_s"]) >= goal for r in ours))))
        lines.append("")
    return lines + table(rows, SIMULATE_COLUMNS)


def median(values):
    values = sorted(values)
    n = len(values)
    return (values[n // 2] + values[(n - 1) // 2]) / 2


def demo_section(rows):
    lines = ["## demo job against Blender (bench/results/demo.csv)", ""]
    shatter = [r for r in rows if r["tool"] == "shatter"]
    blender = [r for r in rows if r["tool"] == "blender"]
    if not shatter:
        return lines + ["No shatter run in the CSV."]
    ours = median([float(r["total_s"]) for r in shatter])
    if blender:
        theirs = median([float(r["total_s"]) for r in blender])
        ratio = theirs / ours
        lines += ["Goal: the demo job at least %g times faster than the same job in Blender: Blender %.1f s, shatter "
                  "%.2f s (medians of %d and %d runs, alternated), %.1f times faster, %s."
                  % (DEMO_GOAL_RATIO, theirs, ours, len(blender), len(shatter), ratio, met(ratio >= DEMO_GOAL_RATIO)), ""]
    else:
        lines += ["Goal: the demo job at least %g times faster than the same job in Blender: shatter %.2f s (median of "
                  "%d runs); no Blender run in the CSV (blender was not installed), so not measured."
                  % (DEMO_GOAL_RATIO, ours, len(shatter)), ""]
    lines += ["Wall time of the whole command (total) and shatter's time per stage as its summary gives it (a stage "
              "run beside render overlaps it: the stages do not add up to the total). Seconds.", "",
              "| run | total | " + " | ".join(DEMO_STAGES) + " | frames |", "|" + " --- |" * (len(DEMO_STAGES) + 3)]
    for r in shatter:
        lines.append("| %s | %s | %s | %s |" % (r["run"], r["total_s"], " | ".join(r[s + "_s"] for s in DEMO_STAGES),
                                               r["frames"]))
    lines.append("| median | %.2f | %s | |" % (ours, " | ".join(
        "%.2f" % median([float(r[s + "_s"]) for r in shatter if r[s + "_s"]]) if any(r[s + "_s"] for r in shatter)
        else "" for s in DEMO_STAGES)))
    if blender:
        lines += ["", "Blender (bench/blender_demo.py: Cell Fracture into 10 pieces, breakable fixed constraints between "
                  "touching pieces, the drop baked, Workbench at 1280x720), its phases as the script times them:", "",
                  "| run | total | " + " | ".join(DEMO_BLENDER_PHASES) + " | frames |",
                  "|" + " --- |" * (len(DEMO_BLENDER_PHASES) + 3)]
        for r in blender:
            lines.append("| %s | %s | %s | %s |" % (r["run"], r["total_s"], " | ".join(
                r["blender_%s_s" % p] for p in DEMO_BLENDER_PHASES), r["frames"]))
    return lines


def render_page(results):
    lines = [
        "# Benchmark results",
        "",
        "Made by scripts/bench_tables.py, which `make bench` runs after the benchmarks, from their CSVs in "
        "bench/results/; the test Bench.Tables fails when this page differs from what the CSVs give. What each benchmark "
        "measures, how to run one and why its goal: docs/benchmarks.md. The figures are of the machine, and of "
        "whatever else ran on it, when the benchmark last ran: to compare two builds, run them side by side "
        "(docs/benchmarks.md).",
    ]
    for name, section in (("prescore", prescore_section), ("render", render_section), ("simulate", simulate_section),
                          ("demo", demo_section)):
        rows = read_csv(os.path.join(results, name + ".csv"))
        lines.append("")
        lines += section(rows) if rows else ["## %s" % name, "", "No bench/results/%s.csv yet: `make bench`." % name]
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true", help="compare the page with what the CSVs give; write nothing")
    ap.add_argument("--results", default=os.path.join(ROOT, RESULTS), help="the CSVs' folder (default: %s)" % RESULTS)
    ap.add_argument("--page", default=os.path.join(ROOT, PAGE), help="the page (default: %s)" % PAGE)
    args = ap.parse_args()
    want = render_page(args.results)
    if args.check:
        have = open(args.page).read() if os.path.exists(args.page) else ""
        if have == want:
            print("%s: as the CSVs in %s give" % (args.page, args.results))
            return 0
        have_lines, want_lines = have.split("\n"), want.split("\n")
        at = next((i for i, (a, b) in enumerate(zip(have_lines, want_lines)) if a != b),
                  min(len(have_lines), len(want_lines)))
        print("%s differs from what the CSVs in %s give, first at line %d:\n  page: %s\n  CSVs: %s\n"
              "fix: scripts/bench_tables.py (after a change to a CSV or to the script)"
              % (args.page, args.results, at + 1, have_lines[at] if at < len(have_lines) else "(end)",
                 want_lines[at] if at < len(want_lines) else "(end)"))
        return 1
    os.makedirs(os.path.dirname(args.page), exist_ok=True)
    with open(args.page + ".tmp", "w") as out:
        out.write(want)
    os.replace(args.page + ".tmp", args.page)
    print("%s: written from the CSVs in %s" % (args.page, args.results))
    return 0


if __name__ == "__main__":
    sys.exit(main())
