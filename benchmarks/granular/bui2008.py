#!/usr/bin/env python3
"""The collapse of a column of aluminium rods against the experiment of Bui,
Fukagawa, Sako and Ohno (2008).

Runs benchmarks/granular/bui2008.prm on a ladder of grid sizes h and prints
one CSV row per run: the toe of the deposit (the furthest point plus half
a point spacing; the furthest edge of a one-cell column where the deposit
is at least a rod thick, 1.5 mm, the experiment's coarser rods, since a
thinner layer is no deposit of rods; the front 99 % of the points stay
behind; and the furthest edge where the deposit is at least 5 mm thick,
the scene's 'Output/front thickness', which a thin sheet of points cannot
move), how far the column's top stays at its height next to the wall
(the plateau: the last x from the wall where the deposit's surface is
within 1 mm of 0.100 m), where the failure line meets the floor (the edge
of the undeformed zone: the furthest point of the bottom 5 mm that moved
less than 1 mm), the kinetic energy left (over the released potential
energy: the deposit must be at rest) and the cost. The measured values, as issue 29 quotes them: toe
0.44-0.46 m, plateau to x of about 0.03 m, failure line at the floor near
x = 0.18 m.

  bui2008.py --exe build/dealii-mpm                      the ladder
  bui2008.py --exe ... --h 0.005 --check                 a ctest
  bui2008.py --exe ... --plot bui2008.png                profiles beside
      the measurements (needs matplotlib)
  bui2008.py --exe ... -s "Simulation/transfer=FLIP"     another scheme
  bui2008.py --exe ... --floor wall:1                    another floor:
      fixed (the scene's no-slip grid face), friction:MU (the grid's
      Coulomb face) or wall:MU (a rigid wall with Coulomb friction MU, on
      the points, through the bottom row's centres two cells above a slip
      face; heights are measured from the column's bottom edge)
"""
import argparse, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_runner import (cost, overrides, points_per_cell,  # noqa: E402
                          run_scene, sweep_arguments)

WIDTH, HEIGHT = 0.6, 0.12  # the grid (m)
H0 = 0.1                   # the column's height (m)
TOE = (0.44, 0.46)         # measured toe (m)
PLATEAU = 0.03             # measured: the top kept for x up to about this
FAILURE_FOOT = 0.18        # measured: the failure line meets the floor
# The ctest's bounds: the toe as issue 29 asks (the experiment's range
# widened by the coarse grid's resolution), the plateau within a cell or
# two. With the rods' rate strengthening (mu(I), session 38) the shipped
# scene's toe a rod thick is 0.470, 0.460, 0.464 m at h = 5, 2.5, 1.25 mm;
# without it the continuum converged 13 % beyond the experiment (0.495,
# 0.500, 0.520).
CHECK_TOE = (0.42, 0.50)
CHECK_PLATEAU = (0.01, 0.06)
UNDEFORMED = 1e-3          # a point that moved less than this (m)
ROD = 1.5e-3               # the diameter of the coarser rods (m)


def surface(points, spacing, h):
    """The deposit's surface: (x, top) per column of one cell, top being
    the highest point plus half a point spacing."""
    top = {}
    for x, y, _ in points:
        k = int(x / h)
        top[k] = max(top.get(k, 0.), y + spacing / 2)
    return [((k + 0.5) * h, top[k]) for k in sorted(top)]


def toe_of_rods(profile, h):
    """The furthest edge of a column of the surface at least a rod thick."""
    return max((x + h / 2 for x, top in profile if top >= ROD), default=0.)


def plateau_end(profile, h):
    """The last x from the wall before the surface falls 1 mm below H0."""
    end = 0.
    for x, top in profile:
        if top < H0 - 1e-3:
            break
        end = x + h / 2
    return end


def failure_line(points, displacement, spacing):
    """The edge of the undeformed zone: per row of one spacing, the
    furthest initial x of a point that moved less than UNDEFORMED."""
    edge = {}
    for (x, y, _), u in zip(points, displacement):
        x0, y0 = x - u[0], y - u[1]
        if (u[0] ** 2 + u[1] ** 2) ** 0.5 < UNDEFORMED:
            k = int(y0 / spacing)
            edge[k] = max(edge.get(k, 0.), x0 + spacing / 2)
    return [(edge[k], (k + 0.5) * spacing) for k in sorted(edge)]


def floor_overrides(floor, h, spacing):
    """The overrides that make the floor @p floor, and the height of the
    column's bottom above the grid's bottom."""
    kind, _, mu = floor.partition(":")
    if kind == "fixed":
        return [], 0.
    if kind == "friction":
        return ["-s", "Grid/boundary y min=friction",
                "-s", "Grid/friction coefficient=" + mu], 0.
    if kind != "wall":
        raise ValueError("--floor: fixed, friction:MU or wall:MU")
    # The wall acts at the points' centres (the body's edge sinks half a
    # spacing into it), so it goes through the bottom row's centres: the
    # column does not settle onto it. Two cells of grid below keep the
    # points that its penalty lets in inside the grid.
    y0 = 2 * h
    return ["-s", "Grid/upper corner=%g, %g" % (WIDTH, HEIGHT + y0),
            "-s", "Grid/boundary y min=slip",
            "-s", "Bodies/Body 0/lower corner=0, %g" % y0,
            "-s", "Bodies/Body 0/upper corner=0.2, %g" % (H0 + y0),
            "-s", "Simulation/constants=H=%g, rho=2650, g=9.81, K0=0.661"
            % (H0 + y0),
            "-s", "Boundary conditions/number of rigid walls=1",
            "-s", "Boundary conditions/Rigid wall 0/point=0, %g"
            % (y0 + spacing / 2),
            "-s", "Boundary conditions/Rigid wall 0/normal=0, 1",
            "-s", "Boundary conditions/Rigid wall 0/friction coefficient="
            + mu], y0


