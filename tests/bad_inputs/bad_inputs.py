#!/usr/bin/env python3
"""The bad-input table: every bad input tried on sward's tools, the error it gets, and that nothing was written.

    bad_inputs.py BIN_DIR SOURCE_DIR TABLE.md [--only REGEX]

For each case (cases.py) the tool runs on a freshly made input in a case folder of its own and must
  - exit with the expected code (2: bad command line, 1: bad input or failed run);
  - print exactly ONE line on stderr (informational "sward: device: ..." lines aside) that starts with
    "<tool>: error: " and matches the case's regex (it names the problem);
  - leave its output folder (--out, or the case's watched path) exactly as found: absent if it was absent,
    otherwise the same listing and bytes;
  - end within the case's limit_s seconds with a peak resident size under its limit_mb (a bad input is refused
    before it costs time or memory).
The cases are cases.py's CASES followed by those of every cases_*.py module beside it (one per part of the code).
The table (input | command | exit | error | nothing written) goes to TABLE.md. Exit status 1 if any case fails.
Python 3 standard library only.
"""

import argparse
import hashlib
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import threading
import time
import glob
import importlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cases as case_table  # noqa: E402

INFO_LINE = re.compile(r"^sward: device: ")


def snapshot(path):
    """None for a missing path, else every entry below it (itself included) with its bytes' hash."""
    if not os.path.lexists(path):
        return None
    if not os.path.isdir(path) or os.path.islink(path):
        with open(path, "rb") as f:
            return {".": hashlib.sha256(f.read()).hexdigest()}
    entries = {".": "dir"}
    for root, dirs, files in os.walk(path):
        for name in dirs:
            entries[os.path.relpath(os.path.join(root, name), path)] = "dir"
        for name in files:
            full = os.path.join(root, name)
            with open(full, "rb") as f:
                entries[os.path.relpath(full, path)] = hashlib.sha256(f.read()).hexdigest()
    return entries


def describe_change(before, after):
    if before is None:
        return "created: " + ", ".join(sorted(after)[:6])
    if after is None:
        return "removed"
    changed = sorted(k for k in set(before) | set(after) if before.get(k) != after.get(k))
    return "changed: " + ", ".join(changed[:6])


def run_measured(command, environment, cwd, timeout):
    """Runs `command`; returns (exit code or "timeout", stderr, wall seconds, peak resident MiB of the process).
    os.wait4 gives the process's own rusage, which subprocess.run would discard."""
    start = time.monotonic()
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=environment, cwd=cwd)
    captured = {}

    def drain(name, stream):
        captured[name] = stream.read()

    readers = [threading.Thread(target=drain, args=(n, s)) for n, s in (("out", process.stdout),
                                                                        ("err", process.stderr))]
    for r in readers:
        r.start()
    status = usage = None
    while True:
        pid, status, usage = os.wait4(process.pid, os.WNOHANG)
        if pid:
            break
        if time.monotonic() - start > timeout:
            process.kill()
            _, status, usage = os.wait4(process.pid, 0)
            status = None
            break
        time.sleep(0.01)
    seconds = time.monotonic() - start
    process.returncode = 0  # reaped above; keeps Popen from waiting again
    for r in readers:
        r.join()
    code = "timeout" if status is None else os.waitstatus_to_exitcode(status)
    stderr = captured.get("err", b"").decode("utf-8", "replace")
    return code, stderr, seconds, usage.ru_maxrss / 1024.0


def all_cases():
    """cases.py's table, then every cases_*.py module's CASES in name order."""
    cases = list(case_table.CASES)
    here = os.path.dirname(os.path.abspath(__file__))
    for path in sorted(glob.glob(os.path.join(here, "cases_*.py"))):
        module = importlib.import_module(os.path.splitext(os.path.basename(path))[0])
        cases += module.CASES
    return cases


