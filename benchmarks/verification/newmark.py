#!/usr/bin/env python3
"""Newmark's gamma on the vibrating bar (issue 11).

The bar of verification/vibrating_bar.prm (fixed at x = 0, free at L = 25,
c = 10 m/s: mode 1 has the period T = 4 L / c = 10 s) in its first mode at
v0 = 0.01 (small strain), over one period at fixed time steps dt, for each
gamma (0.5 is central difference: the plain step). Measured per run:

  period        twice the time between the two zero crossings of the
                momentum (linear interpolation between outputs, one per step)
  energy_error  total energy after one period / initial - 1

and, per gamma, the observed order in dt of the period's time error
(from successive differences, which remove the grid's own dispersion) and
of the energy error. One CSV row per run, then '# ' lines with the orders.

  newmark.py --exe build/dealii-mpm
  newmark.py --exe ... --check    fails unless gamma = 1/2 is second order
                                  in the period and loses no energy beyond
                                  1e-3, and each gamma > 1/2 loses energy at
                                  first order in dt (order 0.8-1.2)
"""
import argparse, math, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_runner import overrides, run_scene, sweep_arguments  # noqa: E402


def zero_crossings(rows):
    out = []
    for a, b in zip(rows, rows[1:]):
        pa, pb = float(a["momentum_x"]), float(b["momentum_x"])
        if pa > 0 >= pb or pa < 0 <= pb:
            ta, tb = float(a["time"]), float(b["time"])
            out.append(ta + (tb - ta) * pa / (pa - pb))
    return out


def run(exe, gamma, dt, extra):
    r = run_scene(exe, "verification/vibrating_bar.prm", [
        "-s", "Simulation/Newmark gamma=%g" % gamma,
        "-s", "Simulation/time step=%g" % dt,
        "-s", "Bodies/Body 0/initial velocity=0.01*sin(pi/50*x)",
        "-s", "Verification/amplitude=0.01",
        "-s", "Output/interval=%g" % dt] + extra)
    crossings = zero_crossings(r.rows)
    period = 2 * (crossings[1] - crossings[0]) if len(crossings) >= 2 else float("nan")
    e0, e1 = float(r.rows[0]["total_energy"]), float(r.rows[-1]["total_energy"])
    return period, e1 / e0 - 1


def order(values):
    """Orders from a ladder halving dt: from successive differences."""
    d = [abs(a - b) for a, b in zip(values, values[1:])]
    return [math.log2(a / b) if a > 0 and b > 0 else float("nan")
            for a, b in zip(d, d[1:])]


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sweep_arguments(parser)
    parser.add_argument("--gammas", default="0.5,0.55,0.6,0.75")
    parser.add_argument("--dts", default="0.04,0.02,0.01,0.005")
    parser.add_argument("--check", action="store_true")
    a = parser.parse_args()
    extra = overrides(a)
    dts = [float(x) for x in a.dts.split(",")]
    print("gamma,dt,period,period_error,energy_error")
    failures = []
    for gamma in [float(g) for g in a.gammas.split(",")]:
        periods, energies = [], []
        for dt in dts:
            period, energy = run(a.exe, gamma, dt, extra)
            periods.append(period)
            energies.append(energy)
            print("%g,%g,%.6f,%.3e,%.3e" % (gamma, dt, period, period / 10 - 1,
                                            energy), flush=True)
        period_orders = order(periods)
        energy_orders = [math.log2(abs(e0 / e1)) for e0, e1 in zip(energies, energies[1:])]
        print("# gamma %g: period time-error orders %s, energy-error orders %s" % (
            gamma, ", ".join("%.2f" % o for o in period_orders),
            ", ".join("%.2f" % o for o in energy_orders)), flush=True)
        if gamma == 0.5:
            if not min(period_orders) >= 1.8:
                failures.append("gamma 0.5: period order %s below 1.8" % period_orders)
            if not max(abs(e) for e in energies) <= 1e-3:
                failures.append("gamma 0.5: energy error %s beyond 1e-3" % energies)
        else:
            if not all(e < 0 for e in energies):
                failures.append("gamma %g: energy not lost: %s" % (gamma, energies))
            if not all(0.8 <= o <= 1.2 for o in energy_orders):
                failures.append("gamma %g: energy-loss orders %s not 0.8-1.2" % (
                    gamma, energy_orders))
    if a.check and failures:
        for f in failures:
            print("FAILED: " + f)
        sys.exit(1)


if __name__ == "__main__":
    main()
