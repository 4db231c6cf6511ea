"""Doc tests: every command block of README.md and docs/python.md runs, as a user following them would, so the
documentation cannot go stale (issue 50, point 6). Run by CTest as Docs.EveryCommandBlockRuns.

Policy (docs/testing.md, "Doc tests"):
- Blocks: every fenced ```sh / ```bash / ```console block of both files (in a console block the lines that start
  with `$ `) and every ```python block of docs/python.md, in document order. An unlabelled fence whose first line
  is a command (build/bin/..., ./sward.sh ...) fails the test: label it, so it runs.
- Skips: only a block marked in the Markdown itself, with an HTML comment on the line right before its fence:
  `<!-- doc-test: skip REASON -->`. A skip without a reason fails the test; the counts of run and skipped blocks
  are printed.
- Where: a temporary folder set up like a user's checkout, which is the working folder of every block: a symbolic
  link to each top-level entry of the source tree that git tracks, `build/` a real folder of symbolic links to the
  build folder's entries (so `build/bin/...`, `build/python`, `build/examples/...` are this build's, and what a
  block creates under `build/`, e.g. pip's `build/pip` (not linked), stays in the temporary folder), and a copy
  of setup.py (it finds its folder through its own resolved path). Outputs (`out/`, `study/`, `~/sward-venv`,
  ...) land in the temporary folder: HOME is a folder in it. Nothing is written into the source or build tree.
- Environment: the one of a user who has run `./sward.sh build` on an offline machine: SWARD_BUILD_DIR=build (pip
  takes this build's extension instead of compiling its own: docs/python.md), PIP_NO_INDEX=1 and no pip version
  check; no PYTHONPATH or VIRTUAL_ENV of the caller's. Shell blocks run under bash with `set -eo pipefail`, one
  bash per block (a `cd` holds for the rest of its block). The python blocks of a file run in order in one
  interpreter session (Debian's python3 running this script, with the build's module on PYTHONPATH), so a block
  may use the variables of the one before.
- The one rewrite: size caps, because renders at the documented settings take minutes on lavapipe. A `sward-render`
  command (also `build/bin/sward-render`) gets `--resolution 64x48`, `--samples 1` and `--frames 0:K` (K = 2, or
  fewer when the scene's sequence is shorter) for each of these options it lacks (no `--frames` where `--shard`
  is given). `./sward.sh render ARGS` is run as its equivalent `build/bin/sward-render ARGS` with the default
  scene and `--out out` that sward.sh adds (the setup and the build it would run first are this test's build),
  capped the same. A `sward-view` command runs under `xvfb-run -a` with `--size 64x48 --samples 1 --frames 3
  --screenshot doc-test-view-N.png` where it lacks them. Everything else (paths, option names, layouts, scene
  files, Python code) runs exactly as written. Any other `./sward.sh` command, or `sward-bench` (no cap defined
  yet), in a block that is not skipped fails the test.

usage: doc_commands_test.py SOURCE_DIR BUILD_DIR
"""
import json
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

DOCS = {"README.md": ("sh", "bash", "console"), "docs/python.md": ("sh", "bash", "console", "python")}
SKIP = re.compile(r"^<!--\s*doc-test:\s*skip\b(.*?)-->\s*$")
DOC_TEST_COMMENT = re.compile(r"^<!--\s*doc-test\b")
COMMAND_START = re.compile(r"^(\$ )?(\./sward\.sh|build/bin/|sward-|python3? |cmake |pip )")
FENCE = re.compile(r"^```\s*([A-Za-z0-9_+-]*)\s*$")
RENDER_CAPS = (("--resolution", "64x48"), ("--samples", "1"))
VIEW_CAPS = (("--size", "64x48"), ("--samples", "1"), ("--frames", "3"))
FRAMES_CAP = 2
# sward-render's options that take no value (as sward.sh's render_args): everything else starting with - takes one.
NO_VALUE = {"-q", "--quiet", "--no-vegetation", "--validation", "-h", "--help", "--version", "--list-devices",
            "--overwrite"}


class DocError(Exception):
    pass


class Block:
    def __init__(self, doc, line, lang, text, skip):
        self.doc, self.line, self.lang, self.text, self.skip = doc, line, lang, text, skip

    def where(self):
        return f"{self.doc}:{self.line}"


