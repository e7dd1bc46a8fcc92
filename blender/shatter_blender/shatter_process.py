"""`shatter run` as a child process: its command line, its progress and its errors.

Nothing here imports bpy, so that the operator's modal timer and the synchronous path of
background mode share one implementation. The child runs in a session of its own, so that a
cancel stops it and everything it started (ffmpeg) at once; its stdout and stderr
are read by two threads into lists of lines, so that a chatty child never blocks on a full pipe.

shatter logs "LEVEL: text" lines on stderr (core/log.cpp): "info: [3/9] render" when a stage
starts, "simulate: 40% (24/60) 3.1s" as a slow loop goes on (core/progress.cpp, one line per
tenth on a pipe), and "error: WHERE: PROBLEM (fix: FIX)" when it refuses its input.
"""

import os
import re
import shutil
import signal
import subprocess
import threading
import time

STAGE_LINE = re.compile(r"^info: \[(\d+)/(\d+)\] (\w+)")
LOOP_LINE = re.compile(r"^(\w+): (\d+)% \(\d+/\d+\)")
ERROR_LINE = re.compile(r"^error: (.*)")


class ShatterNotFound(Exception):
    """The shatter binary is neither where the preferences say nor on PATH."""


def find_binary(preferred):
    """The shatter binary: `preferred` when set (a file or a name on PATH), else `shatter` on PATH."""
    if preferred:
        path = os.path.abspath(os.path.expanduser(preferred)) if os.sep in preferred else shutil.which(preferred)
        if path and os.path.isfile(path) and os.access(path, os.X_OK):
            return path
        raise ShatterNotFound(
            f"the shatter binary '{preferred}' set in the add-on's preferences is not an executable file "
            "(fix: Edit > Preferences > Add-ons > Shatter: the path of build/bin/shatter, or empty to use PATH)")
    path = shutil.which("shatter")
    if not path:
        raise ShatterNotFound(
            "the shatter binary was not found on PATH (fix: build it with `make` and set its path, "
            "build/bin/shatter, in Edit > Preferences > Add-ons > Shatter, or put it on PATH)")
    return path


def run_command(binary, mesh_path, out_dir, settings, stages=None, cache=None):
    """The argument vector of `shatter run MESH -o OUT --set KEY=VALUE ... [--stages ...] [--cache
    DIR]` (no shell)."""
    argv = [binary, "run", mesh_path, "-o", out_dir]
    if cache:
        argv += ["--cache", cache]
    for key, value in settings:
        argv += ["--set", f"{key}={value}"]
    if stages:
        argv += ["--stages", ",".join(stages)]
    return argv


class ShatterProcess:
    """One `shatter run`, started at construction. poll() is cheap and never blocks."""

    def __init__(self, argv):
        self.argv = argv
        self.stdout = []
        self.stderr = []
        self.stage = ""          # the stage running, e.g. "simulate"
        self.stage_index = 0     # 1-based, as shatter counts them
        self.stage_count = 0
        self.loop_percent = 0    # progress within the stage, when it reports any
        self.started = time.monotonic()
        self.cancelled = False
        self._proc = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                      stderr=subprocess.PIPE, start_new_session=True)
        self._threads = [threading.Thread(target=self._read, args=(self._proc.stdout, self.stdout, False), daemon=True),
                         threading.Thread(target=self._read, args=(self._proc.stderr, self.stderr, True), daemon=True)]
        for t in self._threads:
            t.start()

    def _read(self, pipe, lines, parse):
        for raw in iter(pipe.readline, b""):
            line = raw.decode("utf-8", errors="replace").rstrip("\r\n")
            lines.append(line)
            if parse:
                self._parse(line)
        pipe.close()

    def _parse(self, line):
        m = STAGE_LINE.match(line)
        if m:
            self.stage_index, self.stage_count, self.stage = int(m.group(1)), int(m.group(2)), m.group(3)
            self.loop_percent = 0
            return
        m = LOOP_LINE.match(line)
        if m:
            self.loop_percent = int(m.group(2))

    def poll(self):
        """None while running, else the exit code (after both pipes are read to their end)."""
        code = self._proc.poll()
        if code is None:
            return None
        for t in self._threads:
            t.join()
        return code

    def wait(self, timeout=None):
        """Blocks until the run ends (or `timeout` seconds pass: None then) and returns its exit code."""
        try:
            self._proc.wait(timeout)
        except subprocess.TimeoutExpired:
            return None
        return self.poll()

    def fraction(self):
        """How far the run is, 0 to 1, by stage and by the running stage's own progress."""
        if not self.stage_count:
            return 0.0
        return min(1.0, (self.stage_index - 1 + self.loop_percent / 100.0) / self.stage_count)

    def status(self):
        """One line for the status bar."""
        seconds = time.monotonic() - self.started
        if not self.stage:
            return f"Shatter: starting ({seconds:.0f} s)"
        within = f" {self.loop_percent}%" if self.loop_percent else ""
        return f"Shatter: {self.stage}{within}, stage {self.stage_index} of {self.stage_count} ({seconds:.0f} s)"

    def cancel(self):
        """Stops the run and everything it started; returns when they are gone."""
        self.cancelled = True
        if self._proc.poll() is not None:
            return
        for sig, wait in ((signal.SIGTERM, 3.0), (signal.SIGKILL, 10.0)):
            try:
                os.killpg(self._proc.pid, sig)
            except ProcessLookupError:
                break
            try:
                self._proc.wait(wait)
                break
            except subprocess.TimeoutExpired:
                continue
        self.poll()

    def error_message(self, code):
        """What went wrong, in shatter's words: its error lines, else the end of its stderr."""
        errors = [m.group(1) for m in map(ERROR_LINE.match, self.stderr) if m]
        if errors:
            return "; ".join(errors)
        tail = [line for line in self.stderr if line.strip()][-3:]
        if tail:
            return " / ".join(tail)
        return f"shatter run exited with code {code} and printed nothing on stderr"

    def warnings(self):
        """shatter's warnings ("warn: ..." lines), each once."""
        seen = []
        for line in self.stderr:
            if line.startswith("warn: ") and line[6:] not in seen:
                seen.append(line[6:])
        return seen
