#!/usr/bin/python3
"""The study's results page, docs/results/study.md, made from the committed run's files.

    /usr/bin/python3 scripts/study_tables.py [RESULTS_DIR [PAGE]]           # write the page
    /usr/bin/python3 scripts/study_tables.py [RESULTS_DIR [PAGE]] --check   # compare, write nothing

Defaults: bench/results/study and docs/results/study.md, relative to the source folder. The page
has one section per section of docs/accuracy.md that has figures, each table made from the CSV
(or the printed .md) files that `make study` writes into RESULTS_DIR; it names them. Same files,
same bytes: no dates, no paths outside the source folder, fixed number formats. `make study`
runs it after the runs; ctest Docs.StudyResults runs --check, which exits 1 naming the page and
its first line that differs from what the files make. Standard library only (no matplotlib), so
that the check runs wherever the tests do. scripts/study_charts.py draws the charts from the same
files and uses the helpers below.
"""
import csv
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = ["rig", "beam", "plate", "chain", "bunny"]
FEM_SCENES = ["beam", "chain", "plate", "bunny", "corpus"]
CLASSES = ["stable", "refused", "nan", "energy_growth", "cascade", "fly_apart"]
CLASS_LETTER = {"stable": "S", "refused": "R", "nan": "N", "energy_growth": "E", "cascade": "C", "fly_apart": "F"}


# --- helpers shared with study_charts.py --------------------------------------------------------

def read(results, name):
    """The rows of RESULTS/NAME as dicts, or [] when the file is not there."""
    path = os.path.join(results, name)
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def num(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return math.nan


def yes(x):
    return str(x).strip().lower() in ("1", "true")


def knee(points):
    """The cheapest point whose error is within 2x of the smallest error on the curve.
    points: (cost, error, ...) tuples."""
    ok = [p for p in points if math.isfinite(p[1]) and p[1] >= 0]
    if not ok:
        return None
    best = min(p[1] for p in ok)
    good = [p for p in ok if p[1] <= 2 * max(best, 1e-9)]
    return min(good, key=lambda p: p[0])


# --- formatting ---------------------------------------------------------------------------------

def f(x, spec=".3g", scale=1.0):
    """x (a string or number) times scale in format spec; "-" for a missing value or NaN."""
    v = num(x)
    if math.isnan(v):
        return "-"
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    s = format(v * scale, spec)
    return "0" if s in ("-0", "+0") else s


def value(knob, v):
    """A knob's value as the shot keys write it (constraints per pair 0 is "all")."""
    if knob == "constraints_per_pair" and num(v) == 0:
        return "all"
    return f(v, "g")


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + " --- |" * len(header)]
    out += ["| " + " | ".join(str(c).replace("|", "\\|") for c in r) + " |" for r in rows]
    return out


def span(xs, spec):
    """"a to b" over xs in format spec, or one number when they are all the same."""
    lo, hi = format(min(xs), spec), format(max(xs), spec)
    return lo if lo == hi else f"{lo} to {hi}"


def missing(name):
    return [f"*Not in the committed run: `{name}` is missing.*"]


def printed(text):
    """A program's printed output as Markdown: its table lines as they are, every other line a
    list item, with a blank line wherever a table starts or ends."""
    out, in_table = [], False
    for line in text.rstrip("\n").split("\n"):
        if not line.strip():
            continue
        is_row = line.lstrip().startswith("|")
        if out and is_row != in_table:
            out.append("")
        out.append(line if is_row else "- " + line.strip())
        in_table = is_row
    return out


# --- the sections -------------------------------------------------------------------------------

def identities(res):
    rows = read(res, "identities_double.csv") + read(res, "identities_float.csv")
    out = ["## 1. Identities", "",
           "`identities_double.csv`, `identities_float.csv`. The energy identity: the largest "
           "|gained - intended| / intended over a run's breaks, on the rig (8 substeps, 20 iterations). "
           "The stiffness identity: k measured / k - 1 of the stiffness rig's bar pulled by gravity "
           "(stiffness in N/m^3, one column per number of solver iterations; -: the CFM guard refuses the "
           "step).", ""]
    if not rows:
        return out + missing("identities_double.csv")
    energy = [r for r in rows if r["measure"] == "energy"]
    out += table(["precision", "method", "stiffness (N/m^3)", "substeps", "iterations", "energy identity error"],
                 [[r["precision"], r["method"], f(r["stiffness"], "g"), r["substeps"], r["iterations"],
                   f(r["error"])] for r in energy])
    stiff = [r for r in rows if r["measure"] == "stiffness"]
    its = sorted({int(r["iterations"]) for r in stiff})
    keys = list(dict.fromkeys((r["precision"], r["stiffness"], r["substeps"]) for r in stiff))
    cell = {(r["precision"], r["stiffness"], r["substeps"], int(r["iterations"])): r["error"] for r in stiff}
    out += [""] + table(["precision", "stiffness (N/m^3)", "substeps"] + [f"{i} it" for i in its],
                        [[p, f(k, "g"), s] + [f(cell.get((p, k, s, i)), ".2g") for i in its] for p, k, s in keys])
    return out


