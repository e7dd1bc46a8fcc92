"""The corpus pages (docs/results/corpus.md, docs/results/corpus-run.md) and the records they are made from.

A whole-corpus run (scripts/corpus.py --all --table PAGE) writes its record beside the page, PAGE with
.tsv for .md: one line per file with what the run measured, the fields of PRESCORE_FIELDS or
RUN_FIELDS, tab-separated under a header line, floats to six significant digits, an empty cell where
the run measured nothing. The page is then made from the record alone (render), so that
`scripts/corpus.py --render-only PAGE` writes it again after a change to this file, and
`scripts/corpus.py --check PAGE` (a ctest test) fails when a page and its record disagree.

The pass rules live here too (verdict), since a row's result is judged from its record.
"""
import os
import re

LIMIT_SECONDS = 20  # the target for one prescore on this project's 2-core machines (measured, not enforced)
KILL_SECONDS = 180  # a prescore still running then has no end of its own: it fails
RUN_KILL_SECONDS = 900  # the same for a whole `shatter run`
# Refusals that say the file holds no solid mesh (or none a reader can read): not counted
# against the pass rate, but each must come with exit code 3 and its message.
NOT_SOLID = re.compile(r"no triangles|no area|is empty|cannot read mesh|corrupt mesh|crashed on this file|"
                       r"did not finish within|PLY header|non-finite coordinate|outside 1e-09")


def exit_code(text):
    return int(text) if re.fullmatch(r"-?\d+", text) else text  # "timeout" for a run that was killed


def text(cell):
    return cell


def optional(kind):
    return lambda cell: kind(cell) if cell != "" else None


# Each field of a record and how its cell reads back. file: as the page shows it (relative to the
# corpus folder when extracted there); code: the exit code or "timeout"; seconds: wall time;
# auto: prescore's automatic choices, "; "-separated; error: the last "error:" line, file name cut.
PRESCORE_FIELDS = [("file", text), ("code", exit_code), ("seconds", float), ("pieces", text), ("tets", text),
                   ("auto", text), ("error", text)]
# movie: 1 when the run made its movie; stored_J, injected_J, held_J: the summary's energy books,
# alpha its alpha; books: (injected + held) / (alpha x stored); in_view_first, in_view_least,
# still_s: the camera line of run.log; joints: the joint solve the run used; stretch: what the
# breaking joints held by their stretch over stored; warnings: summary.json's model.warnings and
# simulation.warnings, each cut to 200 characters, "; "-separated.
RUN_FIELDS = [("file", text), ("code", exit_code), ("seconds", float), ("movie", lambda c: c == "1"),
              ("pieces", text), ("alpha", optional(float)), ("breaks", optional(int)), ("fragments", optional(int)),
              ("stored_J", optional(float)), ("injected_J", optional(float)), ("held_J", optional(float)),
              ("books", optional(float)), ("in_view_first", optional(int)), ("in_view_least", optional(int)),
              ("still_s", optional(float)), ("joints", optional(text)), ("stretch", optional(float)),
              ("warnings", text), ("error", text)]


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


def record_path(page):
    return re.sub(r"\.md$", "", page) + ".tsv"


def cell(value):
    if value is None:
        return ""
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, float):
        return "%.6g" % value
    return re.sub(r"\s*[\t\r\n]\s*", " ", str(value))


def write_record(rows, page, run):
    fields = [name for name, _ in (RUN_FIELDS if run else PRESCORE_FIELDS)]
    lines = ["# scripts/corpus.py's record of %s; fields: scripts/corpus_pages.py" % os.path.basename(page),
             "\t".join(fields)]
    lines += ["\t".join(cell(r.get(name)) for name in fields) for r in rows]
    write_atomic(record_path(page), "\n".join(lines) + "\n")


def read_record(page):
    """(run, rows): whether the record is of `shatter run`, and its rows as dicts of typed values."""
    with open(record_path(page)) as f:
        lines = [line.rstrip("\n") for line in f if not line.startswith("#") and line.strip()]
    names = lines[0].split("\t")
    run = names == [name for name, _ in RUN_FIELDS]
    fields = RUN_FIELDS if run else PRESCORE_FIELDS
    if names != [name for name, _ in fields]:
        raise SystemExit("%s: the header is neither the prescore nor the run record's (scripts/corpus_pages.py)"
                         % record_path(page))
    rows = []
    for number, line in enumerate(lines[1:], 2):
        cells = line.split("\t")
        if len(cells) != len(fields):
            raise SystemExit("%s: a row with %d fields, not %d: %s" % (record_path(page), len(cells), len(fields), line))
        rows.append({name: read(c) for (name, read), c in zip(fields, cells)})
    return run, rows


