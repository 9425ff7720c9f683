#!/usr/bin/env python3
"""Glen's flow law (issue 10): glen_slab.prm, a slab of the Maxwell
viscoelastic model with Glen's law (n = 3) on an incline, from rest to the
steady profile

  u(z) = 2 A / (n + 1) (rho g sin a)^n (H^(n+1) - (H - z)^(n+1)).

The error is the largest |u_x - u(z)| over the points of the slab's middle
(|x - 3| < 0.5) at the end, over the surface speed u(H); 'steadiness' is
the largest change of u_x there over the last 0.25 s, likewise scaled.
Prints one CSV row per resolution (cells across the thickness):

  glen_slab.py --exe build/dealii-mpm
  glen_slab.py --exe ... --cells 8 --check --max-error 0.05
"""
import argparse, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_runner import cost, overrides, run_scene, sweep_arguments  # noqa: E402

A, N, DRIVING = 1.58e-8, 3, 100.0  # rate factor, exponent, rho g sin a H
SURFACE_SPEED = 2 * A / (N + 1) * DRIVING ** N


def exact(z):
    return SURFACE_SPEED * (1 - (1 - z) ** (N + 1))


def slab(exe, cells, end_time, extra):
    result = run_scene(exe, "glaciology/glen_slab.prm", [
        "-s", "Grid/cells=%d, %d" % (7 * cells, cells * 5 // 4),
        "-s", "Simulation/end time=%g" % end_time,
        "-s", "Output/interval=0.25"] + extra,
        frame="all", fields="velocity", frame_fields=("velocity",))
    last, before = [(p, f["velocity"]) for p, f in
                    zip(result.points[-2:], result.fields[-2:])][::-1]
    middle = [i for i, x in enumerate(last[0]) if abs(x[0] - 3) < 0.5]
    error = max(abs(last[1][i][0] - exact(last[0][i][1])) for i in middle)
    change = max(abs(last[1][i][0] - before[1][i][0]) for i in middle)
    return error / SURFACE_SPEED, change / SURFACE_SPEED, cost(result)[0]


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sweep_arguments(parser)
    parser.add_argument("--cells", default="4,8,16")
    parser.add_argument("--end-time", type=float, default=1.5)
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--max-error", type=float, default=0.05)
    a = parser.parse_args()
    print("cells,error,steadiness,wall_seconds")
    ok = True
    for cells in [int(c) for c in a.cells.split(",")]:
        error, change, wall = slab(a.exe, cells, a.end_time, overrides(a))
        print("%d,%.3e,%.3e,%.2f" % (cells, error, change, wall), flush=True)
        ok = ok and error <= a.max_error and change <= a.max_error
    if a.check and not ok:
        print("FAILED: error or change above %g" % a.max_error)
        sys.exit(1)


if __name__ == "__main__":
    main()