def speed(res):
    rows = read(res, "speed.csv")
    out = ["## 2. Speed", "",
           "`speed.csv`. Seconds of wall time per simulated second, by stage (prescore: seconds for the "
           "model); render at 1280 x 720, 30 frames per simulated second.", ""]
    if not rows:
        return out + missing("speed.csv")
    return out + table(
        ["scene", "bodies", "constraints", "prescore (s)", "simulate (s / sim s)", "energize (s / sim s)",
         "render (s / sim s)", "total (s / sim s)", "steps / s"],
        [[r["scene"], r["bodies"], r["constraints"], f(r["prescore_s"]), f(r["simulate_per_sim_s"]),
          f(r["energize_per_sim_s"], ".2g"), f(r["render_per_sim_s"]), f(r["total_per_sim_s"]),
          f(r["steps_per_s"], ".0f")] for r in rows])


def size(r):
    return f"{r['bodies']} / {r['constraints']} / {r['collision_parts']} / {r['tets']}"


def sweep_row(r, label=None):
    refused = yes(r["refused"])
    v = label if label is not None else value(r["knob"], r["value"]) + (" (default)" if yes(r["is_default"]) else "")
    if refused:
        return [r["knob"], v, "refused by the CFM guard", "", "", "", "", "", ""]
    return [r["knob"], v, r["steps"], f(r["wall_per_sim_s"]), r["breaks"], f(r["first_break_s"], ".5g"),
            f(r["first_break_error_s"], ".3g", 1e3), f(r["trajectory_error_m"], ".3g", 1e3), size(r)]


SWEEP_HEADER = ["knob", "value", "steps", "wall (s / sim s)", "breaks", "first break (s)", "first-break error (ms)",
                "trajectory error (mm)", "bodies / constraints / parts / tets"]


def sweeps(res):
    rows = read(res, "sweeps_double.csv")
    flt = read(res, "sweeps_float.csv")
    out = ["## 3. Cost against error", "",
           "`sweeps_double.csv`, one knob at a time from the study default, against the reference (the "
           "first row of each scene: its substeps in the value column, max(4 x, 1,000) iterations). "
           "Errors are against that reference; a row with no break has no first-break error.", ""]
    if not rows:
        return out + missing("sweeps_double.csv")
    for scene in [s for s in SCENES if any(r["scene"] == s for r in rows)]:
        sr = [r for r in rows if r["scene"] == scene and r["knob"] != "auto_step"]
        body = []
        for r in sr:
            if r["knob"] == "reference":
                body.append(sweep_row(r, f"{f(r['value'], 'g')} substeps"))
            else:
                body.append(sweep_row(r))
        out += [f"### {scene}", ""] + table(SWEEP_HEADER, body) + [""]
    out += ["### Knees", "",
            "The cheapest setting of each knob whose trajectory error is within 2 x the smallest on its "
            "line (the red rings of study-cost-error.png).", ""]
    knees = []
    for scene in [s for s in SCENES if any(r["scene"] == s for r in rows)]:
        for knob in dict.fromkeys(r["knob"] for r in rows if r["scene"] == scene):
            if knob in ("reference", "auto_step"):
                continue
            pts = sorted((num(r["wall_per_sim_s"]), num(r["trajectory_error_m"]) * 1e3, r["value"])
                         for r in rows if r["scene"] == scene and r["knob"] == knob and not yes(r["refused"]))
            k = knee(pts)
            if k:
                knees.append([scene, knob, value(knob, k[2]), f(k[0]), f(k[1])])
    out += table(["scene", "knob", "knee value", "wall (s / sim s)", "trajectory error (mm)"], knees) + [""]
    out += ["### The automatic step", "",
            "`[simulate] substeps = \"auto\"` (knob `auto_step`) beside the reference and the study default "
            "(8 substeps, except the chain's reference: 16).", ""]
    body = []
    for scene in [s for s in SCENES if any(r["scene"] == s for r in rows)]:
        for r in rows:
            if r["scene"] != scene:
                continue
            if r["knob"] == "reference":
                body.append([scene] + sweep_row(r, f"reference ({f(r['value'], 'g')} substeps)")[1:])
        for r in rows:
            if r["scene"] == scene and r["knob"] == "substeps" and yes(r["is_default"]):
                body.append([scene] + sweep_row(r, f"default ({f(r['value'], 'g')} substeps)")[1:])
        for r in rows:
            if r["scene"] == scene and r["knob"] == "auto_step":
                body.append([scene] + sweep_row(r, "auto")[1:])
    out += table(["scene"] + SWEEP_HEADER[1:], body) + [""]
    out += ["### Float against double", "",
            "`sweeps_float.csv`: the substeps sweep with single-precision Bullet, against the double build's "
            "reference, beside the double build's row. The two builds ran one after the other: their wall "
            "times are not compared.", ""]
    if not flt:
        return out + missing("sweeps_float.csv")
    dbl = {(r["scene"], r["knob"], r["value"]): r for r in rows}
    body = []
    for r in flt:
        d = dbl.get((r["scene"], r["knob"], r["value"]), {})
        both = [x if x and not yes(x["refused"]) else None for x in (r, d)]

        def col(name, spec, scale=1.0):
            return [f(x[name], spec, scale) if x else "-" for x in both]

        body.append([r["scene"], value(r["knob"], r["value"])]
                    + [x["breaks"] if x else "refused" if y else "-" for x, y in zip(both, (r, d))]
                    + col("first_break_error_s", ".3g", 1e3) + col("trajectory_error_m", ".3g", 1e3)
                    + col("energy_identity_error", ".2g"))
    out += table(["scene", "substeps", "breaks, float", "breaks, double", "first-break error, float (ms)",
                  "double (ms)", "trajectory error, float (mm)", "double (mm)", "energy identity error, float",
                  "double"], body)
    return out


