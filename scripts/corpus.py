#!/usr/bin/python3
"""Pre-scores a corpus of real meshes with the defaults and tabulates what prescore did.

The corpus is what Debian ships: CGAL's data set (libcgal-demo: data.tar.gz, meshes/*.off),
glmark2-data's models and assimp-testmodels (every file whose extension assimp reads).

  scripts/corpus.py SHATTER WORKDIR --all [--table docs/corpus.md]   the whole corpus (make corpus)
  scripts/corpus.py SHATTER WORKDIR --sample tests/corpus/sample.tsv  a fixed sample (make test)
  scripts/corpus.py SHATTER WORKDIR --all --run [--table docs/corpus-run.md]
                                     `shatter run MESH` on every mesh (make corpus-run)

Each mesh runs as `shatter prescore MESH -o WORKDIR/NAME.model` with a time limit. A mesh passes
when it pre-scores (exit 0) or is refused with exit code 3 for a reason that makes it no solid
mesh (empty, no area, no triangles, unreadable); a crash (any other exit code) or a run past the
limit fails. --sample also checks each file's expected exit code and message. Prints one line per
mesh and a summary; exits 1 when a mesh failed.

With --run each mesh runs as `shatter run MESH -o WORKDIR/runs/NAME` (the default shot: prescore,
simulate, render, encode, export, report) instead; it passes when it makes a movie, or is refused as
above. The table adds what the run measured: breaks, fragments, the energy books (stored, injected,
their ratio to alpha x stored) and the camera (pieces in view, stillness at the end).
"""
import argparse
import concurrent.futures
import glob
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tarfile
import threading
import time

LIMIT_SECONDS = 20  # the target for one prescore on this project's 2-core machines (measured, not enforced)
KILL_SECONDS = 180  # a prescore still running then has no end of its own: it fails
RUN_KILL_SECONDS = 900  # the same for a whole `shatter run`
CGAL_DATA = "/usr/share/doc/libcgal-dev/data.tar.gz"
GLMARK2 = "/usr/share/glmark2/models"
ASSIMP = "/usr/share/assimp/models"
ASSIMP_EXTENSIONS = set(
    "3d 3ds 3mf ac ac3d acc amf ase ask b3d blend bsp bvh cob csm dae dxf enff fbx glb gltf hmp ifc ifczip iqm irr "
    "irrmesh lwo lws lxo md2 md3 md5mesh mdc mdl mesh ms3d ndo nff obj off ogex pk3 ply pmx q3o q3s raw scn sib smd "
    "stl stp ter uc x x3d x3db xgl zae zgl".split())
# Refusals that say the file holds no solid mesh (or none a reader can read): not counted
# against the pass rate, but each must come with exit code 3 and its message.
NOT_SOLID = re.compile(r"no triangles|no area|is empty|cannot read mesh|corrupt mesh|crashed on this file|"
                       r"did not finish within|PLY header|non-finite coordinate|outside 1e-09")


def cgal_meshes(workdir):
    out = os.path.join(workdir, "cgal")
    if not os.path.isdir(out):
        with tarfile.open(CGAL_DATA) as tar:
            members = [m for m in tar.getmembers() if re.search(r"/meshes/[^/]+\.off$", m.name) and m.isfile()]
            tar.extractall(out, members=members)
    found = []
    for root, _, files in os.walk(out):
        found += [os.path.join(root, f) for f in files if f.endswith(".off")]
    return sorted(found)


def corpus(workdir):
    files = cgal_meshes(workdir)
    files += sorted(os.path.join(GLMARK2, f) for f in os.listdir(GLMARK2))
    for root, _, names in os.walk(ASSIMP):
        files += [os.path.join(root, n) for n in names if n.rsplit(".", 1)[-1].lower() in ASSIMP_EXTENSIONS]
    return sorted(set(files), key=lambda f: (not f.startswith(workdir), f))


