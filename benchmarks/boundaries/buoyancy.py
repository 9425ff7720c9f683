#!/usr/bin/env python3
"""Virtual fluid (the virtual stress method): buoyancy and hydrostatic stress.

  floating   floating_block.prm: a block of density 500 in a fluid of
             density 1000 comes to rest at the draft H rho_s / rho_f; the
             draft is the fluid level minus the block's lowest points less
             half a point spacing.
  submerged  submerged_block.prm: a block of density 2000 on the floor under
             the fluid; the points' sigma_xx and sigma_yy against -p(y) and
             -p(y) - (rho_s - rho_f) g (H - y): RMS error over RMS exact.

Prints one CSV row per case and configuration (cells, basis):

  buoyancy.py --exe build/dealii-mpm
  buoyancy.py --exe ... --configs 32:linear --check --max-error 0.02,0.05
"""
import argparse, math, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_runner import cost, overrides, run_scene, sweep_arguments  # noqa: E402

G = 9.81


def floating(exe, cells, basis, extra):
    result = run_scene(exe, "boundaries/floating_block.prm", [
        "-s", "Grid/cells=%d" % cells, "-s", "Simulation/basis=" + basis] + extra)
    spacing = 1.0 / cells / 2
    draft = 0.5 - (float(result.rows[-1]["body0_y_min"]) - spacing / 2)
    exact = 0.25 * 500 / 1000
    return draft, exact, draft / exact - 1, cost(result)[0]


def submerged(exe, cells, basis, extra):
    result = run_scene(exe, "boundaries/submerged_block.prm", [
        "-s", "Grid/cells=%d" % cells, "-s", "Simulation/basis=" + basis] + extra,
        frame=-1, fields="stress, displacement",
        frame_fields=("stress", "displacement"))
    error = exact = 0
    for p, t, d in zip(result.points, result.fields["stress"],
                       result.fields["displacement"]):
        y0 = p[1] - d[1]
        pressure = 1000 * G * (0.75 - y0)
        sxx, syy = -pressure, -pressure - 1000 * G * (0.5 - y0)
        error += (t[0] - sxx) ** 2 + (t[4] - syy) ** 2
        exact += sxx ** 2 + syy ** 2
    return math.sqrt(error / exact), cost(result)[0]


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sweep_arguments(parser)
    parser.add_argument("--configs", default="16:linear,32:linear,64:linear,"
                        "32:uGIMP,32:quadratic B-spline")
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--max-error", default="0.02,0.05",
                        help="bounds of the draft error and the stress error")
    a = parser.parse_args()
    max_draft, max_stress = [float(v) for v in a.max_error.split(",")]
    print("case,cells,basis,measured,exact,error,wall_seconds")
    ok = True
    for config in a.configs.split(","):
        cells, basis = config.split(":")
        cells = int(cells)
        draft, exact, e, wall = floating(a.exe, cells, basis, overrides(a))
        print("floating,%d,%s,%.5f,%.5f,%.2e,%.2f" % (cells, basis, draft, exact, e, wall),
              flush=True)
        stress_error, wall = submerged(a.exe, cells // 2, basis, overrides(a))
        print("submerged,%d,%s,,,%.2e,%.2f" % (cells // 2, basis, stress_error, wall),
              flush=True)
        ok = ok and abs(e) <= max_draft and stress_error <= max_stress
    if a.check and not ok:
        print("FAILED: draft error above %g or stress error above %g"
              % (max_draft, max_stress))
        sys.exit(1)


if __name__ == "__main__":
    main()
