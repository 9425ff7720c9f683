#!/usr/bin/env python3
"""A disk on an incline under multi-body contact (rolling_disk.prm).

Prints one CSV row per run: friction coefficient, cells across the disk's
radius, the acceleration of the disk's centre along the incline (a linear
fit of momentum_x / disk mass over t in [0.05, 0.4] s: the floor is rigid
and does not move), the exact value (rolling: (2/3) g sin(theta) =
3.270 m/s^2 when mu >= tan(theta)/3; sliding: g (sin(theta) - mu
cos(theta)), at least 0), the relative error, and the largest speed of the
disk normal to the incline (bouncing) over that interval.

  rolling_disk.py --exe build/dealii-mpm --mu 0,1 --cells 5,10
  rolling_disk.py --exe ... --mu 0 --check --max-error 0.02
  rolling_disk.py --exe ... --mu 1 --floor-density 1000,1,1e-300 --check
  rolling_disk.py --exe ... --mu 0,0.1 --friction-work --check
      also the contact's work (statistics column contact_work, with the
      energy residual): within 2 % of mu N times the slip of the disk's
      contact point, v_x + omega_z R integrated over time (omega from the
      disk's angular momentum about its centre; no more than 0.01 J where
      mu = 0), and the energy residual within 1 % of the energy put in

The floor is a prescribed (rigid) body: its density must not change the
disk's motion. With several --floor-density values, --check also asserts
that they give the same acceleration to 1e-9 (issue 32: before, a light
floor moved the small-mass guard's threshold, and at 1e-300 it stopped
acting).
"""
import argparse, math, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_runner import least_squares_slope, overrides, run_scene, sweep_arguments  # noqa: E402

G, THETA, RADIUS = 9.81, math.pi / 6, 0.1
FLOOR_VOLUME = 1.2 * 0.04  # the rigid floor box of rolling_disk.prm


def exact(mu):
    rolling = 2 / 3 * G * math.sin(THETA)
    if mu >= math.tan(THETA) / 3:
        return rolling
    return max(0, G * (math.sin(THETA) - mu * math.cos(THETA)))


def friction_work(rows, mu, disk_mass):
    """The contact's work by the last row (J, > 0 taken out), mu N times
    the slip of the disk's contact point (its centre stays at y = 0.14 on
    the floor's top, 0.04), and the energy residual over the energy put
    in."""
    slip_rate, t = [], []
    for row in rows:
        v_x = float(row["momentum_x"]) / disk_mass
        v_y = float(row["momentum_y"]) / disk_mass
        x_c = 0.5 * (float(row["body0_x_front_min"]) +
                     float(row["body0_x_front_max"]))
        spin = float(row["angular_momentum_z"]) - disk_mass * (
            x_c * v_y - 0.14 * v_x)
        omega = spin / (0.5 * disk_mass * RADIUS ** 2)
        slip_rate.append(v_x + omega * RADIUS)
        t.append(float(row["time"]))
    slip = sum(0.5 * (slip_rate[i] + slip_rate[i + 1]) * (t[i + 1] - t[i])
               for i in range(len(t) - 1))
    normal = disk_mass * G * math.cos(THETA)
    return -float(rows[-1]["contact_work"]), mu * normal * slip, \
        float(rows[-1]["energy_residual"])


def run(exe, mu, per_radius, floor_density, extra):
    n = per_radius
    r = run_scene(exe, "contact/rolling_disk.prm", [
        "-s", "Contact/friction coefficient=%g" % mu,
        "-s", "Bodies/Body 1/density=%s" % floor_density,
        "-s", "Grid/cells=%d, %d" % (12 * n, 3 * n)] + extra)
    samples = []
    bounce = 0
    for row in r.rows:
        t = float(row["time"])
        m = float(row["mass"]) - float(floor_density) * FLOOR_VOLUME
        if t >= 0.05 - 1e-9:
            samples.append((t, float(row["momentum_x"]) / m))
            bounce = max(bounce, abs(float(row["momentum_y"]) / m))
    energy = friction_work(r.rows, mu, m) \
        if "contact_work" in r.rows[0] else None
    return least_squares_slope(samples), bounce, energy


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sweep_arguments(parser)
    parser.add_argument("--mu", default="0,1")
    parser.add_argument("--cells", default="5",
                        help="cells across the disk's radius")
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--max-error", type=float, default=0.02)
    parser.add_argument("--friction-work", action="store_true",
                        help="account the energy (the energy residual) and "
                             "check the contact's work against mu N times "
                             "the slip")
    parser.add_argument("--floor-density", default="1000",
                        help="densities of the rigid floor (comma-separated)")
    a = parser.parse_args()
    print("mu,cells_per_radius,floor_density,acceleration,exact,relative_error,"
          "max_normal_speed,contact_work,mu_normal_slip,energy_residual")
    extra = overrides(a)
    if a.friction_work:
        extra += ["-s", "Simulation/energy residual=true"]
    ok = True
    for mu in [float(x) for x in a.mu.split(",")]:
        for n in [int(x) for x in a.cells.split(",")]:
            by_density = []
            for rho in a.floor_density.split(","):
                acceleration, bounce, energy = run(a.exe, mu, n, rho, extra)
                e = acceleration / exact(mu) - 1
                print("%g,%d,%s,%.4f,%.4f,%.2e,%.3f,%s" % (
                    mu, n, rho, acceleration, exact(mu), e, bounce,
                    ",,," if energy is None else "%.4f,%.4f,%.4f" % energy),
                    flush=True)
                ok = ok and abs(e) <= a.max_error
                if energy is not None:
                    work, expected, residual = energy
                    ok = ok and abs(residual) <= 0.01 and (
                        abs(work) <= 0.01 if mu == 0 else
                        abs(work / expected - 1) <= 0.02)
                by_density.append(acceleration)
            spread = max(by_density) - min(by_density)
            if spread > 1e-9 * abs(by_density[0]):
                print("# the floor's density changes the acceleration by %.3e"
                      % spread)
                ok = False
    if a.check and not ok:
        print("FAILED: an acceleration is off by more than %g, or the "
              "contact's work or the energy residual is off "
              "(--friction-work)" % a.max_error)
        sys.exit(1)


if __name__ == "__main__":
    main()
