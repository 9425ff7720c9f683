#!/usr/bin/env python3
"""The energy residual against plasticity (issue 30, item 4).

The two disks of tests/two_disks.prm (time step 0.01 s, to t = 3.5 s, FLIP
1), elastic and with von Mises plasticity (yield stress 40 Pa: the impact
stress is about rho c v = 140 Pa, so the disks yield where they meet),
with `Simulation/energy residual`. Prints one CSV row per material and
scheme: the total energy's relative change at the end and the column
energy_residual there.

What must hold:
- elastic: the residual is the energy balance, to the order of the stress
  power's quadrature (|residual - change| <= --tolerance);
- plastic: the total energy falls by more than half (plasticity
  dissipates), yet USF's creation still shows (residual >= --usf-gain),
  as in the elastic run: the residual is not hidden by plasticity.

  energy_residual.py --exe build/dealii-mpm --check
"""
import argparse, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_runner import overrides, run_scene, sweep_arguments  # noqa: E402

PLASTIC = sum([["-s", "Bodies/Body %d/material=von Mises" % b,
                "-s", "Bodies/Body %d/von Mises/Young's modulus=1000" % b,
                "-s", "Bodies/Body %d/von Mises/Poisson's ratio=0.3" % b,
                "-s", "Bodies/Body %d/von Mises/yield stress=40" % b]
               for b in (0, 1)], [])


def run(exe, scheme, plastic, extra):
    r = run_scene(exe, "../tests/two_disks.prm", [
        "-s", "Simulation/update scheme=" + scheme,
        "-s", "Simulation/time step=0.01",
        "-s", "Simulation/end time=3.5",
        "-s", "Simulation/energy residual=true",
        "-s", "Output/interval=0.25",
        "-s", "Verification/energy change bound=0"] +
        (PLASTIC if plastic else []) + extra)
    first, last = r.rows[0], r.rows[-1]
    change = float(last["total_energy"]) / float(first["total_energy"]) - 1
    return change, float(last["energy_residual"]), float(last["time"])


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sweep_arguments(parser)
    parser.add_argument("--scheme", default="USF,MUSL,USL")
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--tolerance", type=float, default=0.01)
    parser.add_argument("--usf-gain", type=float, default=0.005)
    a = parser.parse_args()
    print("material,scheme,end_time,energy_change,energy_residual")
    ok = True
    for plastic in (False, True):
        material = "von Mises" if plastic else "elastic"
        for scheme in a.scheme.split(","):
            change, residual, t = run(a.exe, scheme, plastic, overrides(a))
            print("%s,%s,%g,%.5f,%.5f" % (material, scheme, t, change,
                                          residual))
            if not a.check:
                continue
            if t < 3.5 - 1e-9:
                ok = False
                print("  FAIL: stopped at t = %g" % t)
            if not plastic and abs(residual - change) > a.tolerance:
                ok = False
                print("  FAIL: elastic, the residual is not the balance")
            if plastic and change > -0.5:
                ok = False
                print("  FAIL: plasticity dissipated less than half")
            if plastic and scheme == "USF" and residual < a.usf_gain:
                ok = False
                print("  FAIL: USF's gain is hidden")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
