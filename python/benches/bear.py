"""Python against Rust on the bear (the paper's 28 curves, 96 points): the time of
``kappa.solve`` per pass over the drawing, and the fixed cost of a call.

    cargo bench --all-features --bench solve -- bear_cold     # the Rust side (criterion)
    python python/benches/bear.py [--repeat N]

The Rust figures are read from criterion's estimates (target/criterion/bear_cold/*/new/
estimates.json, the mean); without them only the Python side is printed. The target:
Python ≤ 2 × Rust + 2 µs per call (28 calls per pass).
"""

import argparse
import json
import time
from pathlib import Path

import kappa

ROOT = Path(__file__).resolve().parents[2]
CASES = [("kappa", "kappa", None), ("ek_cubic_0.85", "ek-cubic", 0.85), ("ek_trig_0.75", "ek-trig", 0.75)]


def best_of(f, repeat, rounds=5):
    """The best per-call time (s) over `rounds` rounds of `repeat` calls."""
    best = float("inf")
    for _ in range(rounds):
        t = time.perf_counter()
        for _ in range(repeat):
            f()
        best = min(best, (time.perf_counter() - t) / repeat)
    return best


def rust_mean(label):
    path = ROOT / "target" / "criterion" / "bear_cold" / label / "new" / "estimates.json"
    if not path.is_file():
        return None
    return json.loads(path.read_text())["mean"]["point_estimate"] * 1e-9


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=2000)
    args = ap.parse_args()
    bear = json.loads(kappa.builtin_design("bear"))
    curves = [(c["points"], True if c.get("closed") is None else c["closed"]) for c in bear["curves"]]
    calls = len(curves)
    rejected = best_of(lambda: _rejected(), args.repeat * 10)
    print(f"bear: {calls} curves, {sum(len(p) for p, _ in curves)} points")
    print(f"a call rejected at once (TooFewPointsError): {rejected * 1e6:.2f} µs")
    for label, scheme, shape in CASES:
        def one_pass():
            for pts, closed in curves:
                kappa.solve(pts, closed, scheme, shape)

        py = best_of(one_pass, max(1, args.repeat // 10))
        rust = rust_mean(label)
        line = f"{label:>14}: Python {py * 1e6:8.1f} µs per pass"
        if rust is not None:
            budget = 2 * rust + calls * 2e-6
            line += (f", Rust {rust * 1e6:8.1f} µs, ratio {py / rust:.2f}, "
                     f"overhead {(py - rust) / calls * 1e6:.2f} µs per call, "
                     f"{'within' if py <= budget else 'OVER'} 2x + 2 µs")
        print(line)


def _rejected():
    try:
        kappa.solve([(0, 0), (1, 1)], True)
    except kappa.TooFewPointsError:
        pass


if __name__ == "__main__":
    main()
