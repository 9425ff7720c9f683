#!/usr/bin/env python3
"""A softening failure of the slope of slope.prm and its runout
(benchmarks/slope/runout.prm, issue 33 item 3).

Stage 0 brings the slope to equilibrium at its peak strength; stage 1
drops the cohesion and lets it soften (c -> 0, phi 20 -> 12 deg over a
plastic strain of 5 %) for 30 s without damping. For each grid of
--ladder (and each --scheme), one CSV row: cell size, the scheme, the
runout of the 99 % front and of the deposit front (at least 0.5 m thick)
beyond the toe (x = 0), how far the 99 % front moved in the last 5 s, the
foot of the slip surface (the smallest x of a point within 0.5 m of the
base whose plastic strain stayed below 0.5: the intact wedge's toe; the
slope's toe was at x = 0), the kinetic energy at the end over its largest (the
slide at rest), the energy residual over the energy put in (the
numerics' share: below 0 they dissipate), the points that left the
grid, the largest plastic strain, and the cost.

  python3 benchmarks/slope/runout.py --exe build/dealii-mpm
      [--ladder "30,6;60,12;120,24"] [--scheme "APIC:Simulation/transfer=APIC"]
      [--png doc/slope_runout.png]

--check (the ctest, on the first grid of --ladder): stage 0 ends in
equilibrium, stage 1 starts from its checkpoint (the points keep the
fields the softened soil needs), the mass is kept, the slope fails (the
deposit front passes the toe by more than --min-runout), it comes to
rest (kinetic energy below 1e-2 of its largest), the numerics create no
energy (residual at most --max-residual) and the deposit front's runout
lies in --expect LOW,HIGH.
"""
import argparse, csv, os, subprocess, sys, tempfile, time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from vtu_points import read_field, read_points  # noqa: E402


def run(a, cells, extra, out):
    command = [a.exe, a.prm,
               "-s", "Output/directory=" + out,
               "-s", "Output/progress interval=1e9",
               "-s", "Grid/cells=" + cells] + extra
    start = time.time()
    r = subprocess.run(command, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        raise RuntimeError(r.stderr)
    rows = list(csv.DictReader(open(os.path.join(out, "statistics.csv"))))
    return rows, time.time() - start, r.stdout


def last_frame(out):
    frames = sorted(f for f in os.listdir(out)
                    if f.startswith("particles_") and f.endswith(".pvtu"))
    return os.path.join(out, frames[-1])


def measure(rows, out):
    stage1 = [r for r in rows if r["stage"] == "1"]
    last = rows[-1]
    t_end = float(last["time"])
    before = [r for r in stage1 if float(r["time"]) <= t_end - 5 + 1e-9][-1]
    eqps = read_field(last_frame(out), "plastic_strain")
    largest_ke = max(float(r["kinetic_energy"]) for r in stage1)
    return {
        "release": float(stage1[0]["time"]),
        "runout99": -float(last["body0_x_front_min"]),
        "runout_deposit": -float(last["body0_x_deposit_min"]),
        "creep_last_5s": float(before["body0_x_front_min"]) -
        float(last["body0_x_front_min"]),
        "slip_foot": min([p[0] for p, e in zip(read_points(last_frame(out)),
                                                eqps)
                          if e[0] < 0.5 and p[1] < 0.5] or [30]),
        "rest": float(last["kinetic_energy"]) / largest_ke,
        "residual": float(last["energy_residual"]),
        "removed": float(last["removed"]),
        "mass_change": float(last["mass"]) / float(rows[0]["mass"]) - 1,
        "max_plastic_strain": max(e[0] for e in eqps),
    }


def picture(out, png, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    frame = last_frame(out)
    xyz = read_points(frame)
    eqps = [e[0] for e in read_field(frame, "plastic_strain")]
    fig, ax = plt.subplots(figsize=(10, 3.2))
    sc = ax.scatter([p[0] for p in xyz], [p[1] for p in xyz], c=eqps, s=4,
                    cmap="viridis", vmin=0, vmax=1)
    ax.plot([0, 20, 30], [0, 10, 10], "k--", lw=0.8, label="slope before")
    ax.set_aspect("equal")
    ax.set_xlim(-30, 30)
    ax.set_ylim(0, 11)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title)
    ax.legend(loc="upper left", fontsize=8)
    fig.colorbar(sc, ax=ax, label="equivalent plastic strain (clipped at 1)")
    fig.tight_layout()
    fig.savefig(png, dpi=120)


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--exe", required=True)
    p.add_argument("--prm", default=os.path.join(HERE, "runout.prm"),
                   help="the scene (a variant of runout.prm)")
    p.add_argument("--ladder", default="30,6;60,12;120,24")
    p.add_argument("--scheme", action="append", default=[],
                   help="NAME:path=value[:path=value...] (repeatable); "
                   "without, the scene's own scheme")
    p.add_argument("--png", help="picture of the deposit on the last grid")
    p.add_argument("--check", action="store_true")
    p.add_argument("--min-runout", type=float, default=2.0)
    p.add_argument("--max-residual", type=float, default=0.0)
    p.add_argument("--expect", type=lambda t: [float(x) for x in t.split(",")])
    a = p.parse_args()
    schemes = [("shipped", [])] + [
        (s.split(":")[0], sum((["-s", x] for x in s.split(":")[1:]), []))
        for s in a.scheme]
    ladder = a.ladder.split(";")
    if a.check:
        ladder = ladder[:1]
    keys = ["release", "runout99", "runout_deposit", "creep_last_5s",
            "slip_foot", "rest", "residual", "removed", "mass_change",
            "max_plastic_strain"]
    print("cell_size,scheme," + ",".join(keys) + ",wall_seconds")
    failures = []
    for cells in ladder:
        h = 60 / float(cells.split(",")[0])
        for name, extra in schemes:
            with tempfile.TemporaryDirectory() as out:
                rows, seconds, _ = run(a, cells, extra, out)
                m = measure(rows, out)
                # The numbers first: a picture that fails loses no run.
                print("%g,%s," % (h, name) +
                      ",".join("%.4g" % m[k] for k in keys) +
                      ",%.1f" % seconds)
                sys.stdout.flush()
                if a.png and cells == ladder[-1] and name == "shipped":
                    picture(out, a.png, "runout 30 s after the release, "
                            "%g m cells: points coloured by plastic strain"
                            % h)
            if a.check:
                if not m["release"] < 60:
                    failures.append("stage 0 did not end in equilibrium")
                if abs(m["mass_change"]) > 1e-12:
                    failures.append("mass changed by %g" % m["mass_change"])
                if not m["rest"] < 1e-2:
                    failures.append("not at rest: kinetic energy %g of its "
                                    "largest" % m["rest"])
                if not m["residual"] <= a.max_residual:
                    failures.append("the numerics created energy: residual "
                                    "%g > %g" % (m["residual"],
                                                 a.max_residual))
                runout = m["runout_deposit"]
                if not runout > a.min_runout:
                    failures.append("the slope did not fail: runout %g m"
                                    % runout)
                if a.expect and not (a.expect[0] <= runout <= a.expect[1]):
                    failures.append("runout %g m outside [%g, %g]" % (
                        runout, *a.expect))
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