def methods(res):
    rows = read(res, "methods.csv")
    out = ["## 4. Methods side by side", "",
           "`methods.csv`, every method at the study defaults. \"injected\" is measured in each broken pair's "
           "frame; \"momentum work\" is dP . V, what the kicks' net momentum adds in the world's frame; the "
           "two books errors are (sum injected - alpha sum E) / (alpha sum E) and the same with the momentum "
           "work added. \"from plain\": mean distance of the material points from the plain run.", ""]
    if not rows:
        return out + missing("methods.csv")
    return out + table(
        ["scene", "method", "wall (s / sim s)", "breaks", "first break (s)", "stored E (J)", "injected (J)",
         "injected - alpha E", "momentum work (J)", "world: + momentum work - alpha E", "fragments",
         "KE 0.1 s after (J)", "from plain (mm)"],
        [[r["scene"], r["method"], f(r["wall_per_sim_s"]), r["breaks"], f(r["first_break_s"], ".4g"),
          f(r["stored_J"]), f(r["injected_J"]), f(r["books_error"], "+.3g", 100) + "%",
          f(r.get("momentum_work_J")), f(r.get("world_books_error"), "+.3g", 100) + "%", r["fragments"],
          f(r["kinetic_0.1s_after_J"]), f(r["difference_from_plain_m"], ".3g", 1e3)] for r in rows])


def seeds(res):
    rows = read(res, "seeds.csv")
    out = ["### Uniform and impact seeds", "",
           "`seeds.csv`: the demo shot (assets/bunny.toml) at 40 pieces with uniform and with impact seeds, 1.5 s "
           "as shipped. near / far: the mean volume of the pieces whose centres lie within 0.3 of the diagonal of "
           "the impact's contact over the mean volume of the rest; spread: the pieces' kinetic energy about their "
           "common centre of mass 0.1 s after the first break.", ""]
    if not rows:
        return out + missing("seeds.csv")
    return out + table(
        ["seeds", "ratio", "radius (m)", "breaks", "first break (s)", "fragments", "spread (J)", "near / far pieces",
         "near / far volume"],
        [[r["seeds"], f(r["ratio"]), f(r["radius_m"]), r["breaks"], f(r["first_break_s"], ".4g"), r["fragments"],
          f(r["spread_0.1s_after_J"]), f"{r['near']} / {r['far']}", f(r["near_over_far_volume"])] for r in rows])


