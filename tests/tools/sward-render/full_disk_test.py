#!/usr/bin/env python3
"""sward-render on a full disk: a small tmpfs, mounted in a private mount namespace (unshare), so nothing on the
machine is touched.

    full_disk_test.py SWARD_RENDER SCENE

(a) a file system too small for one frame: refused up front, nothing written;
(b) room for about three frames of a six-frame run: exit 1, one error line "cannot write '<file>': no space left on
    device", and the output folder as found (it did not exist: it still does not);
(c) the same after an earlier run finished frame 0: that run's files stay, bitwise, and nothing else is left.
Exit 77 (skipped) where no mount namespace can be made, except under CI (CI set), where that fails. Python 3 standard library only.
"""

import os
import re
import subprocess
import sys
import tempfile

SKIP = 77


def snapshot(root):
    """{relative path: bytes or '<folder>'} of everything under root ({} when root does not exist)."""
    files = {}
    for folder, dirs, names in os.walk(root):
        for d in dirs:
            files[os.path.relpath(os.path.join(folder, d), root)] = "<folder>"
        for n in names:
            with open(os.path.join(folder, n), "rb") as f:
                files[os.path.relpath(os.path.join(folder, n), root)] = f.read()
    return files


def render(exe, scene, out, *args):
    command = [exe, scene, "--resolution", "160x120", "--samples", "1", "--quiet", "--out", out, *args]
    result = subprocess.run(command, capture_output=True, text=True)
    return result.returncode, result.stderr


def error_lines(stderr):
    return [line for line in stderr.splitlines() if "error" in line]


def mount_tmpfs(path, size):
    subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", path], check=True)


def inside(exe, scene):
    failures = []

    def check(condition, message):
        if not condition:
            failures.append(message)

    with tempfile.TemporaryDirectory() as mnt:
        # (a) too small for one frame
        mount_tmpfs(mnt, 256 * 1024)
        code, err = render(exe, scene, mnt + "/out")
        check(code == 1, f"(a) exit {code}, expected 1: {err}")
        check(len(error_lines(err)) == 1 and "not enough space" in err, f"(a) expected one clear error: {err}")
        check(snapshot(mnt) == {}, f"(a) wrote {sorted(snapshot(mnt))}")
        needed = re.search(r"needs up to (\d+) bytes", err)
        subprocess.run(["umount", mnt], check=True)
        if not needed:
            print("\n".join(failures) or "(a) the error gives no byte count", file=sys.stderr)
            return 1

        # (b) room for the up-front check's bound (about three actual frames) of a six-frame run
        room = (int(needed.group(1)) + 64 * 1024 + 4095) // 4096 * 4096
        mount_tmpfs(mnt, room)
        code, err = render(exe, scene, mnt + "/out")
        lines = error_lines(err)
        check(code == 1, f"(b) exit {code}, expected 1: {err}")
        check(len(lines) == 1 and "no space left on device" in lines[0] and f"cannot write '{mnt}/out/" in lines[0],
              f"(b) expected one line 'cannot write '<file>': no space left on device': {err}")
        check(snapshot(mnt) == {}, f"(b) left {sorted(snapshot(mnt))}")
        subprocess.run(["umount", mnt], check=True)

        # (c) an earlier run's finished frame stays, bitwise; the failed run's files go. The extra room holds
        # what the earlier run wrote (a stereo frame with right-view truth and masks: about 0.6 MB at 160x120), so
        # the later run passes the up-front check and fills the disk mid-run.
        mount_tmpfs(mnt, room + 1024 * 1024)
        code, err = render(exe, scene, mnt + "/out", "--frames", "0:1")
        check(code == 0, f"(c) the one-frame run failed: {err}")
        before = snapshot(mnt)
        code, err = render(exe, scene, mnt + "/out")
        check(code == 1 and "no space left on device" in err, f"(c) expected a full disk: exit {code}: {err}")
        check(snapshot(mnt) == before, "(c) the folder differs from what the earlier run left")
        subprocess.run(["umount", mnt], check=True)

    for message in failures:
        print(message, file=sys.stderr)
    print(f"full disk: {'FAILED' if failures else 'ok'} (tmpfs of {room} bytes for (b) and (c))")
    return 1 if failures else 0


def main():
    if len(sys.argv) == 4 and sys.argv[3] == "--inside":
        return inside(sys.argv[1], sys.argv[2])
    exe, scene = sys.argv[1], sys.argv[2]
    me = [sys.executable, os.path.abspath(__file__), exe, scene, "--inside"]
    # As root a private mount namespace; otherwise a user namespace whose root may mount a tmpfs.
    for prefix in (["unshare", "--mount", "--propagation", "private"], ["unshare", "-rm"]):
        probe = subprocess.run(prefix + ["true"], capture_output=True)
        if probe.returncode == 0:
            return subprocess.run(prefix + me).returncode
    # CI has namespaces (it runs as root): there a skip would hide a test that no longer runs.
    if os.environ.get("CI"):
        print("error: no mount namespace (unshare) available, and CI must run this test", file=sys.stderr)
        return 1
    print("skipped: no mount namespace (unshare) available", file=sys.stderr)
    return SKIP


if __name__ == "__main__":
    sys.exit(main())