def write_atomic(path, content):
    with open(path + ".tmp", "w") as out:
        out.write(content)
    os.replace(path + ".tmp", path)


def escape(text):
    return text.replace("|", "\\|")


def shown(page):
    """PAGE as the page names itself: from the source folder when inside it (the same text wherever the
    command runs)."""
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    path = os.path.relpath(os.path.abspath(page), root)
    return page if path.startswith("..") else path


def made_by(page, command):
    page = shown(page)
    return ("This page is written by `%s` from its record, %s (one line per file, what the run measured; "
            "scripts/corpus_pages.py names the fields). `scripts/corpus.py --render-only %s` writes it again from "
            "the record, and the test Corpus.Pages fails when the two differ." % (command, record_path(page), page))


def render_prescore(rows, page):
    ok = sum(verdict(r) == "ok" for r in rows)
    refused = sum(verdict(r) == "refused" for r in rows)
    failed = sum(verdict(r).startswith("FAIL") for r in rows)
    solid = ok + failed
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
        made_by(page, "make corpus"),
        "",
        "| | files |",
        "| --- | --- |",
        "| pre-scored | %d |" % ok,
        "| refused: no solid mesh | %d |" % refused,
        "| failed | %d |" % failed,
        "| solid meshes pre-scored | %d of %d (%.1f%%) |" % (ok, solid, 100.0 * ok / max(solid, 1)),
        "| longer than %d s | %d (longest %.1f s) |" % (LIMIT_SECONDS, sum(r["seconds"] > LIMIT_SECONDS for r in rows),
                                                 max(r["seconds"] for r in rows)),
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
    for r in rows:
        result = verdict(r)
        if result != "ok":
            result += ": " + short(r["error"]) if r["error"] else ""
        lines.append("| %s | %s | %s | %s | %s | %s | %.1f |" % (
            escape(r["file"]), r["file"].rsplit(".", 1)[-1].lower(), escape(result), escape(r["auto"] or "-"),
            r["pieces"], r["tets"], r["seconds"]))
    return "\n".join(lines) + "\n"


def held_J(r):
    """The energy a run ends with held in cracks, 0 when it is round-off (within 1e-9 of alpha x
    stored, as the run summary's books line)."""
    held = r["held_J"] or 0.0
    return held if abs(held) > 1e-9 * r["alpha"] * r["stored_J"] else 0.0