def continuum(res):
    rows = read(res, "continuum.csv")
    out = ["## 5. Continuum reference: the beam against Euler-Bernoulli", "",
           "`continuum.csv`. M: the moment at the score of the constraints that broke in the first breaking "
           "step; Euler-Bernoulli: what the simply supported beam (L = 0.4 m) stores under the central load "
           "that makes M, and the time the formula takes; the last two columns: the modulus of rupture's "
           "moment and what Euler-Bernoulli stores at it.", ""]
    if not rows:
        return out + missing("continuum.csv")
    return out + table(
        ["iterations", "substeps", "first break (s)", "joints broken", "M (N m)", "stored at break (J)",
         "Euler-Bernoulli (J)", "ratio", "simulate (s)", "Euler-Bernoulli (s)", "rupture moment (N m)",
         "Euler-Bernoulli at it (J)"],
        [[r["iterations"], r["substeps"], f(r["first_break_s"], ".4g"), r["breaks_at_first"],
          f(r["moment_Nm"], ".4g"), f(r["stored_J"], ".4g"), f(r["euler_bernoulli_J"], ".4g"), f(r["ratio"], ".4g"),
          f(r["wall_s"]), f(r["euler_bernoulli_s"], ".2g"), f(r["rupture_moment_Nm"], "g"),
          f(r["rupture_energy_J"], ".3g")] for r in rows])


def stable_where_plain(mr, method):
    """As Study.Quick counts them: the cells of the mass x alpha map with alpha > 0 whose mass ratio
    plain breaking (energized at alpha 0) is stable at, and in how many of them METHOD is stable."""
    cls = {(r["method"], num(r["x"]), num(r["y"])): r["class"] for r in mr}
    cells = [(x, y) for (m, x, y) in cls if m == method and y > 0 and cls.get(("energized", x, 0.0)) == "stable"]
    return sum(1 for x, y in cells if cls[(method, x, y)] == "stable"), len(cells)


def stable_in(mr, method, cell_filter):
    rr = [r for r in mr if r["method"] == method and cell_filter(num(r["x"]), num(r["y"]))]
    return sum(1 for r in rr if r["class"] == "stable"), len(rr)


def stability(res):
    rows = read(res, "stability.csv")
    out = ["## 6. The stability map", "",
           "`stability.csv`, on the rig. Cells per class (guarded: the cells the CFM guard admits at "
           "max_cfm 0.5), then each map as a grid: S stable, R refused, N nan, E energy_growth, C cascade, "
           "F fly_apart; \"x\" after the letter: the guard at 0.5 refuses the cell and the letter is the run "
           "at max_cfm 0.99.", ""]
    if not rows:
        return out + missing("stability.csv")
    for m in dict.fromkeys(r["map"] for r in rows):
        mr = [r for r in rows if r["map"] == m]
        xn, yn = mr[0]["x_name"], mr[0]["y_name"]
        out += [f"### {m} (x: {xn}, y: {yn})", ""]
        meths = list(dict.fromkeys(r["method"] for r in mr))
        body = []
        for meth in meths:
            rr = [r for r in mr if r["method"] == meth]
            guarded = [r for r in rr if not yes(r["guard_refuses"])]
            line = [meth] + [str(sum(1 for r in rr if r["class"] == c)) for c in CLASSES]
            line.append(f"{sum(1 for r in guarded if r['class'] == 'stable')} of {len(guarded)}")
            if m == "mass_alpha":
                s, n = stable_where_plain(mr, meth)
                line.append(f"{s} of {n}")
            body.append(line)
        header = ["method"] + CLASSES + ["stable of guarded"]
        if m == "mass_alpha":
            header.append("stable where plain breaking is (alpha > 0)")
        out += table(header, body) + [""]
        xs = sorted({num(r["x"]) for r in mr})
        ys = sorted({num(r["y"]) for r in mr})
        cell = {(r["method"], num(r["x"]), num(r["y"])): CLASS_LETTER[r["class"]] + ("x" if yes(r["guard_refuses"])
                                                                                     else "") for r in mr}
        grid = [[meth, f(y, "g")] + [cell.get((meth, x, y), "") for x in xs] for meth in meths for y in ys]
        out += table(["method", yn] + [f(x, ".3g") for x in xs], grid) + [""]
    out += ["### 6.1 3D scenes", ""]
    scenes = read(res, "stability_scenes.csv")
    if not scenes:
        return out + missing("stability_scenes.csv") + [""] + [
            "(`make study` writes it; `study --quick --section stability --out DIR` writes all but the grid.)"]
    out += ["`stability_scenes.csv`. measure: hanging and alternating, sag / expected - 1; stack, the top "
            "cube's displacement (m); tower, the largest speed of a cube 2 or more from the hit (m/s); grid, "
            "the largest displacement (m). (x): the guard at 0.5 refuses; the run is without it.", ""]
    out += table(["scene", "mass ratio", "method", "joints", "class", "breaks", "far breaks", "measure",
                  "largest open (mm)", "KE at end (J)", "KE peak (J)", "stable"],
                 [[r["scene"], f(r["mass_ratio"], "g"), r["method"], r["joints"],
                   ("(x) " if yes(r["guard_refuses"]) else "") + r["class"], r["breaks"], r["far_breaks"],
                   f(r["measure"]), f(r["open_m"], ".3g", 1e3), f(r["ke_end_J"], ".2g"), f(r["ke_peak_J"], ".2g"),
                   "yes" if yes(r["stable"]) else "no"] for r in scenes])
    return out


