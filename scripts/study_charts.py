#!/usr/bin/python3
"""Charts of the accuracy and cost study (docs/accuracy.md) from the CSV files of bench/study.

    /usr/bin/python3 scripts/study_charts.py [RESULTS_DIR] [IMAGES_DIR]

Defaults: bench/results/study and docs/images. Writes study-*.png (small PNGs). The tables of the
same files are scripts/study_tables.py's (docs/results/study.md), whose helpers this uses, so that
a chart's knee and the table's are one computation. Needs Debian's matplotlib (python3-matplotlib).
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402

import study_tables  # noqa: E402  (scripts/, this file's folder)
from study_tables import CLASSES, knee, num, yes  # noqa: E402

RESULTS = sys.argv[1] if len(sys.argv) > 1 else "bench/results/study"
IMAGES = sys.argv[2] if len(sys.argv) > 2 else "docs/images"
DPI = 80


def read(name):
    return study_tables.read(RESULTS, name)


def save(fig, name):
    os.makedirs(IMAGES, exist_ok=True)
    fig.savefig(os.path.join(IMAGES, name), dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    print(f"wrote {os.path.join(IMAGES, name)}", file=sys.stderr)


def row_legend(axes):
    """The handles and labels of the first row of axes, each label once, in order of appearance."""
    handles, labels = [], []
    for ax in axes[0]:
        for h, label in zip(*ax.get_legend_handles_labels()):
            if label not in labels:
                handles.append(h)
                labels.append(label)
    return handles, labels


KNOB_STYLE = {
    "substeps": ("C0", "o"),
    "iterations": ("C1", "s"),
    "constraints_per_side": ("C2", "^"),
    "constraints_per_pair": ("C2", "^"),
    "collision_parts": ("C4", "D"),
    "resolution": ("C5", "v"),
    "rollback": ("C3", "P"),
}
FLOOR_MM = 1e-4  # errors below this are drawn at it (log scale)


def cost_error():
    rows = read("sweeps_double.csv") + read("sweeps_float.csv")
    scenes = [s for s in ["rig", "beam", "plate", "chain", "bunny"] if any(r["scene"] == s for r in rows)]
    if not scenes:
        return
    fig, axes = plt.subplots(1, len(scenes), figsize=(4.2 * len(scenes), 3.6), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        ref = [r for r in rows if r["scene"] == scene and r["knob"] == "reference"]
        for precision in ["double", "float"]:
            sr = [r for r in rows if r["scene"] == scene and r["precision"] == precision and r["knob"] != "reference"]
            for knob in dict.fromkeys(r["knob"] for r in sr):
                kr = [r for r in sr if r["knob"] == knob and not yes(r["refused"])]
                pts = sorted(
                    (num(r["wall_per_sim_s"]), num(r["trajectory_error_m"]) * 1e3, r["value"], yes(r["is_default"]))
                    for r in kr
                )
                if not pts:
                    continue
                colour, marker = KNOB_STYLE.get(knob, ("C7", "x"))
                style = "-" if precision == "double" else ":"
                label = knob.replace("_", " ") + (" (float)" if precision == "float" else "")
                ys = [max(p[1], FLOOR_MM) if math.isfinite(p[1]) else math.nan for p in pts]
                ax.plot([p[0] for p in pts], ys, style, color=colour, marker=marker, ms=4, label=label)
                for p, y in zip(pts, ys):
                    if knob in ("substeps", "iterations", "rollback") or precision == "double":
                        ax.annotate(f"{float(p[2]):g}", (p[0], y), fontsize=6, xytext=(2, 2), textcoords="offset points")
                    if p[3] and precision == "double":
                        ax.plot([p[0]], [y], "*", color="k", ms=11, zorder=5)
                if precision == "double":
                    k = knee(pts)
                    if k:
                        ax.plot([k[0]], [max(k[1], FLOOR_MM)], "o", mfc="none", mec="r", ms=12, mew=1.5, zorder=6)
        if ref:
            ax.axvline(num(ref[0]["wall_per_sim_s"]), color="0.6", lw=0.8, ls="--")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(scene)
        ax.set_xlabel("wall s per simulated s")
        ax.grid(alpha=0.3, which="both", lw=0.4)
    axes[0][0].set_ylabel("mean trajectory error (mm)")
    handles, labels = row_legend(axes)
    if not labels:
        return
    fig.legend(handles, labels, loc="lower center", ncol=min(8, len(labels)), fontsize=8, bbox_to_anchor=(0.5, -0.14))
    fig.suptitle("Cost against error, one knob at a time (star: study default; red ring: knee; dashed: reference)",
                 fontsize=10)
    save(fig, "study-cost-error.png")



def first_break():
    rows = [r for r in read("sweeps_double.csv") if r["knob"] in ("substeps", "iterations") and not yes(r["refused"])]
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    if not scenes:
        return
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.4))
    for ax, knob in zip(axes, ["substeps", "iterations"]):
        for i, scene in enumerate(scenes):
            kr = [r for r in rows if r["scene"] == scene and r["knob"] == knob]
            pts = sorted((num(r["value"]), num(r["first_break_error_s"]) * 1e3) for r in kr)
            pts = [(x, max(y, 1e-2)) for x, y in pts if math.isfinite(y)]
            if pts:
                ax.plot(*zip(*pts), "-o", ms=3, color=f"C{i}", label=scene)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(knob)
        ax.set_ylabel("|first break - reference| (ms)")
        ax.grid(alpha=0.3, which="both", lw=0.4)
    axes[0].legend(fontsize=8)
    fig.suptitle("Time of the first break against the reference (drawn at >= 0.01 ms; missing: no break)", fontsize=10)
    save(fig, "study-first-break.png")


def identities():
    rows = [r for r in read("identities_double.csv") + read("identities_float.csv") if r["measure"] == "stiffness"]
    if not rows:
        return
    stiffs = sorted({r["stiffness"] for r in rows}, key=float)
    fig, axes = plt.subplots(1, len(stiffs), figsize=(4.5 * len(stiffs), 3.4), squeeze=False)
    for ax, k in zip(axes[0], stiffs):
        for precision, style in [("double", "-"), ("float", ":")]:
            for i, sub in enumerate(sorted({r["substeps"] for r in rows}, key=int)):
                kr = [r for r in rows if r["stiffness"] == k and r["substeps"] == sub and r["precision"] == precision]
                pts = sorted((num(r["iterations"]), max(abs(num(r["error"])), 1e-16)) for r in kr)
                pts = [p for p in pts if math.isfinite(p[1])]
                if pts:
                    ax.plot(*zip(*pts), style, marker="o", ms=3, color=f"C{i}", label=f"{sub} substeps, {precision}")
        ax.axhline(1e-6, color="r", lw=0.8, ls="--")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(f"stiffness {float(k):g} N/m^3")
        ax.set_xlabel("solver iterations")
        ax.grid(alpha=0.3, which="both", lw=0.4)
    axes[0][0].set_ylabel("|k measured / k - 1|")
    axes[0][-1].legend(fontsize=7)
    fig.suptitle("Stiffness identity: a bar pulled along its axis by gravity (red: the 1e-6 check)", fontsize=10)
    save(fig, "study-stiffness.png")


COLOURS = ["#4caf50", "#bdbdbd", "#212121", "#e53935", "#fb8c00", "#8e24aa"]


def stability():
    rows = read("stability.csv")
    for m in dict.fromkeys(r["map"] for r in rows):
        mr = [r for r in rows if r["map"] == m]
        methods = list(dict.fromkeys(r["method"] for r in mr))
        xs = sorted({num(r["x"]) for r in mr})
        ys = sorted({num(r["y"]) for r in mr})
        n = len(methods)
        cols = min(n, 4)
        nrows = (n + cols - 1) // cols
        fig, axes = plt.subplots(nrows, cols, figsize=(3.3 * cols, 3.0 * nrows), squeeze=False)
        cmap = ListedColormap(COLOURS)
        for ax in axes.flat[n:]:
            ax.axis("off")
        for ax, method in zip(axes.flat, methods):
            grid = [[math.nan] * len(xs) for _ in ys]
            for r in mr:
                if r["method"] != method:
                    continue
                i, j = ys.index(num(r["y"])), xs.index(num(r["x"]))
                grid[i][j] = CLASSES.index(r["class"])
                if yes(r["guard_refuses"]):
                    ax.plot(j, i, "x", color="k", ms=5, mew=0.8)
            ax.imshow(grid, cmap=cmap, vmin=-0.5, vmax=len(CLASSES) - 0.5, origin="lower", aspect="auto")
            ax.set_xticks(range(len(xs)))
            ax.set_xticklabels([f"{x:.3g}" for x in xs], fontsize=6, rotation=45)
            ax.set_yticks(range(len(ys)))
            ax.set_yticklabels([f"{y:g}" for y in ys], fontsize=6)
            ax.set_title(method, fontsize=9)
            ax.set_xlabel(mr[0]["x_name"], fontsize=7)
            ax.set_ylabel(mr[0]["y_name"], fontsize=7)
        handles = [plt.Rectangle((0, 0), 1, 1, color=c) for c in COLOURS]
        fig.legend(handles, CLASSES, loc="lower center", ncol=len(CLASSES), fontsize=8, bbox_to_anchor=(0.5, -0.04))
        fig.suptitle(f"Stability map '{m}' on the rig (x: the CFM guard refuses; the cell shows the run without it)",
                     fontsize=9)
        fig.tight_layout()
        save(fig, f"study-stability-{m.replace('_', '-')}.png")



def methods():
    rows = read("methods.csv")
    if not rows:
        return
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    names = list(dict.fromkeys(r["method"] for r in rows))
    fig, axes = plt.subplots(1, 4, figsize=(17, 3.6))
    width = 0.8 / len(names)
    for k, name in enumerate(names):
        xs = [i + (k - len(names) / 2 + 0.5) * width for i in range(len(scenes))]
        get = lambda col: [num(next((r.get(col) for r in rows if r["scene"] == s and r["method"] == name), "nan"))
                           for s in scenes]
        walls = get("wall_per_sim_s")
        plain = [num(next(r["wall_per_sim_s"] for r in rows if r["scene"] == s and r["method"] == "plain"))
                 for s in scenes]
        axes[0].bar(xs, [w / p for w, p in zip(walls, plain)], width, label=name, color=f"C{k}")
        axes[1].bar(xs, [b * 100 for b in get("books_error")], width, color=f"C{k}")
        axes[2].bar(xs, [b * 100 for b in get("world_books_error")], width, color=f"C{k}")
        axes[3].bar(xs, [d * 1e3 for d in get("difference_from_plain_m")], width, color=f"C{k}")
    titles = ["wall time relative to plain", "injected - alpha E, % of alpha E\n(in each broken pair's frame)",
              "injected + momentum work - alpha E, % of alpha E\n(in the world's frame)",
              "mean distance from plain (mm)"]
    for ax, t in zip(axes, titles):
        ax.set_xticks(range(len(scenes)))
        ax.set_xticklabels(scenes)
        ax.set_title(t, fontsize=9)
        ax.grid(alpha=0.3, axis="y", lw=0.4)
    for ax in axes[1:3]:
        ax.set_yscale("symlog", linthresh=1)
    axes[3].set_yscale("symlog", linthresh=0.1)
    fig.legend(loc="lower center", ncol=len(names), fontsize=8, bbox_to_anchor=(0.5, -0.08))
    save(fig, "study-methods.png")



def smallest():
    """Section 7: deviation from the finest model / tolerance against cost, one knob at a time."""
    rows = read("smallest.csv")
    summary = {r["shot"]: r for r in read("smallest_summary.csv")}
    shots = [s for s in ["beam", "chain", "plate", "bunny", "bunny_sphere"] if any(r["shot"] == s for r in rows)]
    if not shots:
        return
    fig, axes = plt.subplots(1, len(shots), figsize=(4.0 * len(shots), 3.6), squeeze=False)
    for ax, shot in zip(axes[0], shots):
        sr = [r for r in rows if r["shot"] == shot]
        ref = [r for r in sr if r["role"] == "reference"]
        for knob in dict.fromkeys(r["knob"] for r in sr if r["role"] == "sweep"):
            kr = [r for r in sr if r["role"] == "sweep" and r["knob"] == knob and not yes(r["refused"])]
            pts = [(num(r["cpu_per_sim_s"]), num(r["worst_ratio"]), r["value"]) for r in kr]
            if ref:
                pts.append((num(ref[0]["cpu_per_sim_s"]), 0.0, "finest"))
            pts.sort()
            colour, marker = KNOB_STYLE.get(knob, ("C7", "x"))
            ys = [min(max(p[1], 0.01), 1e3) for p in pts]
            ax.plot([p[0] for p in pts], ys, "-", color=colour, marker=marker, ms=4, label=knob.replace("_", " "))
            for p, y in zip(pts, ys):
                if p[2] != "finest":
                    ax.annotate(p[2], (p[0], y), fontsize=6, xytext=(2, 2), textcoords="offset points")
        for role, mk, colour, label in (("chosen", "*", "r", "chosen"), ("shipped", "D", "k", "shipped")):
            rr = [r for r in sr if r["role"] == role]
            if rr:
                r = rr[-1]
                ax.plot([num(r["cpu_per_sim_s"])], [min(max(num(r["worst_ratio"]), 0.01), 1e3)], mk, color=colour,
                        ms=10 if mk == "*" else 6, mfc="none" if mk == "D" else colour, zorder=6, label=label)
        if ref:
            ax.axvline(num(ref[0]["cpu_per_sim_s"]), color="0.6", lw=0.8, ls="--")
        ax.axhline(1, color="r", lw=0.8, ls=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        m = summary.get(shot, {}).get("measure", "")
        ax.set_title(f"{shot} ({m})", fontsize=9)
        ax.set_xlabel("CPU s per simulated s")
        ax.grid(alpha=0.3, which="both", lw=0.4)
    axes[0][0].set_ylabel("deviation from finest / tolerance")
    handles, labels = row_legend(axes)
    fig.legend(handles, labels, loc="lower center", ncol=min(8, len(labels)), fontsize=8, bbox_to_anchor=(0.5, -0.12))
    fig.suptitle("The smallest model that serves: one knob at a time down from the finest (dotted: tolerance; "
                 "dashed: the finest model's cost)", fontsize=10)
    save(fig, "study-smallest.png")



def continuum():
    """The rigid method at each alpha against the continuum reference (fem_compare's fem_SCENE.csv):
    CPU seconds against the mean energy error, one panel per scene, the reference's own point at
    the error axis's floor (its error is 0 by definition)."""
    scenes = [s for s in ["beam", "chain", "plate", "bunny", "corpus"] if read(f"fem_{s}.csv")]
    if not scenes:
        return
    fig, axes = plt.subplots(1, len(scenes), figsize=(3.4 * len(scenes), 3.4), squeeze=False)
    floor = 1e-3
    for ax, scene in zip(axes[0], scenes):
        rows = read(f"fem_{scene}.csv")
        rigid = [r for r in rows if r["method"] == "rigid"]
        ref = [r for r in rows if r["method"] != "rigid"]
        xs = [num(r["cpu_s"]) for r in rigid]
        ys = [max(num(r["energy_error"]), floor) for r in rigid]
        ax.plot(xs, ys, "o", color="C0", ms=5, label="rigid, energized")
        best = min(rigid, key=lambda r: num(r["energy_error"]))
        for r, x, y in zip(rigid, xs, ys):
            ax.annotate(f"{num(r['alpha']):g}", (x, y), fontsize=7, xytext=(3, 2), textcoords="offset points")
            if r is best:
                ax.plot([x], [y], "o", mfc="none", mec="r", ms=11, mew=1.5)
        # The reference is the first non-rigid row; rows after it are coarser meshes, drawn at their
        # error against it (the mesh's own error).
        for i, r in enumerate(ref):
            if i == 0:
                ax.plot([num(r["cpu_s"])], [floor], "s", color="k", ms=7, label="reference (FEM; error 0)")
            else:
                y = max(num(r["energy_error"]), floor)
                ax.plot([num(r["cpu_s"])], [y], "s", color="0.6", ms=6, label="reference, a coarser mesh")
                ax.annotate(r["method"].split(";")[0].replace("fem ", ""), (num(r["cpu_s"]), y), fontsize=7,
                            xytext=(3, 2), textcoords="offset points")
        ax.set_xscale("log")
        ax.set_yscale("log")
        allx = xs + [num(r["cpu_s"]) for r in ref]
        ax.set_xlim(min(allx) / 3, max(allx) * 3)
        ax.set_ylim(floor / 2, max(ys + [1.0]) * 3)
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_title(scene)
        ax.set_xlabel("CPU s per run")
        ax.grid(alpha=0.3, which="both", lw=0.4)
    axes[0][0].set_ylabel("mean energy error against the reference")
    handles, labels = row_legend(axes)
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=8, bbox_to_anchor=(0.5, -0.1))
    fig.suptitle("The rigid method against the continuum reference: cost and error per alpha (red ring: best alpha)",
                 fontsize=10)
    save(fig, "study-continuum.png")



if __name__ == "__main__":
    cost_error()
    first_break()
    identities()
    stability()
    methods()
    smallest()
    continuum()