def run_summary(ok):
    """The summary lines of the run page that need figures a record may lack (a record made before
    they were kept): 'not recorded' then."""
    def recorded(name):
        return all(r[name] is not None for r in ok)

    stretch = sorted(r["stretch"] for r in ok if r["stretch"] is not None)
    ratios = [r["books"] for r in ok if r["books"] is not None]
    return [
        "| joints solved directly (the default shot's `joints = \"direct\"`) | %s |"
        % (sum(r["joints"] == "direct" for r in ok) if recorded("joints") else "not recorded"),
        "| what the breaking joints held by their stretch, over what their forces stored | %s |"
        % ("median %.3g; within 10%% in %d runs, over twice in %d, of %d"
           % (stretch[len(stretch) // 2], sum(abs(x - 1) <= 0.1 for x in stretch), sum(x > 2 for x in stretch),
              len(stretch)) if stretch else "not recorded"),
        "| (injected + held) / (alpha x stored) | %.4g to %.4g |" % (min(ratios, default=0), max(ratios, default=0)),
        "| runs ending with energy held in cracks not yet opened | %d (%.0f%% of alpha x stored at most) |"
        % (sum(held_J(r) > 0 for r in ok),
           100 * max(((r["held_J"] or 0) / (r["alpha"] * r["stored_J"]) for r in ok if r["alpha"] and r["stored_J"]),
                     default=0)),
        "| runs with negative injected energy | %s |"
        % (sum(r["injected_J"] < 0 for r in ok) if recorded("injected_J") else "not recorded"),
    ]


def render_run(rows, page):
    ok = [r for r in rows if verdict(r) == "ok"]
    seen = [r for r in ok if r["in_view_first"] is not None]
    times = sorted(r["seconds"] for r in ok)
    lines = [
        "# The mesh corpus, run",
        "",
        "`shatter run MESH` (the default shot: a 1.5 m drop onto the ground, the defaults of assets/bunny.toml) on "
        "every mesh of the corpus (docs/results/corpus.md): `make corpus-run` (scripts/corpus.py --run). A file "
        "passes when the run makes a movie, or is refused with exit code 3 as no solid mesh; anything else, or a run "
        "still going after %d s, fails. Times are wall times of the whole job (prescore, simulate, render, encode, "
        ".glb, report) on a shared 2-core machine, with whatever else ran beside them." % RUN_KILL_SECONDS,
        "",
        made_by(page, "make corpus-run"),
        "",
        "| | |",
        "| --- | --- |",
        "| movies made | %d |" % len(ok),
        "| refused: no solid mesh | %d |" % sum(verdict(r) == "refused" for r in rows),
        "| failed | %d |" % sum(verdict(r).startswith("FAIL") for r in rows),
        "| job time | median %.1f s, longest %.1f s |" % (times[len(times) // 2] if times else 0, max(times, default=0)),
        "| runs with breaks | %d |" % sum(r["breaks"] > 0 for r in ok),
    ] + run_summary(ok) + [
        "| runs with warnings (summary.json: model.warnings, simulation.warnings) | %d |" % sum(bool(r["warnings"]) for r in ok),
        "| every piece in view in the first frame | %d of %d |" % (sum(r["in_view_first"] == 100 for r in seen), len(seen)),
        "| at least 90%% of the pieces in view in every frame | %d of %d |" % (sum(r["in_view_least"] >= 90 for r in seen),
                                                                              len(seen)),
        "| at most 1 s still at the end | %d of %d |" % (sum(r["still_s"] <= 1.0 for r in seen), len(seen)),
        "",
        "How to read a row. `stored (J)` is what the joints that broke stored at their breaks. The books are "
        "counted as the breaks give them: each break's alpha E is given back as kinetic energy (injected), or held "
        "in a crack its joints keep closed until a later break opens it (docs/physics.md section 4), so "
        "(injected + held) / (alpha x stored) is 1 when they balance (`-` for a run that stored nothing). `held (J)` is "
        "what the run ends with held in cracks not yet opened; within 1e-9 of alpha x stored it is round-off and "
        "shows as 0. `in view` is the share of the pieces wholly in view in the first frame and in the frame with "
        "the fewest; `still at end` the time at the end of the movie in which no piece moves on screen by more than "
        "half a pixel (render/camera_path.h, CameraCoverage). `warnings` are what prescore and simulate kept in "
        "summary.json, each cut to 200 characters. In the summary, what the breaking joints held by their stretch "
        "is the energy CSV's last removed_J, and the joint solve is the one the trajectory's settings name, "
        "`auto` resolved.",
        "",
        "| file | result | pieces | breaks | fragments | stored (J) | (injected + held) / (alpha x stored) | held (J) "
        "| in view: first, least (%) "
        "| still at end (s) | warnings | time (s) |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for r in rows:
        result = verdict(r)
        if result != "ok":
            lines.append("| %s | %s | | | | | | | | | | %.1f |" % (
                escape(r["file"]), escape(result + (": " + short(r["error"]) if r["error"] else "")), r["seconds"]))
            continue
        ratio = "%.4f" % r["books"] if r["books"] is not None else "-"
        view = "%d, %d" % (r["in_view_first"], r["in_view_least"]) if r["in_view_first"] is not None else "-"
        still = "%.2f" % r["still_s"] if r["still_s"] is not None else "-"
        lines.append("| %s | ok | %s | %d | %d | %.3g | %s | %.3g | %s | %s | %s | %.1f |" % (
            escape(r["file"]), r["pieces"], r["breaks"], r["fragments"], r["stored_J"], ratio, held_J(r), view, still,
            escape(r["warnings"]) or "-", r["seconds"]))
    return "\n".join(lines) + "\n"


def render(page):
    run, rows = read_record(page)
    return (render_run if run else render_prescore)(rows, page)


def check(page):
    """0 when PAGE is what its record gives; else says where they differ and how to fix it, and 1."""
    want = render(page)
    with open(page) as f:
        have = f.read()
    if have == want:
        print("%s: as its record %s gives" % (page, record_path(page)))
        return 0
    have_lines, want_lines = have.split("\n"), want.split("\n")
    at = next((i for i, (a, b) in enumerate(zip(have_lines, want_lines)) if a != b), min(len(have_lines), len(want_lines)))
    print("%s differs from what its record %s gives, first at line %d:\n  page:   %s\n  record: %s\n"
          "fix: `scripts/corpus.py --render-only %s` (after a change to the record or to scripts/corpus_pages.py), "
          "or measure again (make corpus, make corpus-run)"
          % (page, record_path(page), at + 1, have_lines[at][:300] if at < len(have_lines) else "(end)",
             want_lines[at][:300] if at < len(want_lines) else "(end)", page))
    return 1