def tolerance(r):
    if r["measure"] == "trajectory":
        return (f"RMS {f(r['tol_trajectory_m'], '.3g', 1e3)} mm, first break {f(r['tol_first_break_s'], '.3g', 1e3)} ms")
    return (f"first break {f(r['tol_first_break_s'], '.3g', 1e3)} ms, broken {f(r['tol_broken_fraction'], '.3g')}, "
            f"fragments {f(r['tol_fragments'], '.3g')}, scatter {f(r['tol_scatter_rel'], '.3g', 100)}%, "
            f"KE 0.1 s after {f(r['tol_kinetic_rel'], '.3g', 100)}%, its spread {f(r['tol_spread_rel'], '.3g', 100)}%, "
            f"early RMS {f(r['tol_early_m'], '.3g', 1e3)} mm")


def smallest(res):
    rows = read(res, "smallest.csv")
    summary = read(res, "smallest_summary.csv")
    out = ["## 7. The smallest model that serves", "",
           "`smallest_summary.csv`: per shot, what a model is held to (the measure, the drops per model, "
           "the window compared, the tolerances) and the finest, chosen and shipped models. Cost: CPU s of "
           "simulate per simulated s. worst / tol: the largest deviation from the finest model over its "
           "tolerance, 1 or less passes.", ""]
    if not summary:
        return out + missing("smallest_summary.csv")
    out += table(["shot", "measure", "drops", "window (s)", "tolerances (besides the joints' residual, 5% of "
                  "the strength)"],
                 [[r["shot"], r["measure"], r["drops"], f(r["window_s"], "g"), tolerance(r)] for r in summary])
    out += [""] + table(
        ["shot", "finest", "its size", "cost", "chosen", "its size", "cost", "worst / tol", "shipped", "cost",
         "worst / tol"],
        [[r["shot"], r["finest"], r["finest_size"], f(r["finest_cpu_per_sim_s"]), r["chosen"], r["chosen_size"],
          f(r["chosen_cpu_per_sim_s"]), f(r["chosen_worst_ratio"]), r["shipped"], f(r["shipped_cpu_per_sim_s"]),
          f(r["shipped_worst_ratio"])] for r in summary])
    if not rows:
        return out + [""] + missing("smallest.csv")
    out += ["", "`smallest.csv`: every model run (means over its drops). Roles: reference, the finest model; "
            "sweep, one knob down from it; variant, a knob swept but never chosen (another object, not a finer "
            "one); chosen (each attempt, the last passes) and shipped. Size: bodies / constraints / collision "
            "parts / tets.", ""]
    out += table(
        ["shot", "role", "knob", "value", "size", "substeps per recorded frame", "CPU (s / sim s)", "breaks", "fragments",
         "first break (s)", "trajectory RMS (mm)", "early RMS (mm)", "scatter (m)", "KE after (J)", "spread (J)",
         "residual / strength", "worst / tol"],
        [[r["shot"], r["role"], r["knob"], ("refused" if yes(r["refused"]) else value(r["knob"], r["value"])
                                            if r["role"] in ("sweep", "variant") else r["value"]),
          size(r), r["substeps"], f(r["cpu_per_sim_s"]), f(r["breaks"], ".4g"), f(r["fragments"], ".3g"),
          f(r["first_break_s"], ".4g"), f(r["trajectory_rms_m"], ".3g", 1e3), f(r["early_rms_m"], ".3g", 1e3),
          f(r["scatter_m"]), f(r["kinetic_after_J"]), f(r["spread_after_J"]), f(r["residual"], ".2g"),
          f(r["worst_ratio"])] for r in rows])
    return out


