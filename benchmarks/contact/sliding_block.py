#!/usr/bin/env python3
"""Block sliding on a friction floor: deceleration and stop distance.

Runs benchmarks/contact/sliding_block.prm for each friction coefficient and
prints one CSV row per run: mu, the measured deceleration (from the mean
velocity, momentum_x / mass, between t = 0.05 and 0.15 s, while it slides)
against mu g, and the stop distance (the drift of body0_x_min at the end)
against v0^2 / (2 mu g), with relative errors.

  sliding_block.py --exe build/dealii-mpm                 mu = 0.1, 0.3, 0.5
  sliding_block.py --exe ... --check --max-error 0.02     a ctest assertion
"""
import argparse, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_runner import overrides, run_scene, sweep_arguments  # noqa: E402

G, V0 = 9.81, 1.0


def run(exe, mu, extra):
    stop_time = V0 / (mu * G)
    width = 0.4 + 1.1 * V0 ** 2 / (2 * mu * G)
    rows = run_scene(exe, "contact/sliding_block.prm", [
        "-s", "Grid/friction coefficient=%g" % mu,
        "-s", "Simulation/end time=%g" % (1.3 * stop_time),
        "-s", "Grid/upper corner=%g, 0.2" % width,
        "-s", "Grid/cells=%d, 8" % round(width / 0.025),
        "-s", "Output/interval=0.01"] + extra).rows
    speed = {round(float(r["time"]), 6): float(r["momentum_x"]) / float(r["mass"])
             for r in rows}
    t0, t1 = 0.05, min(0.15, 0.8 * stop_time)
    t1 = round(round(t1 / 0.01) * 0.01, 6)
    deceleration = (speed[t0] - speed[t1]) / (t1 - t0)
    distance = float(rows[-1]["body0_x_min"]) - float(rows[0]["body0_x_min"])
    return deceleration, distance


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sweep_arguments(parser)
    parser.add_argument("--mu", default="0.1,0.3,0.5")
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--max-error", type=float, default=0.02)
    a = parser.parse_args()
    print("mu,deceleration,exact_deceleration,deceleration_error,"
          "stop_distance,exact_stop_distance,stop_distance_error")
    ok = True
    for mu in [float(x) for x in a.mu.split(",")]:
        deceleration, distance = run(a.exe, mu, overrides(a))
        exact_a, exact_d = mu * G, V0 ** 2 / (2 * mu * G)
        ea, ed = deceleration / exact_a - 1, distance / exact_d - 1
        print("%g,%.5f,%.5f,%.2e,%.5f,%.5f,%.2e" %
              (mu, deceleration, exact_a, ea, distance, exact_d, ed), flush=True)
        ok = ok and abs(ea) <= a.max_error and abs(ed) <= a.max_error
    if a.check and not ok:
        print("FAILED: an error exceeds %g" % a.max_error)
        sys.exit(1)


if __name__ == "__main__":
    main()
