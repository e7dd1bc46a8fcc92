#!/usr/bin/python3
"""Runs one case of tests/blender/addon_test.py in Debian's Blender, headless.

  run_addon_test.py CASE --zip BUILD/shatter_blender.zip --shatter BUILD/bin/shatter --work DIR

Blender is $SHATTER_BLENDER when set, else `blender` on PATH (scripts/install-deps.sh installs
Debian's). Without it the case is skipped: exit code 77, which ctest reports as a skip, with the
reason printed. The add-on is installed into DIR/blender-user (BLENDER_USER_SCRIPTS and
BLENDER_USER_CONFIG), never into the user's own Blender folders, and Blender starts from its
factory settings.
"""

import argparse
import os
import shutil
import subprocess
import sys

SKIP = 77
HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("case")
    p.add_argument("--zip", required=True)
    p.add_argument("--shatter", required=True)
    p.add_argument("--work", required=True)
    a = p.parse_args()

    blender = os.environ.get("SHATTER_BLENDER") or shutil.which("blender")
    if not blender:
        print("SKIP: Blender is not installed (no `blender` on PATH, SHATTER_BLENDER unset); "
              "scripts/install-deps.sh installs Debian's")
        return SKIP
    for what, path in (("the add-on's .zip (built by `make`)", a.zip), ("the shatter binary", a.shatter)):
        if not os.path.isfile(path):
            print(f"FAIL: {what} is not at {path}")
            return 1

    work = os.path.join(os.path.abspath(a.work), a.case)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    env = dict(os.environ)
    env["BLENDER_USER_SCRIPTS"] = os.path.join(work, "blender-user", "scripts")
    env["BLENDER_USER_CONFIG"] = os.path.join(work, "blender-user", "config")
    argv = [blender, "-b", "--factory-startup", "--python-exit-code", "1",
            "--python", os.path.join(HERE, "addon_test.py"), "--",
            "--case", a.case, "--zip", os.path.abspath(a.zip), "--shatter", os.path.abspath(a.shatter),
            "--work", work, "--source", os.path.dirname(os.path.dirname(HERE))]
    print("run:", " ".join(argv), flush=True)
    return subprocess.run(argv, env=env).returncode


if __name__ == "__main__":
    sys.exit(main())