def read_blocks(doc, path, langs):
    """The fenced blocks of the languages `langs`, with their skip reasons (None: runs)."""
    lines = path.read_text().split("\n")
    blocks, i = [], 0
    while i < len(lines):
        fence = FENCE.match(lines[i])
        if not fence:
            i += 1
            continue
        start, lang = i, fence.group(1)
        i += 1
        while i < len(lines) and not lines[i].startswith("```"):
            i += 1
        text = "\n".join(lines[start + 1:i])
        i += 1
        before = lines[start - 1].strip() if start > 0 else ""
        skip = None
        if DOC_TEST_COMMENT.match(before):
            marked = SKIP.match(before)
            if not marked:
                raise DocError(f"{doc}:{start}: unknown doc-test comment {before!r} (only '<!-- doc-test: skip "
                               "REASON -->')")
            skip = marked.group(1).strip()
            if not skip:
                raise DocError(f"{doc}:{start}: '<!-- doc-test: skip -->' without a reason: say why the block "
                               "cannot run here and what covers it instead")
        if not lang and text.strip() and COMMAND_START.match(text.strip().split("\n")[0]):
            raise DocError(f"{doc}:{start + 1}: an unlabelled block of commands: label its fence ```sh so the doc "
                           "test runs it")
        if lang in langs:
            blocks.append(Block(doc, start + 1, lang, text, skip))
    return blocks


def logical_lines(block):
    """The block's commands: continuation lines joined, blank and comment-only lines dropped."""
    raw = block.text.split("\n")
    if block.lang == "console":  # commands and their continuation lines; the rest is output
        kept = []
        for line in raw:
            if line.startswith("$ ") or (kept and kept[-1].endswith("\\")):
                kept.append(line[2:] if line.startswith("$ ") else line)
        raw = kept
    commands, pending = [], ""
    for line in raw:
        if line.endswith("\\"):
            pending += line[:-1] + " "
            continue
        line, pending = pending + line, ""
        if line.strip() and not line.strip().startswith("#"):
            commands.append(line)
    return commands


def split_comment(line):
    """(command, ' # comment'): a # that starts a word outside quotes starts the comment."""
    quote = None
    for i, c in enumerate(line):
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c == "#" and (i == 0 or line[i - 1].isspace()):
            return line[:i].rstrip(), " " + line[i:]
    return line.rstrip(), ""


def split_segments(command):
    """The simple commands of a line and the operators between them (&&, ||, ;, |), outside quotes."""
    parts, quote, start, i = [], None, 0, 0
    while i < len(command):
        c = command[i]
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif command.startswith(("&&", "||"), i) or c in ";|":
            width = 2 if command.startswith(("&&", "||"), i) else 1
            parts += [command[start:i], command[i:i + width]]
            start = i = i + width
            continue
        i += 1
    return parts + [command[start:]]


def has_option(words, name):
    return any(w == name or w.startswith(name + "=") for w in words)


def positionals(words):
    found, expect_value = [], False
    for word in words:
        if expect_value:
            expect_value = False
        elif word.startswith("-"):
            expect_value = word not in NO_VALUE and "=" not in word
        else:
            found.append(word)
    return found


def scene_frames(scene, cwd):
    """The scene file's sequence.frames (1 when it has none, the scene format's default)."""
    try:
        return int(json.loads((cwd / scene).read_text()).get("sequence", {}).get("frames", 1))
    except (OSError, ValueError, AttributeError):
        return FRAMES_CAP  # sward-render says what is wrong with it


def render_caps(args, cwd):
    if has_option(args, "--help") or has_option(args, "-h") or has_option(args, "--version") \
            or has_option(args, "--list-devices"):
        return []
    added = [f"{name} {value}" for name, value in RENDER_CAPS if not has_option(args, name)]
    if not has_option(args, "--frames") and not has_option(args, "--shard"):
        scene = positionals(args)
        frames = min(FRAMES_CAP, scene_frames(scene[0], cwd)) if scene else 1
        added.append(f"--frames 0:{frames}")
    return added


