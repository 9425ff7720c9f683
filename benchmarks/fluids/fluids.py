#!/usr/bin/env python3
"""The Newtonian fluid (issue 10) against known answers.

  hydrostatic  hydrostatic_column.prm: every point's pressure against
               rho g (H - y) at the end; the largest error over rho g H.
  dam_break    dam_break.prm: the surge front against Martin and Moyce
               (1952), T = t sqrt(2 g / a), Z = x / a, the experiment's time
               shifted by -0.175 (gate opening); the largest |Z / Z_exp - 1|
               over the 15 measurements. --plot writes the curves as a PNG.
  soft_column  the hydrostatic column of a fluid so soft (K = rho g H / 10)
               that its own weight halves its volume at the bottom: the
               pressure of the Tait fluid in equilibrium,
                 p = K/gamma ((1 + (gamma-1) rho0 g (H-y) / K)^(gamma/(gamma-1)) - 1),
               given as the initial stress, must stay; the largest error
               over p(0). The compressed fluid carries waves sqrt(7) to 8
               times faster than at rest: a time step from K alone was
               unstable within 16 steps.

Prints one CSV row per case and resolution (cells across a = 0.2 for the
dam break, across the column height for the hydrostatic case):

  fluids.py --exe build/dealii-mpm
  fluids.py --exe ... --cases dam_break --cells 16 --check --max-error 0.1
"""
import argparse, math, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_runner import cost, overrides, run_scene, sweep_arguments  # noqa: E402

G = 9.81
# Martin and Moyce (1952), square column, n^2 = 2 (height 2a), as quoted in
# the issue.
MM_T = [0.41, 0.84, 1.19, 1.43, 1.63, 1.83, 1.98, 2.20, 2.32, 2.51, 2.65,
        2.83, 2.98, 3.11, 3.33]
MM_Z = [1.11, 1.22, 1.44, 1.67, 1.89, 2.11, 2.33, 2.56, 2.78, 3.00, 3.22,
        3.44, 3.67, 3.89, 4.11]
GATE_SHIFT = 0.175


def hydrostatic(exe, cells, extra):
    """Largest |p - rho g (H - y)| / (rho g H) at the end, with H = 1."""
    result = run_scene(exe, "fluids/hydrostatic_column.prm", [
        "-s", "Grid/cells=%d, %d" % (cells // 4, cells * 5 // 4)] + extra,
        frame=-1, fields="pressure", frame_fields=("pressure",))
    scale = 1000 * G * 1.0
    error = max(abs(p[0] - 1000 * G * (1.0 - x[1])) / scale
                for x, p in zip(result.points, result.fields["pressure"]))
    return error, cost(result)[0]


def soft_column(exe, cells, extra):
    """Largest |p - p_exact(y)| / p_exact(0) at the end, H = 1, gamma = 7.

    The points keep their reference positions to within far less than a
    cell (the column is at rest), so p_exact is taken at their end
    positions."""
    rho, g, H, K = 1000.0, G, 1.0, 981.0
    law = "K/7*((1+6*rho*g*(H-y)/K)^(7/6)-1)"

    def exact(y):
        return K / 7 * ((1 + 6 * rho * g * (H - y) / K) ** (7 / 6) - 1)
    stress = "-%s; -%s; -%s; 0" % (law, law, law)
    result = run_scene(exe, "fluids/hydrostatic_column.prm", [
        "-s", "Grid/cells=%d, %d" % (cells // 4, cells * 5 // 4),
        "-s", "Simulation/constants=rho=%g, g=%g, H=%g, K=%g" % (rho, g, H, K),
        "-s", "Bodies/Body 0/initial stress=" + stress,
        "-s", "Bodies/Body 0/Newtonian fluid/bulk modulus=%g" % K] + extra,
        frame=-1, fields="pressure", frame_fields=("pressure",))
    error = max(abs(p[0] - exact(x[1])) / exact(0.0)
                for x, p in zip(result.points, result.fields["pressure"]))
    return error, cost(result)[0]


def dam_break(exe, cells, extra):
    """(T, Z) of the simulated front, and the errors at the measurements."""
    a = 0.2
    h = a / cells
    result = run_scene(exe, "fluids/dam_break.prm", [
        "-s", "Grid/cells=%d, %d" % (round(1.1 / h), round(0.45 / h))] + extra,
        fields="pressure")
    spacing = h / 2  # 2 points per cell and direction
    times = [float(r["time"]) for r in result.rows]
    fronts = [float(r["body0_x_max"]) + spacing / 2 for r in result.rows]
    scale_t = math.sqrt(2 * G / a)

    def front_at(t):
        for i in range(1, len(times)):
            if times[i] >= t:
                w = (t - times[i - 1]) / (times[i] - times[i - 1])
                return fronts[i - 1] + w * (fronts[i] - fronts[i - 1])
        return fronts[-1]

    errors = [front_at((T - GATE_SHIFT) / scale_t) / a / Z - 1
              for T, Z in zip(MM_T, MM_Z)]
    curve = [(t * scale_t, x / a) for t, x in zip(times, fronts)]
    return curve, errors, cost(result)[0]


def plot(curves, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for cells, curve in curves:
        ax.plot([T + GATE_SHIFT for T, _ in curve], [Z for _, Z in curve], "-",
                label="dealii-mpm, a / h = %d (T + %.3f)" % (cells, GATE_SHIFT))
    ax.plot(MM_T, MM_Z, "ko", label="Martin and Moyce (1952)")
    ax.set_xlabel("T = t sqrt(2g/a)")
    ax.set_ylabel("Z = x / a")
    ax.set_xlim(0, 3.5)
    ax.set_ylim(1, 4.5)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("Dam break: surge front", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=80)


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sweep_arguments(parser)
    parser.add_argument("--cases", default="hydrostatic,dam_break")
    parser.add_argument("--cells", default="8,16,32")
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--max-error", default="0.02,0.1",
                        help="bounds of the hydrostatic and dam break errors")
    parser.add_argument("--plot", help="PNG of the dam break fronts")
    a = parser.parse_args()
    max_hydrostatic, max_front = [float(v) for v in a.max_error.split(",")]
    print("case,cells,error,wall_seconds")
    ok = True
    curves = []
    for cells in [int(c) for c in a.cells.split(",")]:
        if "hydrostatic" in a.cases:
            error, wall = hydrostatic(a.exe, cells, overrides(a))
            print("hydrostatic,%d,%.3e,%.2f" % (cells, error, wall), flush=True)
            ok = ok and error <= max_hydrostatic
        if "soft_column" in a.cases:
            error, wall = soft_column(a.exe, cells, overrides(a))
            print("soft_column,%d,%.3e,%.2f" % (cells, error, wall), flush=True)
            ok = ok and error <= max_hydrostatic
        if "dam_break" in a.cases:
            curve, errors, wall = dam_break(a.exe, cells, overrides(a))
            worst = max(errors, key=abs)
            print("dam_break,%d,%.3e,%.2f" % (cells, worst, wall), flush=True)
            print("#   Z / Z_exp - 1 at each T: " +
                  " ".join("%+.3f" % e for e in errors), flush=True)
            curves.append((cells, curve))
            ok = ok and abs(worst) <= max_front
    if a.plot and curves:
        plot(curves, a.plot)
    if a.check and not ok:
        print("FAILED: hydrostatic error above %g or front error above %g"
              % (max_hydrostatic, max_front))
        sys.exit(1)


if __name__ == "__main__":
    main()
