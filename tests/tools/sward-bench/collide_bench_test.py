"""sward-bench collide --tick-rate (render/benchmarks.cpp): paced ticks start 1 / rate seconds apart, as in a
real-time loop, and give the same contacts as ticks back to back.

Usage: collide_bench_test.py SWARD_BENCH"""
import json
import os
import subprocess
import sys
import tempfile
import time

TICKS, WARMUP, RATE = 4, 1, 10.0


def collide(bench: str, tmp: str, rate: float) -> tuple[dict, float]:
    figures = os.path.join(tmp, f"collide-{rate}.json")
    start = time.monotonic()
    run = subprocess.run([bench, "--json", figures, "collide", "--no-gpu", "--density", "1", "--fields", "10",
                          "--ticks", str(TICKS), "--warmup", str(WARMUP), "--tick-rate", str(rate)],
                         capture_output=True, text=True, timeout=120)
    elapsed = time.monotonic() - start
    assert run.returncode == 0, run.stderr
    with open(figures) as f:
        return json.load(f), elapsed


def main() -> int:
    bench = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        paced, pacedSeconds = collide(bench, tmp, RATE)
        unpaced, _ = collide(bench, tmp, 0.0)
    assert paced["tick_rate"] == RATE and unpaced["tick_rate"] == 0.0, (paced, unpaced)
    # Five ticks are four periods apart: the paced run cannot be shorter.
    least = (TICKS + WARMUP - 1) / RATE
    assert pacedSeconds >= least, f"paced run took {pacedSeconds:.3f} s, at least {least:.3f} s expected"
    p, u = paced["results"][0], unpaced["results"][0]
    assert p["contacts_fnv1a"] == u["contacts_fnv1a"] and p["contacts"] == u["contacts"] > 0, (p, u)
    print(f"paced run {pacedSeconds:.3f} s (>= {least:.3f}), contacts {p['contacts']}, hash {p['contacts_fnv1a']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
