#!/usr/bin/env python3
"""The CFL numbers at which the explicit step is stable, per basis
(issue 12): each scene is run with each basis at CFL numbers from 0.5 to 1,
and a run is stable if it reaches its end time without a run-health guard
stopping it (energy growth beyond 'Simulation/energy growth bound', J
bounds, an inverted or non-finite point). The verification bounds are
switched off: accuracy is not the question here. Prints one CSV row per
run and, per basis, the largest CFL number below which every scene was
stable; 'Simulation/CFL number' allows the smallest of those (the sweep
lifts that limit through the environment variable DEALII_MPM_MAX_CFL).

  cfl_range.py --exe build/dealii-mpm [--cfl 0.5,0.6,...] [--bases linear,...]
"""
import argparse, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_runner import run_scene  # noqa: E402

SCENES = {
    "two_disks": "../tests/two_disks.prm",
    "block_settling": "../tests/block_settling.prm",
    "block_3d": "../tests/block_3d.prm",
}
BASES = {"linear": "linear", "uGIMP": "uGIMP", "cpGIMP": "cpGIMP",
         "QBS": "quadratic B-spline", "CBS": "cubic B-spline"}
QUIET = ["-s", "Verification/energy change bound=0",
         "-s", "Verification/momentum change bound=0",
         "-s", "Verification/error bound=0"]


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--exe", required=True)
    parser.add_argument("--cfl", default="0.5,0.6,0.7,0.8,0.9,1")
    parser.add_argument("--bases", default=",".join(BASES))
    parser.add_argument("--scenes", default=",".join(SCENES))
    a = parser.parse_args()
    cfls = [float(c) for c in a.cfl.split(",")]
    # The program refuses CFL numbers above its measured limit; lift it.
    os.environ["DEALII_MPM_MAX_CFL"] = str(max(cfls))
    print("scene,basis,cfl,stable,steps,diagnosis")
    largest = {}
    for basis in a.bases.split(","):
        limit = max(cfls)
        for scene in a.scenes.split(","):
            for cfl in cfls:
                r = run_scene(a.exe, SCENES[scene],
                              ["-s", "Simulation/basis=" + BASES[basis],
                               "-s", "Simulation/CFL number=%g" % cfl] + QUIET,
                              check=False)
                stable = r.returncode == 0
                steps = r.rows[-1]["step"] if r.rows else ""
                diagnosis = "" if stable else \
                    r.stderr.split("run stopped: ")[-1].replace(",", ";")[:90]
                print("%s,%s,%g,%d,%s,%s" % (scene, basis, cfl, stable, steps,
                                             diagnosis), flush=True)
                if not stable:
                    limit = min(limit, max([c for c in cfls if c < cfl],
                                           default=0))
                    break
        largest[basis] = limit
    for basis, limit in largest.items():
        print("# %s: stable on every scene up to CFL %g" % (basis, limit))
    print("# every basis: up to CFL %g" % min(largest.values()))


if __name__ == "__main__":
    main()
