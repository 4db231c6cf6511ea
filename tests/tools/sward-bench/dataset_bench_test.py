"""sward-bench dataset (render/dataset_benchmark.cpp): a three-frame run's figures agree with each other and with
the files it wrote, and the temporary folder it wrote them to is gone afterwards.

Usage: dataset_bench_test.py SWARD_BENCH SCENE"""
import json
import os
import subprocess
import sys
import tempfile


def main() -> int:
    bench, scene = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as tmp:
        figures = os.path.join(tmp, "figures.json")
        scratch = os.path.join(tmp, "scratch")  # the benchmark's temporary folder goes here (TMPDIR)
        os.mkdir(scratch)
        run = subprocess.run([bench, "--json", figures, "dataset", scene, "--resolution", "64x48", "--frames", "3"],
                             capture_output=True, text=True, env=dict(os.environ, TMPDIR=scratch), timeout=240)
        assert run.returncode == 0, run.stderr
        with open(figures) as f:
            fig = json.load(f)
        assert os.listdir(scratch) == [], f"left behind: {os.listdir(scratch)}"

    assert fig["frames"] == 3 and fig["resolution"] == "64x48", fig
    wall = fig["seconds_per_frame"]
    assert wall > 0 and abs(fig["frames_per_second"] * wall - 1.0) < 1e-9, fig
    assert abs(fig["cpu_utilisation"] - fig["cpu_seconds_per_frame"] / wall) < 1e-9, fig
    assert fig["cpu_seconds_per_frame"] > 0, fig
    # A frame's files are on disk one frame after it rendered: each interval holds at least one render.
    assert 0 < fig["render_seconds"] and 0 < fig["write_seconds"] and fig["wait_seconds"] >= 0, fig
    assert fig["setup_seconds"] > 0 and fig["first_frame_seconds"] > 0 and fig["manifest_seconds"] > 0, fig
    assert fig["bytes_per_frame"] > 64 * 48, fig  # at least one byte a pixel: the colour EXRs alone are more
    print(json.dumps(fig, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