class Rewriter:
    """The one rewrite of the policy: size caps on renders and viewers; counts what it changed."""

    def __init__(self, cwd):
        self.cwd, self.views, self.rewritten = cwd, 0, 0

    def segment(self, text, where):
        words = shlex.split(text)
        assignments = []
        while words and re.match(r"^[A-Za-z_][A-Za-z0-9_]*=", words[0]):
            assignments, words = assignments + [words[0]], words[1:]
        under_x = bool(words) and words[0] == "xvfb-run"
        if under_x:  # its options, then the command it runs
            words = words[1:]
            while words and words[0].startswith("-"):
                takes_value = words[0] in ("-n", "-s", "-e", "-f", "-p", "-w", "--server-num", "--server-args")
                words = words[2:] if takes_value else words[1:]
        if not words:
            return text
        program, args = words[0], words[1:]
        name = pathlib.PurePath(program).name
        if program == "./sward.sh":
            if not args or args[0] in ("help", "-h", "--help"):
                return text
            if args[0] != "render":
                raise DocError(f"{where}: './sward.sh {args[0]}' sets up and builds: mark the block "
                               "'<!-- doc-test: skip REASON -->'")
            args = args[1:]
            given = shlex.join(args)
            scene = "" if positionals(args) else " examples/meadow.json"
            out = "" if has_option(args, "--out") or has_option(args, "-o") else " --out out"
            caps = render_caps(args + (["examples/meadow.json"] if scene else []), self.cwd)
            self.rewritten += 1
            return f"build/bin/sward-render{scene}{(' ' + given) if given else ''}{out} {' '.join(caps)}".rstrip()
        if name == "sward-render":
            caps = render_caps(args, self.cwd)
            self.rewritten += bool(caps)
            return f"{text.rstrip()} {' '.join(caps)}".rstrip()
        if name == "sward-view":
            self.views += 1
            caps = [f"{n} {v}" for n, v in VIEW_CAPS if not has_option(args, n)]
            if not has_option(args, "--screenshot"):
                caps.append(f"--screenshot doc-test-view-{self.views}.png")
            self.rewritten += 1
            if under_x:
                return f"{text.strip()} {' '.join(caps)}".rstrip()
            command = shlex.join(words)  # under xvfb-run, after the variables it passes on
            prefix = " ".join(shlex.quote(a) for a in assignments)
            return f"{prefix} xvfb-run -a {command} {' '.join(caps)}".strip()
        if name == "sward-bench":
            raise DocError(f"{where}: sward-bench has no size cap in the doc test yet: add one (docs/testing.md)")
        return text

    def line(self, line, where):
        command, comment = split_comment(line)
        parts = split_segments(command)
        for i in range(0, len(parts), 2):
            rewritten = self.segment(parts[i], where)
            if rewritten != parts[i]:
                lead = parts[i][:len(parts[i]) - len(parts[i].lstrip())]
                parts[i] = lead + rewritten.strip() + (" " if i + 1 < len(parts) else "")
        return "".join(parts) + comment


def make_checkout(source, build, tmp):
    """A user's checkout in tmp, without copying the tree (see the policy above)."""
    checkout, home = tmp / "checkout", tmp / "home"
    checkout.mkdir()
    home.mkdir()
    tracked = subprocess.run(["git", "-C", str(source), "ls-files"], capture_output=True, text=True)
    if tracked.returncode == 0 and tracked.stdout.strip():
        names = sorted({line.split("/")[0] for line in tracked.stdout.split("\n") if line})
    else:  # an unpacked source archive: everything but build folders and outputs
        names = sorted(p.name for p in source.iterdir() if not p.name.startswith(("build", ".git", "out")))
    for name in names:
        if name == "setup.py":
            shutil.copyfile(source / name, checkout / name)
        elif name != "build" and (source / name).exists():
            (checkout / name).symlink_to(source / name)
    (checkout / "build").mkdir()
    for entry in build.iterdir():
        if entry.name != "pip":  # setup.py's own build folder: pip writes there
            (checkout / "build" / entry.name).symlink_to(entry)
    return checkout, home


def environment(home):
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    env.update(HOME=str(home), SWARD_BUILD_DIR="build", PIP_NO_INDEX="1", PIP_DISABLE_PIP_VERSION_CHECK="1")
    return env


def run_shell(block, rewriter, cwd, env):
    commands = [rewriter.line(line, f"{block.where()}") for line in logical_lines(block)]
    script = "set -eo pipefail\n" + "\n".join(commands) + "\n"
    for command in commands:
        print(f"    $ {command}", flush=True)
    result = subprocess.run(["bash", "-c", script], cwd=cwd, env=env, capture_output=True, text=True)
    if result.returncode != 0:
        raise DocError(f"{block.where()}: the block failed (exit {result.returncode}):\n{result.stdout}"
                       f"{result.stderr}")


