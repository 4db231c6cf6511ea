"""tools/bench-against.py with a prebuilt "old" sward-bench (here the same binary, so CI needs no second build): one
pair at 64x48 prints both runs, the medians and new / old, the JSON's figures agree with each other, and bad
arguments and an unknown revision stop with one error line.

Usage: bench_against_test.py BENCH_AGAINST SWARD_BENCH"""
import json
import os
import subprocess
import sys
import tempfile


def main() -> int:
    script, bench = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "against.json")
        run = subprocess.run([sys.executable, script, "HEAD", "--old-bench", bench, "--new-bench", bench,
                              "--pairs", "1", "--frames", "1", "--json", out, "--", "--resolution", "64x48"],
                             capture_output=True, text=True, timeout=300)
        assert run.returncode == 0, run.stderr
        with open(out) as f:
            result = json.load(f)
    lines = run.stdout.splitlines()
    assert lines[0].startswith("pair 1 old: ") and lines[1].startswith("pair 1 new: "), lines
    assert "new / old: " in run.stdout and "as fast as HEAD" in run.stdout, run.stdout
    assert result["frame_args"] == ["--resolution", "64x48"] and result["frames"] == 1, result
    for build in ("old", "new"):
        (figures,) = result["runs"][build]
        passes = [figures[k] for k in ("expansion", "shadow", "main", "resolve", "truth")]
        assert figures["main"] > 0 and abs(figures["all"] - sum(passes)) < 1e-6, figures
        assert result["medians"][build] == figures, result  # one run: its own median
    ratio = result["new_over_old"]["all"]
    assert abs(ratio - result["runs"]["new"][0]["all"] / result["runs"]["old"][0]["all"]) < 1e-12, result
    assert abs(result["speedup"] * ratio - 1.0) < 1e-12, result

    bad = subprocess.run([sys.executable, script, "HEAD", "--old-bench", bench, "--new-bench", bench, "--pairs", "0"],
                         capture_output=True, text=True, timeout=60)
    assert bad.returncode != 0 and bad.stderr.strip().splitlines() == [
        "bench-against: --pairs and --frames must be at least 1"], bad.stderr
    missing = subprocess.run([sys.executable, script, "HEAD", "--old-bench", bench, "--new-bench", "/nonexistent"],
                             capture_output=True, text=True, timeout=60)
    assert missing.returncode != 0 and "'/nonexistent' does not exist" in missing.stderr, missing.stderr
    unknown = subprocess.run([sys.executable, script, "no-such-revision", "--new-bench", bench],
                             capture_output=True, text=True, timeout=60)
    assert unknown.returncode != 0 and unknown.stderr.strip().splitlines() == [
        "bench-against: 'no-such-revision' names no commit of this repository"], unknown.stderr
    print(run.stdout)
    return 0


if __name__ == "__main__":
    sys.exit(main())
