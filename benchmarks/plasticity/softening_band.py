#!/usr/bin/env python3
"""Softening in a shear band on a ladder of grids, local and regularised
(benchmarks/plasticity/softening_band.prm, issue 33 item 3).

For each cell size h of --ladder and each softening of --softenings
(local; 'shear band thickness' = --band; nonlocal: 'nonlocal length' =
--nonlocal-length with --nonlocal-factor and --nonlocal-weight), one CSV
row: the peak axial force (per metre,
2 c = 20 kN/m for Tresca), the platen's displacement at the peak, the
softening slip (how far the platen moves from the peak until the force has
fallen halfway from the peak to the residual 2 c_r = 4 kN/m: the measure
of how brittle the specimen is), the force at the end, and the cost.
Local softening's slip shrinks with h (the band is a cell wide); the
band-scaled one's grows (the band is wider than a cell on fine grids); the
nonlocal one's should converge.

  python3 benchmarks/plasticity/softening_band.py --exe build/dealii-mpm
      [--ladder 0.1,0.05,0.025] [--band 0.1]

--check (the ctest): on each grid, the peak lies within --peak-tolerance
of 2 c; the slip of the finest grid over the coarsest's lies in
--local-ratio LOW,HIGH for local softening (it shrinks like h), in
--band-ratio LOW,HIGH for the band-scaled one (it does not shrink) and in
--nonlocal-ratio LOW,HIGH for the nonlocal one (it stays).
"""
import argparse, csv, os, subprocess, sys, tempfile, time

HERE = os.path.dirname(os.path.abspath(__file__))
SPEED = 0.02             # m/s, the platen's
PEAK = 2e4               # 2 c per metre of width
RESIDUAL = 4e3           # 2 c_r


MC = "Bodies/Body 0/Mohr-Coulomb/"


def softening_settings(a, name):
    """The -s arguments of a softening: local, band or nonlocal."""
    if name == "local":
        return []
    if name == "band":
        return ["-s", MC + "shear band thickness=%g" % a.band]
    return ["-s", MC + "nonlocal length=%g" % a.nonlocal_length,
            "-s", MC + "nonlocal factor=%g" % a.nonlocal_factor,
            "-s", MC + "nonlocal weight=" + a.nonlocal_weight]


def label(a, name):
    if name == "band":
        return "band %g m" % a.band
    if name == "nonlocal":
        return "nonlocal %g m %s m=%g" % (a.nonlocal_length,
                                          a.nonlocal_weight,
                                          a.nonlocal_factor)
    return name


def run(a, h, name):
    cells = "%d,%d" % (round(2 / h), round(2.5 / h))
    extra = softening_settings(a, name) + a.set
    with tempfile.TemporaryDirectory() as out:
        start = time.time()
        r = subprocess.run([a.exe, os.path.join(HERE, "softening_band.prm"),
                            "-s", "Grid/cells=" + cells,
                            "-s", "Output/directory=" + out,
                            "-s", "Output/progress interval=1e9",
                            "-s", "Simulation/end time=%g" % a.end_time]
                           + extra,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           text=True)
        if r.returncode != 0:
            raise RuntimeError(r.stderr)
        rows = list(csv.DictReader(open(os.path.join(out,
                                                     "statistics.csv"))))
        seconds = time.time() - start
    curve = [(float(r["time"]) * SPEED, -float(r["region_force_y"]))
             for r in rows]
    peak_at, peak = max(curve, key=lambda c: c[1])
    half = 0.5 * (peak + RESIDUAL)
    after = [(d, f) for d, f in curve if d > peak_at]
    slip = float("nan")
    for (d0, f0), (d1, f1) in zip(after, after[1:]):
        if f1 <= half < f0:
            slip = d0 + (f0 - half) / (f0 - f1) * (d1 - d0) - peak_at
            break
    return {"peak": peak, "peak_at": peak_at, "slip": slip,
            "final": curve[-1][1], "seconds": seconds}


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--exe", required=True)
    p.add_argument("--ladder", default="0.1,0.05,0.025")
    p.add_argument("--softenings", default="local,band,nonlocal",
                   help="which of local, band, nonlocal to run")
    p.add_argument("--band", type=float, default=0.1)
    p.add_argument("--nonlocal-length", type=float, default=0.2)
    p.add_argument("--nonlocal-factor", type=float, default=2)
    p.add_argument("--nonlocal-weight", default="bell")
    p.add_argument("-s", "--set", action="append", default=[],
                   help="a further -s PATH=VALUE for every run")
    p.add_argument("--end-time", type=float, default=1.5)
    p.add_argument("--check", action="store_true")
    p.add_argument("--peak-tolerance", type=float, default=0.05)
    p.add_argument("--local-ratio", default="0.4,0.65")
    p.add_argument("--band-ratio", default="0.9,1.5")
    p.add_argument("--nonlocal-ratio", default="0.85,1.15")
    a = p.parse_args()
    a.set = [x for pair in a.set for x in ("-s", pair)]
    names = a.softenings.split(",")
    print("h,softening,peak_N_per_m,peak_at_m,softening_slip_m,"
          "final_N_per_m,wall_seconds")
    slips = {name: [] for name in names}
    failures = []
    for h in [float(x) for x in a.ladder.split(",")]:
        for name in names:
            m = run(a, h, name)
            slips[name].append(m["slip"])
            print("%g,%s,%.0f,%.4f,%.4f,%.0f,%.1f" % (
                h, label(a, name), m["peak"],
                m["peak_at"], m["slip"], m["final"], m["seconds"]))
            sys.stdout.flush()
            if a.check and abs(m["peak"] / PEAK - 1) > a.peak_tolerance:
                failures.append("peak %g N/m at h = %g, not within %g of %g"
                                % (m["peak"], h, a.peak_tolerance, PEAK))
    if a.check:
        bounds = {"local": a.local_ratio, "band": a.band_ratio,
                  "nonlocal": a.nonlocal_ratio}
        for name in names:
            ratio = slips[name][-1] / slips[name][0]
            low, high = [float(x) for x in bounds[name].split(",")]
            print("slip ratio finest / coarsest, %s: %.3f" % (name, ratio))
            if not low <= ratio <= high:
                failures.append("%s slip ratio %g, not in [%g, %g]"
                                % (name, ratio, low, high))
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