def fem(res):
    out = ["## 8. A continuum reference", ""]
    checks = os.path.join(res, "fem_checks.md")
    out += ["### The reference's checks against theory", "",
            "`fem_checks.md`: what `fem_checks` prints (the cantilever's deflection and frequency, time "
            "integration, the bar's wave speed, energy at large rotation, the interfaces).", ""]
    if os.path.exists(checks):
        with open(checks) as fh:
            out += printed(fh.read())
    else:
        out += missing("fem_checks.md")
    titles = {"beam": "8.1 The beam", "chain": "8.2 The chain", "plate": "8.3 The plate", "bunny": "8.3 The hollow bunny",
              "corpus": "8.3 A corpus mesh (asteroid-low.3ds, 4 pieces)"}
    for scene in FEM_SCENES:
        out += ["", f"### {titles[scene]}", "",
                f"`fem_{scene}.md`: what `fem_compare --scene {scene}` prints (its rows are `fem_{scene}.csv`). "
                "Energies in J at 0.1 s and 0.5 s after the first break, CPU in s per run, the energy error "
                "against the reference's row marked 0.", ""]
        path = os.path.join(res, f"fem_{scene}.md")
        if os.path.exists(path):
            with open(path) as fh:
                out += printed(fh.read())
        else:
            out += missing(f"fem_{scene}.md")
    ref = read(res, "reference.csv")
    out += ["", "### The quick study's reference runs", "",
            "`reference.csv`: the chain's and the plate's reference at 2 cells across and h = 1e-5 s, and the "
            "rigid method as shipped (the runs Study.Quick checks). predicted: the quasi-static break "
            "(chain) or the free fall's first contact (plate); ramp ratio: the first break as a fraction of "
            "the quasi-static ramp.", ""]
    if ref:
        out += table(["method", "cells", "step (s)", "first break (s)", "predicted (s)", "ramp ratio",
                      "joints broken", "middle joint's force / the bar's", "CPU (s)"],
                     [[r["method"], r["cells"], f(r["step_s"], ".3g"), f(r["first_break_s"], ".6g"),
                       f(r["predicted_s"], ".6g"), f(r["ramp_ratio"], ".4g"), r["joints_broken"] or "-",
                       f(r["middle_force_ratio"], ".5g"), f(r["cpu_s"])] for r in ref])
    else:
        out += missing("reference.csv")
    out += ["", "### 8.4 Summary: best alpha, the error left, the cost", "",
            "From `fem_SCENE.csv`: each scene's mean energy error (as its table defines it) at the best alpha, "
            "at 0 and at 1; the first break, the same at every alpha, minus the reference's; CPU s per run.", ""]
    body = []
    for scene in FEM_SCENES:
        rows = read(res, f"fem_{scene}.csv")
        rigid = [r for r in rows if r["method"] == "rigid"]
        others = [r for r in rows if r["method"] != "rigid"]
        if not rigid or not others:
            continue
        ref0 = others[0]
        best = min(rigid, key=lambda r: num(r["energy_error"]))
        at = {num(r["alpha"]): r for r in rigid}
        cpus = [num(r["cpu_s"]) for r in rigid]
        dt = [1e3 * (num(r["first_break_s"]) - num(ref0["first_break_s"])) for r in rigid]
        rc = num(ref0["cpu_s"])
        body.append([scene, f(best["alpha"], "g"), f(best["energy_error"]), f(at.get(0.0, {}).get("energy_error")),
                     f(at.get(1.0, {}).get("energy_error")), span(dt, "+.2f"),
                     f"{min(cpus):.2f} to {max(cpus):.2f}", f(rc, ".0f"),
                     f"{rc / max(cpus):,.0f} to {rc / min(cpus):,.0f}"])
    out += table(["scene", "best alpha", "its energy error", "alpha 0 (plain)", "alpha 1",
                  "first break, rigid - reference (ms)", "rigid CPU (s)", "reference CPU (s)", "cost ratio"], body)
    return out