def run(exe, h, extra, floor="fixed"):
    spacing = h / points_per_cell(extra)
    at_floor, y0 = floor_overrides(floor, h, spacing)
    nx, ny = round(WIDTH / h), round((HEIGHT + y0) / h)
    r = run_scene(exe, "granular/bui2008.prm",
                  ["-s", "Grid/cells=%d, %d" % (nx, ny)] + at_floor + extra,
                  frame=-1, fields="displacement",
                  frame_fields=("displacement",))
    last = r.rows[-1]
    points = [(x, y - y0, z) for x, y, z in r.points]
    toe = max(x for x, _, _ in points) + spacing / 2
    toe99 = float(last["body0_x_front_max"]) + spacing / 2
    toe_thick = float(last["body0_x_deposit_max"])
    profile = surface(points, spacing, h)
    line = failure_line(points, r.fields["displacement"], spacing)
    bottom = [x for x, y in line if y < 5e-3]
    foot = max(bottom) if bottom else 0.
    released = float(r.rows[0]["gravitational_energy"]) - \
        float(last["gravitational_energy"])
    rest = float(last["kinetic_energy"]) / max(released, 1e-300)
    wall, ns = cost(r)
    return dict(h=h, toe=toe, toe_rods=toe_of_rods(profile, h), toe99=toe99,
                toe_thick=toe_thick,
                plateau=plateau_end(profile, h), foot=foot, rest=rest,
                wall=wall, ns=ns, profile=profile, line=line)


def plot(runs, path, label):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 2.8))
    for r in runs:
        mm = r["h"] * 1e3
        ax.plot(*zip(*r["profile"]), "-", lw=1,
                label="surface, h = %g mm" % mm)
        ax.plot(*zip(*r["line"]), "--", lw=1,
                label="failure line (moved < 1 mm), h = %g mm" % mm)
    ax.plot([0, 0.2, 0.2], [H0, H0, 0], ":", color="gray",
            label="column at t = 0")
    ax.plot(TOE, [0, 0], "k-", lw=4, label="measured toe")
    ax.plot([0, PLATEAU], [H0, H0], "ks-", label="measured plateau")
    ax.plot([FAILURE_FOOT], [0], "k^", ms=8,
            label="measured failure line at the floor")
    ax.set_xlim(0, 0.5)
    ax.set_ylim(0, 0.11)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(fontsize=6, loc="upper right")
    ax.set_title("Bui et al. (2008) collapse: %s" % label, fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sweep_arguments(parser)
    parser.add_argument("--h", default="0.005,0.0025,0.00125",
                        help="grid sizes in m, comma-separated")
    parser.add_argument("--check", action="store_true",
                        help="fail unless every toe (a rod thick) lies in "
                        "%g-%g m, every "
                        "plateau in %g-%g m and every deposit is at rest" %
                        (CHECK_TOE + CHECK_PLATEAU))
    parser.add_argument("--floor", default="fixed",
                        help="fixed, friction:MU or wall:MU")
    parser.add_argument("--plot", help="PNG of the profiles")
    parser.add_argument("--label",
                        default="MUSL, FLIP with PIC relaxation 0.1 s, "
                        "quadratic B-spline, mu(I)",
                        help="the scheme, for the plot's title")
    a = parser.parse_args()
    extra = overrides(a)
    print("h,toe,toe_rods,toe_99,toe_5mm,plateau,failure_foot,"
          "kinetic_over_released,wall_seconds,ns_per_particle_step")
    runs, ok = [], True
    for h in [float(x) for x in a.h.split(",")]:
        r = run(a.exe, h, extra, a.floor)
        runs.append(r)
        print("%g,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.2e,%.2f,%.1f" % (
            h, r["toe"], r["toe_rods"], r["toe99"], r["toe_thick"],
            r["plateau"], r["foot"], r["rest"], r["wall"], r["ns"]),
            flush=True)
        ok = ok and CHECK_TOE[0] <= r["toe_rods"] <= CHECK_TOE[1] and \
            CHECK_PLATEAU[0] <= r["plateau"] <= CHECK_PLATEAU[1] and \
            r["rest"] < 1e-3
    if a.plot:
        plot(runs, a.plot, a.label)
    if a.check and not ok:
        print("FAILED: a toe or plateau lies outside its bounds or a deposit "
              "is still moving")
        sys.exit(1)


if __name__ == "__main__":
    main()