DRIVER = r"""
import json, sys, traceback
session = {"__name__": "__main__"}
for line in sys.stdin:
    block = json.loads(line)
    ok = True
    try:
        exec(compile("\n" * block["line"] + block["code"], block["doc"], "exec"), session)
    except BaseException:
        traceback.print_exc()
        ok = False
    sys.stderr.flush()
    print("\n@@doc-test-block-done@@", "ok" if ok else "failed", flush=True)
"""


class PythonSession:
    """One interpreter for a file's python blocks, fed block by block, so a block sees its predecessors' names."""

    def __init__(self, cwd, env, build):
        env = {**env, "PYTHONPATH": str(build / "python")}
        self.process = subprocess.Popen([sys.executable, "-c", DRIVER], cwd=cwd, env=env, text=True,
                                        stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)

    def run(self, block):
        self.process.stdin.write(json.dumps({"doc": block.doc, "line": block.line, "code": block.text}) + "\n")
        self.process.stdin.flush()
        output = []
        for line in self.process.stdout:
            if line.startswith("@@doc-test-block-done@@"):
                if line.split()[1] != "ok":
                    raise DocError(f"{block.where()}: the python block failed:\n{''.join(output)}")
                return
            output.append(line)
        raise DocError(f"{block.where()}: the python session ended:\n{''.join(output)}")

    def close(self):
        self.process.stdin.close()
        self.process.wait()


def source_status(source):
    """The checkout's `git status --porcelain` (untracked and changed files; ignored ones, such as build/, left out)."""
    return subprocess.run(["git", "-C", str(source), "status", "--porcelain"], capture_output=True, text=True,
                          check=True).stdout


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.split("usage: ")[1])
    source, build = pathlib.Path(sys.argv[1]).resolve(), pathlib.Path(sys.argv[2]).resolve()
    started = time.monotonic()
    counts = {}
    try:
        blocks = [b for doc, langs in DOCS.items() for b in read_blocks(doc, source / doc, langs)]
        before = source_status(source)
        with tempfile.TemporaryDirectory(prefix="sward-doc-test-") as tmp:
            cwd, home = make_checkout(source, build, pathlib.Path(tmp))
            env = environment(home)
            rewriter, sessions = Rewriter(cwd), {}
            try:
                for block in blocks:
                    ran, skipped = counts.get(block.doc, (0, 0))
                    if block.skip is not None:
                        counts[block.doc] = (ran, skipped + 1)
                        print(f"skip {block.where()} ({block.lang}): {block.skip}", flush=True)
                        continue
                    print(f"run  {block.where()} ({block.lang})", flush=True)
                    block_started = time.monotonic()
                    if block.lang == "python":
                        if block.doc not in sessions:
                            sessions[block.doc] = PythonSession(cwd, env, build)
                        sessions[block.doc].run(block)
                    else:
                        run_shell(block, rewriter, cwd, env)
                    print(f"     {time.monotonic() - block_started:.1f} s", flush=True)
                    counts[block.doc] = (ran + 1, skipped)
            finally:
                for session in sessions.values():
                    session.close()
        # The working folder links the checkout's top-level entries: an --out that names one of its folders (the
        # source's world/ once) would write into the source tree. Nothing may appear or change there.
        if source_status(source) != before:
            raise DocError("the blocks wrote into the source tree (git status changed): an --out names a folder "
                           "of the checkout")
        for doc in DOCS:
            if counts.get(doc, (0, 0))[0] == 0:
                raise DocError(f"{doc}: no block ran (is the extraction broken?)")
    except DocError as error:
        sys.exit(f"FAIL: {error}")
    ran = sum(r for r, _ in counts.values())
    skipped = sum(s for _, s in counts.values())
    per_doc = "; ".join(f"{doc}: {r} run, {s} skipped" for doc, (r, s) in counts.items())
    print(f"ok: {ran} blocks run, {skipped} skipped ({per_doc}); {rewriter.rewritten} commands size-capped; "
          f"{time.monotonic() - started:.1f} s")


if __name__ == "__main__":
    main()