def headlines(res):
    """The quantities Study.Quick checks on its own quick run, as the committed full run has them."""
    out = ["## Headline numbers", "",
           "What Study.Quick checks (docs/accuracy.md, \"Headline numbers\"), as the committed full run "
           "measured it. Study.Quick checks its own quick run, which can differ in the last digits.", ""]
    body = []
    ids = read(res, "identities_double.csv")
    fl = read(res, "identities_float.csv")
    e = [r for r in ids if r["measure"] == "energy" and r["method"] == "energized"]
    ef = [r for r in fl if r["measure"] == "energy" and r["method"] == "energized"]
    if e:
        body.append(["energy identity, rig, energized, exact energy: max per-break error < 1e-9",
                     f(e[0]["error"], ".2g") + (f"; float build {f(ef[0]['error'], '.2g')}" if ef else "")])
    s = [r for r in ids if r["measure"] == "stiffness" and num(r["stiffness"]) == 1e10 and r["substeps"] == "8"
         and r["iterations"] == "2000"]
    if s:
        body.append(["stiffness identity, 1e10 N/m^3, 8 substeps, 2,000 iterations: abs(k measured / k - 1) < 1e-6",
                     f(s[0]["error"], ".2g")])
    sw = [r for r in read(res, "sweeps_double.csv") if r["scene"] == "rig" and r["knob"] == "substeps"]
    if sw:
        sw.sort(key=lambda r: num(r["value"]))
        errs = [num(r["trajectory_error_m"]) for r in sw]
        falls = all(b < a for a, b in zip(errs, errs[1:]))
        body.append(["rig trajectory error falls with every doubling of substeps (mm, "
                     f"{f(sw[0]['value'], 'g')} to {f(sw[-1]['value'], 'g')})",
                     ", ".join(f(e, ".3g", 1e3) for e in errs) + ("" if falls else " (does not fall at every doubling)")])
    me = {(r["scene"], r["method"]): r for r in read(res, "methods.csv")}
    if ("rig", "plain") in me and ("rig", "energized") in me and ("rig", "paper") in me:
        body.append(["rig: plain injects nothing; energized books within 1e-9; the paper's magnitudes off by "
                     "more than 1%", f"{f(me[('rig', 'plain')]['injected_J'], 'g')} J; "
                     f"{f(me[('rig', 'energized')]['books_error'], '.2g')}; "
                     f"{f(me[('rig', 'paper')]['books_error'], '+.3g', 100)}%"])
    st = read(res, "stability.csv")
    ss = [r for r in st if r["map"] == "step_stiffness" and not yes(r["guard_refuses"])]
    if ss:
        cnt = {m: (sum(1 for r in ss if r["method"] == m and r["class"] == "stable"),
                   sum(1 for r in ss if r["method"] == m)) for m in ("energized", "plain")}
        body.append(["step x stiffness: energized stable in at least as many guarded cells as plain",
                     f"{cnt['energized'][0]}/{cnt['energized'][1]} and {cnt['plain'][0]}/{cnt['plain'][1]}"])
    ma = [r for r in st if r["map"] == "mass_alpha"]
    if ma:
        parts = []
        for m in dict.fromkeys(r["method"] for r in ma):
            a, n = stable_where_plain(ma, m)
            parts.append(f"{m} {a} of {n}")
        body.append(["mass x alpha (alpha > 0): energized stable in every cell where plain breaking (energized at "
                     "alpha 0) is; the other methods printed, not checked", "; ".join(parts)])
        a, n = stable_in(ma, "energized+direct", lambda x, y: x >= 100 and y <= 10)
        body.append(["mass x alpha (mass ratio 100 and 1,000, alpha 0 to 10): energized with direct joints stable in "
                     "every cell", f"{a} of {n}"])
        a, n = stable_in(ma, "opposed+auto", lambda x, y: y <= 10)
        body.append(["mass x alpha (alpha 0 to 10): the shipped method and joints (opposed+auto) stable in every "
                     "cell", f"{a} of {n}"])
    sm = {r["shot"]: r for r in read(res, "smallest_summary.csv")}
    if "beam" in sm and "chain" in sm:
        body.append(["smallest model: the beam and the chain as shipped within tolerance of their finest "
                     "models (worst / tol <= 1)", f"beam {f(sm['beam']['shipped_worst_ratio'], '.2g')}, "
                     f"chain {f(sm['chain']['shipped_worst_ratio'], '.2g')}"])
    ref = {r["method"]: r for r in read(res, "reference.csv")}
    if "reference" in ref:
        r = ref["reference"]
        body.append(["continuum reference, the chain: the middle joint's force at the first break over the "
                     "uniform bar's, within 2%", f(r["middle_force_ratio"], ".5g")])
        body.append(["continuum reference, the chain: the first joint's separation as a fraction of the "
                     "quasi-static ramp, 0.75 to 1", f"{f(r['ramp_ratio'], '.3g')} ({f(r['first_break_s'], '.5g')} s "
                     f"against {f(r['predicted_s'], '.5g')} s; the rigid method as shipped, printed: "
                     f"{f(ref.get('rigid', {}).get('first_break_s'), '.5g')} s)"])
    if "reference plate" in ref:
        r = ref["reference plate"]
        dt = num(r["first_break_s"]) - num(r["predicted_s"])
        body.append(["continuum reference, the plate: the first tie breaks within 1 ms after the free fall's "
                     "first contact", f"{f(r['first_break_s'], '.5g')} s, {f(dt, '.2g', 1e3)} ms after the "
                     f"contact at {f(r['predicted_s'], '.5g')} s"])
        if "rigid plate" in ref:
            rp = ref["rigid plate"]
            body.append(["the plate: the rigid method as shipped first breaks within 1 ms of the reference",
                         f"{f(rp['first_break_s'], '.5g')} s, "
                         f"{f(num(rp['first_break_s']) - num(r['first_break_s']), '+.2g', 1e3)} ms"])
    best = []
    for scene in ("beam", "chain", "bunny", "corpus"):
        rigid = [r for r in read(res, f"fem_{scene}.csv") if r["method"] == "rigid"]
        if rigid:
            b = min(rigid, key=lambda r: num(r["energy_error"]))
            best.append(f"{scene} {f(b['alpha'], 'g')} ({f(b['energy_error'])})")
    if best:
        body.append(["the comparison's best-matching alpha (ctest Continuum.BestAlpha.*): the rigid rows run "
                     "again give the committed best alpha, its error within 10%", ", ".join(best)])
    return out + table(["check", "the committed run"], body)