def run_case(case, ctx, work):
    folder = os.path.join(work, f"{ctx.index:03d}-{case.slug}")
    ctx.index += 1
    os.makedirs(folder)
    env = case_table.Env(ctx.bin, ctx.source, folder, ctx.base_dataset)
    args = case.setup(env) if case.setup else []
    watched = env.watched or env.out
    before = snapshot(watched)
    tool = case.tool
    command = [sys.executable, os.path.join(ctx.source, "tools", tool)] if tool.endswith(".py") else \
        [os.path.join(ctx.bin, tool)]
    environment = dict(os.environ)
    environment.pop("DISPLAY", None)
    code, stderr, seconds, peak_mb = run_measured(command + args, environment, folder, timeout=max(120, case.limit_s))
    after = snapshot(watched)
    lines = [line for line in stderr.splitlines() if not INFO_LINE.match(line)]
    problems = []
    if code != case.exit:
        problems.append(f"exit {code}, expected {case.exit}")
    if len(lines) != 1:
        problems.append(f"{len(lines)} stderr lines, expected 1")
    elif not lines[0].startswith(f"{tool}: error: ") or not re.search(case.error, lines[0]):
        problems.append(f"error line does not match /{case.error}/")
    if before != after:
        problems.append("output folder " + describe_change(before, after))
    if seconds > case.limit_s:
        problems.append(f"took {seconds:.1f} s, limit {case.limit_s:g} s")
    if peak_mb > case.limit_mb:
        problems.append(f"peak resident size {peak_mb:.0f} MiB, limit {case.limit_mb} MiB")
    shown = " ".join(shlex.quote(os.path.relpath(a, folder) if a.startswith(folder) else a) for a in args)
    return {
        "case": case,
        "command": f"{tool} {shown}".strip(),
        "exit": code,
        # The case folder is a temporary name: shown as "." so that the table reads the same on every run.
        "error": (lines[0] if len(lines) == 1 else " / ".join(lines) or "(none)").replace(folder, ".")
                 .replace(os.path.dirname(folder), "..").replace(ctx.source, "<source>"),
        "untouched": before == after,
        "problems": problems,
    }


class Context:
    def __init__(self, bin_dir, source):
        self.bin = os.path.abspath(bin_dir)
        self.source = os.path.abspath(source)
        self.base_dataset = None
        self.index = 0


def make_base_dataset(ctx, work):
    """One tiny rendered dataset (1 frame, 32x24) that the sward-eval and resume cases corrupt copies of."""
    out = os.path.join(work, "base-dataset")
    scene = case_table.write_scene(os.path.join(work, "base-scene"), case_table.base_scene(ctx.source))
    result = subprocess.run([os.path.join(ctx.bin, "sward-render"), scene, "--out", out, "--quiet"],
                            capture_output=True, text=True, timeout=300)
    if result.returncode != 0:
        sys.exit(f"bad_inputs.py: error: cannot render the base dataset: {result.stderr.strip()}")
    ctx.base_dataset = out


def table_row(r):
    def cell(text):
        return str(text).replace("|", "\\|").replace("\n", " ")
    status = "yes" if r["untouched"] else "NO"
    return (f"| {cell(r['case'].name)} | `{cell(r['command'])}` | {r['exit']} | {cell(r['error'])} | {status} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("bin_dir")
    parser.add_argument("source_dir")
    parser.add_argument("table")
    parser.add_argument("--only", default="", help="run only cases whose name matches this regex")
    args = parser.parse_args()
    ctx = Context(args.bin_dir, args.source_dir)
    selected = [c for c in all_cases() if re.search(args.only, c.name)]
    work = tempfile.mkdtemp(prefix="sward-bad-inputs-")
    failed = 0
    rows = []
    try:
        if any(c.needs_dataset for c in selected):
            make_base_dataset(ctx, work)
        for case in selected:
            r = run_case(case, ctx, work)
            rows.append(r)
            failed += bool(r["problems"])
            detail = ": " + "; ".join(r["problems"]) if r["problems"] else ""
            print(f"{'FAIL' if r['problems'] else 'ok':7} {case.name}{detail}")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    with open(args.table, "w", encoding="utf-8") as f:
        f.write("| input | command | exit | error | nothing written |\n|---|---|---|---|---|\n")
        f.write("\n".join(table_row(r) for r in rows) + "\n")
    print(f"{len(rows)} cases: {len(rows) - failed} ok, {failed} failed; table: {args.table}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