def prescore(shatter, workdir, mesh):
    name = re.sub(r"[^A-Za-z0-9._-]", "_", os.path.relpath(mesh, "/"))
    model = os.path.join(workdir, "models", name + ".model")
    os.makedirs(os.path.dirname(model), exist_ok=True)
    start = time.monotonic()
    try:
        p = subprocess.run([shatter, "prescore", mesh, "-o", model], capture_output=True, text=True,
                           timeout=KILL_SECONDS)
        code, out, err = p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired:
        code, out, err = "timeout", "", ""
    seconds = time.monotonic() - start
    auto = [m.group(1) for m in re.finditer(r"auto: (.*?) \(", err)]
    m = re.search(r"prescore: (\d+) pieces, (\d+) tets", out)
    error = ""
    for line in err.splitlines():
        if line.startswith("error:"):
            error = line[len("error:"):].strip().replace(mesh + ": ", "")
    return {"file": mesh, "code": code, "seconds": seconds, "pieces": m.group(1) if m else "",
            "tets": m.group(2) if m else "", "auto": auto, "error": error}


def run_warnings(summary):
    """The warnings prescore and simulate kept in their files (summary.json's model.warnings and
    simulation.warnings)."""
    return summary["model"].get("warnings", []) + summary["simulation"].get("warnings", [])


def run_dir(workdir, mesh):
    return os.path.join(workdir, "runs", re.sub(r"[^A-Za-z0-9._-]", "_", os.path.relpath(mesh, "/")))


def run_mesh(shatter, workdir, mesh):
    """`shatter run MESH` into WORKDIR/runs/NAME; keeps summary.json, run.log, the movie and the report."""
    out = run_dir(workdir, mesh)
    os.makedirs(os.path.dirname(out), exist_ok=True)
    start = time.monotonic()
    try:
        p = subprocess.run([shatter, "run", mesh, "-o", out], capture_output=True, text=True, timeout=RUN_KILL_SECONDS)
        code, err = p.returncode, p.stderr
    except subprocess.TimeoutExpired:
        code, err = "timeout", ""
    seconds = time.monotonic() - start
    r = {"file": mesh, "code": code, "seconds": seconds, "pieces": "", "tets": "", "error": "",
         "auto": [m.group(1) for m in re.finditer(r"auto: (.*?) \(", err)]}
    for line in err.splitlines():
        if line.startswith("error:"):
            r["error"] = line[len("error:"):].strip().replace(mesh + ": ", "")
    m = re.search(r"camera \S+: (\d+)% of the pieces in view in the first frame, at least (\d+)% in every frame "
                  r"\(frame \d+\), ([0-9.]+) s still at the end", err)
    if m:
        r["in_view_first"], r["in_view_least"], r["still_s"] = int(m.group(1)), int(m.group(2)), float(m.group(3))
    try:
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        sim = summary["simulation"]
        r.update(pieces=summary["model"]["pieces"], tets=summary["model"]["tets"], alpha=summary["alpha"],
                 breaks=sim["breaks"], fragments=sim["fragments"], stored=sim["stored_energy_J"],
                 injected=sim["injected_energy_J"], held=sim.get("held_energy_J", 0.0), frames=sim["frames"],
                 movie=os.path.exists(os.path.join(out, summary["files"].get("mp4", "-"))),
                 warnings=run_warnings(summary))
    except (OSError, KeyError, ValueError):
        r["movie"] = False
    shutil.rmtree(os.path.join(out, "frames"), ignore_errors=True)  # the movie keeps them
    return r


def verdict(r):
    """'ok', 'refused' (no solid mesh, with its reason) or 'FAIL: why'."""
    if r["code"] == "timeout":
        return "FAIL: still running after %d s" % (RUN_KILL_SECONDS if "movie" in r else KILL_SECONDS)
    if r["code"] == 0:
        return "ok" if r.get("movie", True) else "FAIL: no movie"
    if r["code"] == 3 and NOT_SOLID.search(r["error"]):
        return "refused"
    if r["code"] == 3:
        return "FAIL: refused a solid mesh"
    return "FAIL: exit %s" % r["code"]


def short(text, n=90):
    text = re.sub(r"\s*\(fix:.*$", "", text)
    return text if len(text) <= n else text[:n - 3] + "..."