SOURCES = ["identities_double.csv", "identities_float.csv", "speed.csv", "sweeps_double.csv", "sweeps_float.csv",
           "methods.csv", "continuum.csv", "stability.csv", "stability_scenes.csv", "smallest.csv",
           "smallest_summary.csv", "fem_checks.md"] + [f"fem_{s}.{e}" for s in FEM_SCENES for e in ("csv", "md")] + [
           "reference.csv", "seeds.csv"]


def page(res):
    shown = os.path.relpath(res, ROOT) if os.path.abspath(res).startswith(ROOT + os.sep) else res
    have = [s for s in SOURCES if os.path.exists(os.path.join(res, s))]
    lacking = [s for s in SOURCES if s not in have]
    out = ["# Study results", "",
           "<!-- Generated by scripts/study_tables.py from " + shown + "/: do not edit by hand. -->", "",
           "Generated: `make study` writes this page after its runs, and `/usr/bin/python3 scripts/study_tables.py` "
           f"writes it again from the committed files alone. Every figure below comes from these files of {shown}/, "
           "one whole run of the study: " + ", ".join(f"`{s}`" for s in have) + "."
           + (" Not in the committed run: " + ", ".join(f"`{s}`" for s in lacking) + "." if lacking else ""),
           "",
           "`/usr/bin/python3 scripts/study_tables.py --check` (ctest Docs.StudyResults) fails when this page and "
           "those files disagree. What each measure means, the scenes, how to read the tables and what follows "
           "from them: docs/accuracy.md, whose section numbers this page keeps; the charts are docs/images/study-*.png. "
           "Wall and CPU times come from a shared 2-core machine: compare rows of one table, not across runs. "
           "Lengths in mm or m, times in s or ms, energies in J, as each header says.", ""]
    for section in (identities, speed, sweeps, methods, seeds, continuum, stability, smallest, fem, headlines):
        out += section(res) + [""]
    return "\n".join(out).rstrip("\n") + "\n"


def main(argv):
    args = [a for a in argv if not a.startswith("--")]
    flags = [a for a in argv if a.startswith("--")]
    if any(a not in ("--check",) for a in flags) or len(args) > 2:
        print(__doc__, file=sys.stderr)
        return 2
    res = args[0] if args else os.path.join(ROOT, "bench", "results", "study")
    dest = args[1] if len(args) > 1 else os.path.join(ROOT, "docs", "results", "study.md")
    text = page(res)
    if "--check" in flags:
        old = open(dest).read() if os.path.exists(dest) else None
        if old == text:
            return 0
        if old is None:
            print(f"{dest}: missing; run `/usr/bin/python3 scripts/study_tables.py`", file=sys.stderr)
            return 1
        a, b = old.split("\n"), text.split("\n")
        n = next((i for i in range(min(len(a), len(b))) if a[i] != b[i]), min(len(a), len(b)))
        print(f"{dest}:{n + 1}: differs from what the files of {res} make; "
              "run `/usr/bin/python3 scripts/study_tables.py` and commit the page", file=sys.stderr)
        print(f"  page:  {a[n] if n < len(a) else '(end of file)'}", file=sys.stderr)
        print(f"  files: {b[n] if n < len(b) else '(end of file)'}", file=sys.stderr)
        return 1
    os.makedirs(os.path.dirname(os.path.abspath(dest)), exist_ok=True)
    tmp = dest + ".tmp"
    with open(tmp, "w") as fh:
        fh.write(text)
    os.replace(tmp, dest)
    print(f"wrote {dest}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
