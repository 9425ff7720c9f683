#!/usr/bin/env python3
"""Quasi-static helpers (issue 11): how many steps the settling column
(tests/block_settling.prm: an elastic block under gravity on a slip floor,
exact sigma_yy = -rho g (H - y0)) needs to reach its static stress.

For each configuration prints the step (and time) from which the stress
error stays within --bound to the end, the error and kinetic energy at the
end, and the wall time:

  global    the shipped global damping, c = 10 /s
  local     Cundall's local damping, alpha = 0.8, no global damping
  local+ms  the same with mass scaling 100 (time step x 10)
  kinetic   kinetic damping (dynamic relaxation) once per macro step of
            5 ms (substeps from the CFL condition), no other damping

  quasi_static.py --exe build/dealii-mpm
  quasi_static.py --exe ... --check     local, local+ms and kinetic settle
                                        in fewer steps than global
"""
import argparse, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_runner import cost, overrides, run_scene, sweep_arguments  # noqa: E402

CONFIGS = {
    "global": [],
    "local": ["-s", "Simulation/damping=0", "-s", "Simulation/local damping=0.8"],
    "local+ms": ["-s", "Simulation/damping=0", "-s", "Simulation/local damping=0.8",
                 "-s", "Simulation/mass scaling=100", "-s", "Simulation/end time=3"],
    "kinetic": ["-s", "Simulation/damping=0", "-s", "Simulation/macro time step=0.005",
                "-s", "Simulation/kinetic damping=true"],
}


def settled(exe, config, bound, extra):
    r = run_scene(exe, "../tests/block_settling.prm", CONFIGS[config] + [
        "-s", "Output/interval=0.02", "-s", "Verification/error bound=0"] + extra)
    rows = r.rows
    since = None
    for row in rows:
        if float(row["error"]) <= bound:
            since = since or row
        else:
            since = None
    return since, rows[-1], cost(r)[0]


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sweep_arguments(parser)
    parser.add_argument("--bound", type=float, default=0.08)
    parser.add_argument("--check", action="store_true")
    a = parser.parse_args()
    print("config,settled_at_step,settled_at_time,end_error,end_kinetic_energy,"
          "wall_seconds")
    steps = {}
    for config in CONFIGS:
        since, last, wall = settled(a.exe, config, a.bound, overrides(a))
        steps[config] = int(since["step"]) if since else float("inf")
        print("%s,%s,%s,%.4f,%.3g,%.2f" % (
            config, since["step"] if since else "never",
            since["time"] if since else "", float(last["error"]),
            float(last["kinetic_energy"]), wall), flush=True)
    slower = [c for c in CONFIGS if c != "global" and not steps[c] < steps["global"]]
    if a.check and slower:
        print("FAILED: %s do(es) not settle in fewer steps than the global "
              "damping" % ", ".join(slower))
        sys.exit(1)


if __name__ == "__main__":
    main()