def write_table(results, path, workdir):
    ok = sum(verdict(r) == "ok" for r in results)
    refused = sum(verdict(r) == "refused" for r in results)
    failed = [r for r in results if verdict(r).startswith("FAIL")]
    solid = ok + len(failed)
    lines = [
        "# The mesh corpus",
        "",
        "Every mesh Debian ships in CGAL's data set (libcgal-demo), glmark2-data and assimp-testmodels (each file "
        "whose extension assimp reads), pre-scored with the defaults: `make corpus` "
        "(scripts/corpus.py; a fixed sample runs in `make test`). A file passes when it pre-scores, or is refused "
        "with exit code 3 for a reason that makes it no solid mesh (empty, no area, no triangles, unreadable); a "
        "crash, a refused solid mesh or a run that does not end by itself (killed after %d s) fails. The target "
        "for one prescore is %d s." % (KILL_SECONDS, LIMIT_SECONDS),
        "",
        "| | files |",
        "| --- | --- |",
        "| pre-scored | %d |" % ok,
        "| refused: no solid mesh | %d |" % refused,
        "| failed | %d |" % len(failed),
        "| solid meshes pre-scored | %d of %d (%.1f%%) |" % (ok, solid, 100.0 * ok / max(solid, 1)),
        "| longer than %d s | %d (longest %.1f s) |" % (LIMIT_SECONDS, sum(r["seconds"] > LIMIT_SECONDS for r in results),
                                                 max(r["seconds"] for r in results)),
        "",
        "`what prescore did` lists its automatic choices (prescore/adapt.h): `size` (a file without units "
        "made 0.3 m long), `repair` (alpha wrap), `resolution` (raised where Mesh_3 lost thin parts), "
        "`thicken` (walls given a thickness), `slivers` (small tet clusters joined to their pieces), `pieces` "
        "(raised to the number of separate bodies), `render surfaces` (drawn with the input's own triangles "
        "where the tets came from a wrap, prescore/render_surface.h). Times are wall times on a shared 2-core "
        "machine, with "
        "whatever else ran beside them.",
        "",
        "| file | format | result | what prescore did | pieces | tets | time (s) |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    for r in results:
        f = r["file"]
        shown = os.path.relpath(f, workdir) if f.startswith(workdir) else f
        fmt = f.rsplit(".", 1)[-1].lower()
        result = verdict(r)
        if result != "ok":
            result += ": " + short(r["error"]) if r["error"] else ""
        auto = "; ".join(re.sub(r" \(.*", "", a) for a in r["auto"]) or "-"
        lines.append("| %s | %s | %s | %s | %s | %s | %.1f |" % (shown.replace("|", "\\|"), fmt, result.replace("|", "\\|"),
                                                            auto.replace("|", "\\|"), r["pieces"], r["tets"], r["seconds"]))
    with open(path + ".tmp", "w") as out:
        out.write("\n".join(lines) + "\n")
    os.replace(path + ".tmp", path)


def books_ratio(r):
    """(injected + held) / (alpha x stored): a break's alpha E is given back as kinetic energy, or held
    in a crack its joints keep closed until a later break opens it (docs/physics.md section 4)."""
    return (r["injected"] + r.get("held", 0.0)) / (r["alpha"] * r["stored"])


def held_J(r):
    """The energy a run ends with held in cracks, 0 when it is round-off (within 1e-9 of alpha x
    stored, as the run summary's books line)."""
    held = r.get("held", 0.0)
    return held if abs(held) > 1e-9 * r["alpha"] * r["stored"] else 0.0


def run_joints(out):
    """The joint solve a run used ("direct" or "iterative": its trajectory's settings, with auto
    resolved) and the energy its breaking joints held by their stretch (the energy CSV's last
    removed_J); (None, None) when the files are not there."""
    joints = removed = None
    try:
        traj = glob.glob(os.path.join(out, "*.traj"))[0]
        with open(traj, "rb") as f:
            head = f.read(1 << 20)
        at = 16 + 4 + struct.unpack_from("<I", head, 16)[0]  # past the magic, version, mark and producer
        settings = json.loads(head[at + 4:at + 4 + struct.unpack_from("<I", head, at)[0]])
        joints = settings.get("simulate", {}).get("joints")
        for choice in settings.get("auto", []):
            if choice.get("what", "").startswith("[simulate] joints = "):
                joints = choice["what"].split('"')[1]
        with open(glob.glob(os.path.join(out, "*.energy.csv"))[0]) as f:
            rows = f.read().split("\n")
        header = rows[0].split(",")
        last = [r for r in rows if r][-1].split(",")
        removed = float(last[header.index("removed_J")])
    except (OSError, IndexError, ValueError, struct.error):
        pass
    return joints, removed


def write_run_table(results, path, workdir):
    ok = [r for r in results if verdict(r) == "ok"]
    for r in ok:  # a journal written before runs kept their warnings: read them from the run's summary
        if "warnings" not in r:
            try:
                with open(os.path.join(run_dir(workdir, r["file"]), "summary.json")) as f:
                    r["warnings"] = run_warnings(json.load(f))
            except (OSError, KeyError, ValueError):
                r["warnings"] = []
    for r in ok:
        r["joints"], r["removed"] = run_joints(run_dir(workdir, r["file"]))
    stretch = sorted(r["removed"] / r["stored"] for r in ok if r["removed"] is not None and r["stored"] > 0)
    failed = [r for r in results if verdict(r).startswith("FAIL")]
    ratios = [books_ratio(r) for r in ok if r["alpha"] > 0 and r["stored"] > 0]
    seen = [r for r in ok if "in_view_first" in r]
    lines = [
        "# The mesh corpus, run",
        "",
        "`shatter run MESH` (the default shot: a 1.5 m drop onto the ground, the defaults of assets/bunny.toml) on "
        "every mesh of the corpus (docs/corpus.md): `make corpus-run` (scripts/corpus.py --run). A file passes when "
        "the run makes a movie, or is refused with exit code 3 as no solid mesh; anything else, or a run still going "
        "after %d s, fails. Times are wall times of the whole job (prescore, simulate, render, encode, .glb, report) "
        "on a shared 2-core machine." % RUN_KILL_SECONDS,
        "",
        "| | |",
        "| --- | --- |",
        "| movies made | %d |" % len(ok),
        "| refused: no solid mesh | %d |" % sum(verdict(r) == "refused" for r in results),
        "| failed | %d |" % len(failed),
        "| job time | median %.1f s, longest %.1f s |" % (sorted(r["seconds"] for r in ok)[len(ok) // 2] if ok else 0,
                                                       max((r["seconds"] for r in ok), default=0)),
        "| runs with breaks | %d |" % sum(r["breaks"] > 0 for r in ok),
        "| joints solved directly (the default shot's `joints = \"direct\"`) | %d |" % sum(r["joints"] == "direct" for r in ok),
        "| what the breaking joints held by their stretch, over what their forces stored | median %.3g; within 10%% in %d "
        "runs, over twice in %d, of %d |" % (stretch[len(stretch) // 2] if stretch else 0,
                                            sum(abs(x - 1) <= 0.1 for x in stretch), sum(x > 2 for x in stretch),
                                            len(stretch)),
        "| (injected + held) / (alpha x stored) | %.4g to %.4g |" % (min(ratios, default=0), max(ratios, default=0)),
        "| runs ending with energy held in cracks not yet opened | %d (%.0f%% of alpha x stored at most) |"
        % (sum(held_J(r) > 0 for r in ok),
           100 * max((r.get("held", 0) / (r["alpha"] * r["stored"]) for r in ok if r["alpha"] > 0 and r["stored"] > 0),
                     default=0)),
        "| runs with negative injected energy | %d |" % sum(r["injected"] < 0 for r in ok),
        "| runs with warnings (summary.json: model.warnings, simulation.warnings) | %d |" % sum(bool(r["warnings"]) for r in ok),
        "| every piece in view in the first frame | %d of %d |" % (sum(r["in_view_first"] == 100 for r in seen), len(seen)),
        "| at least 90%% of the pieces in view in every frame | %d of %d |" % (sum(r["in_view_least"] >= 90 for r in seen),
                                                                              len(seen)),
        "| at most 1 s still at the end | %d of %d |" % (sum(r["still_s"] <= 1.0 for r in seen), len(seen)),
        "",
        "| file | result | pieces | breaks | fragments | stored (J) | (injected + held) / (alpha x stored) | held (J) "
        "| in view: first, least (%) "
        "| still at end (s) | warnings | time (s) |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for r in results:
        f = r["file"]
        shown = (os.path.relpath(f, workdir) if f.startswith(workdir) else f).replace("|", "\\|")
        result = verdict(r)
        if result != "ok":
            lines.append("| %s | %s | | | | | | | | | | %.1f |" % (
                shown, (result + (": " + short(r["error"]) if r["error"] else "")).replace("|", "\\|"), r["seconds"]))
            continue
        ratio = "%.4f" % books_ratio(r) if r["alpha"] > 0 and r["stored"] > 0 else "-"
        view = "%d, %d" % (r["in_view_first"], r["in_view_least"]) if "in_view_first" in r else "-"
        still = "%.2f" % r["still_s"] if "still_s" in r else "-"
        lines.append("| %s | ok | %s | %d | %d | %.3g | %s | %.3g | %s | %s | %s | %.1f |" % (
            shown, r["pieces"], r["breaks"], r["fragments"], r["stored"], ratio, held_J(r), view, still,
            "; ".join(short(w, 200) for w in r["warnings"]).replace("|", "\\|").replace("\n", " ") or "-", r["seconds"]))
    with open(path + ".tmp", "w") as out:
        out.write("\n".join(lines) + "\n")
    os.replace(path + ".tmp", path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("shatter")
    ap.add_argument("workdir")
    ap.add_argument("--all", action="store_true", help="the whole corpus")
    ap.add_argument("--sample", help="a TSV of FILE, EXPECTED EXIT CODE, TEXT THE MESSAGE CONTAINS")
    ap.add_argument("--table", help="write the Markdown table here")
    ap.add_argument("--run", action="store_true", help="`shatter run MESH` instead of `shatter prescore MESH`")
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args()
    workdir = os.path.abspath(args.workdir)
    os.makedirs(workdir, exist_ok=True)
    expected = {}
    if args.sample:
        cgal_meshes(workdir)
        for line in open(args.sample):
            if line.startswith("#") or not line.strip():
                continue
            f, code, text = (line.rstrip("\n").split("\t") + ["", ""])[:3]
            f = f.replace("{cgal}", os.path.join(workdir, "cgal", "data", "meshes"))
            f = f.replace("{source}", os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
            expected[f] = (int(code), text)
        files = list(expected)
    else:
        files = corpus(workdir)
    # Each result is appended to WORKDIR/results.jsonl as it comes, so that an interrupted --all
    # run resumes where it stopped (results of another shatter binary are not reused).
    journal = os.path.join(workdir, "runs.jsonl" if args.run else "results.jsonl")
    stamp = "%s %d" % (os.path.realpath(args.shatter), int(os.path.getmtime(args.shatter)))
    done = {}
    if args.all and os.path.exists(journal):
        for line in open(journal):
            r = json.loads(line)
            if r.get("shatter") == stamp:
                done[r["file"]] = r
    lock = threading.Lock()

    def run(f):
        if f in done:
            return done[f]
        r = (run_mesh if args.run else prescore)(args.shatter, workdir, f)
        r["shatter"] = stamp
        with lock, open(journal, "a") as out:
            out.write(json.dumps(r) + "\n")
        return r

    with concurrent.futures.ThreadPoolExecutor(args.workers) as pool:
        results = list(pool.map(run, files))
    failures = 0
    for r in results:
        v = verdict(r)
        if r["file"] in expected:
            code, text = expected[r["file"]]
            if r["code"] != code or text not in r["error"] or v.startswith("FAIL"):
                v = "FAIL: expected exit %d%s" % (code, " with '%s'" % text if text else "")
        failures += v.startswith("FAIL")
        print("%-7s %5.1fs %s: %s %s" % (v.split(":")[0], r["seconds"], r["file"], "; ".join(r["auto"]),
                                         short(r["error"], 200) if r["error"] else "%s pieces, %s tets" % (r["pieces"], r["tets"])))
    ok = sum(verdict(r) == "ok" for r in results)
    print("%d passed, %d failed" % (len(results) - failures, failures))
    print("corpus: %d meshes, %d pre-scored, %d refused (no solid mesh), %d failed" %
          (len(results), ok, sum(verdict(r) == "refused" for r in results), failures))
    if args.run:
        ratios = [books_ratio(r) for r in results if verdict(r) == "ok" and r["alpha"] > 0 and r["stored"] > 0]
        print("runs: %d movies; (injected + held) / (alpha x stored) from %.4g to %.4g; %d with negative injected energy" %
              (sum(verdict(r) == "ok" for r in results), min(ratios, default=0), max(ratios, default=0),
               sum(r.get("injected", 0) < 0 for r in results)))
    if args.table:
        (write_run_table if args.run else write_table)(results, args.table, workdir)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
