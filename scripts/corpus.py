#!/usr/bin/python3
"""Pre-scores a corpus of real meshes with the defaults and tabulates what prescore did.

The corpus is what Debian ships: CGAL's data set (libcgal-demo: data.tar.gz, meshes/*.off),
glmark2-data's models and assimp-testmodels (every file whose extension assimp reads).

  scripts/corpus.py SHATTER WORKDIR --all --table docs/results/corpus.md   the whole corpus (make corpus)
  scripts/corpus.py SHATTER WORKDIR --sample tests/corpus/sample.tsv       a fixed sample (make test)
  scripts/corpus.py SHATTER WORKDIR --all --run --table docs/results/corpus-run.md
                                     `shatter run MESH` on every mesh (make corpus-run)
  scripts/corpus.py --render-only PAGE...   write each page again from its record (PAGE's .tsv)
  scripts/corpus.py --check PAGE...         exit 1 when a page differs from what its record gives

Each mesh runs as `shatter prescore MESH -o WORKDIR/NAME.model` with a time limit. A mesh passes
when it pre-scores (exit 0) or is refused with exit code 3 for a reason that makes it no solid
mesh (empty, no area, no triangles, unreadable); a crash (any other exit code) or a run past the
limit fails. --sample also checks each file's expected exit code and message. Prints one line per
mesh and a summary; exits 1 when a mesh failed.

With --run each mesh runs as `shatter run MESH -o WORKDIR/runs/NAME` (the default shot: prescore,
simulate, render, encode, export, report) instead; it passes when it makes a movie, or is refused as
above. The table adds what the run measured: breaks, fragments, the energy books (stored, injected,
their ratio to alpha x stored) and the camera (pieces in view, stillness at the end).

--table writes the run's record beside the page (docs/results/corpus.tsv, corpus-run.tsv) and makes the
page from the record alone (scripts/corpus_pages.py), so that a page can be made again, and checked,
without running the corpus.
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

sys.dont_write_bytecode = True  # no __pycache__ in the source folder from a test
import corpus_pages  # noqa: E402
from corpus_pages import KILL_SECONDS, RUN_KILL_SECONDS, short, verdict

CGAL_DATA = "/usr/share/doc/libcgal-dev/data.tar.gz"
GLMARK2 = "/usr/share/glmark2/models"
ASSIMP = "/usr/share/assimp/models"
ASSIMP_EXTENSIONS = set(
    "3d 3ds 3mf ac ac3d acc amf ase ask b3d blend bsp bvh cob csm dae dxf enff fbx glb gltf hmp ifc ifczip iqm irr "
    "irrmesh lwo lws lxo md2 md3 md5mesh mdc mdl mesh ms3d ndo nff obj off ogex pk3 ply pmx q3o q3s raw scn sib smd "
    "stl stp ter uc x x3d x3db xgl zae zgl".split())


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


def books_ratio(r):
    """(injected + held) / (alpha x stored): a break's alpha E is given back as kinetic energy, or held
    in a crack its joints keep closed until a later break opens it (docs/physics.md section 4)."""
    return (r["injected"] + r.get("held", 0.0)) / (r["alpha"] * r["stored"])


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


def shown_file(workdir, f):
    return os.path.relpath(f, workdir) if f.startswith(workdir) else f


def prescore_record(results, workdir):
    """The record's rows (corpus_pages.PRESCORE_FIELDS) of a prescore run."""
    return [{"file": shown_file(workdir, r["file"]), "code": r["code"], "seconds": r["seconds"], "pieces": r["pieces"],
             "tets": r["tets"], "auto": "; ".join(re.sub(r" \(.*", "", a) for a in r["auto"]), "error": r["error"]}
            for r in results]


def run_record(results, workdir):
    """The record's rows (corpus_pages.RUN_FIELDS) of a `shatter run` of each mesh; reads what the
    journal does not keep (the joint solve, the joints' stretch) from each run's files."""
    rows = []
    for r in results:
        row = {"file": shown_file(workdir, r["file"]), "code": r["code"], "seconds": r["seconds"],
               "movie": r.get("movie", False), "error": r["error"], "pieces": r["pieces"]}
        if verdict(r) == "ok":
            out = run_dir(workdir, r["file"])
            warnings = r.get("warnings")
            if warnings is None:  # a journal written before runs kept their warnings: read them from the run's summary
                try:
                    with open(os.path.join(out, "summary.json")) as f:
                        warnings = run_warnings(json.load(f))
                except (OSError, KeyError, ValueError):
                    warnings = []
            joints, removed = run_joints(out)
            row.update(alpha=r["alpha"], breaks=r["breaks"], fragments=r["fragments"], stored_J=r["stored"],
                       injected_J=r["injected"], held_J=r.get("held", 0.0),
                       books=books_ratio(r) if r["alpha"] > 0 and r["stored"] > 0 else None,
                       in_view_first=r.get("in_view_first"), in_view_least=r.get("in_view_least"),
                       still_s=r.get("still_s"), joints=joints,
                       stretch=removed / r["stored"] if removed is not None and r["stored"] > 0 else None,
                       warnings="; ".join(short(w, 200) for w in warnings))
        rows.append(row)
    return rows


def pages(args):
    """--render-only and --check: the pages from their records, no run."""
    failed = 0
    for page in args.render_only or []:
        corpus_pages.write_atomic(page, corpus_pages.render(page))
        print("%s: written from %s" % (page, corpus_pages.record_path(page)))
    for page in args.check or []:
        failed += corpus_pages.check(page)
    return 1 if failed else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("shatter", nargs="?")
    ap.add_argument("workdir", nargs="?")
    ap.add_argument("--all", action="store_true", help="the whole corpus")
    ap.add_argument("--sample", help="a TSV of FILE, EXPECTED EXIT CODE, TEXT THE MESSAGE CONTAINS")
    ap.add_argument("--table", metavar="PAGE", help="write the page here, and its record beside it (PAGE's .tsv)")
    ap.add_argument("--run", action="store_true", help="`shatter run MESH` instead of `shatter prescore MESH`")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--render-only", nargs="+", metavar="PAGE", help="write each PAGE again from its record; runs nothing")
    ap.add_argument("--check", nargs="+", metavar="PAGE", help="exit 1 when a PAGE differs from what its record gives")
    args = ap.parse_args()
    if args.render_only or args.check:
        return pages(args)
    if not args.shatter or not args.workdir:
        ap.error("SHATTER and WORKDIR are needed to run the corpus")
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
        corpus_pages.write_record((run_record if args.run else prescore_record)(results, workdir), args.table, args.run)
        corpus_pages.write_atomic(args.table, corpus_pages.render(args.table))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
