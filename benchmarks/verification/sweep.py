#!/usr/bin/env python3
"""Speed-against-error sweep for dealii-mpm (issue 3).

Runs every problem over a resolution ladder for every update scheme and
transfer, writes one CSV row per run, fits the observed order of the error
against the cell size, and (with --plots) draws error-vs-h and
error-vs-wall-time PNGs and regenerates doc/verification.md.

  sweep.py --exe build/dealii-mpm                        full sweep + report
  sweep.py --exe ... --problems mms_1d_small --ladder coarse --check
           --configs USL-FLIP --min-order 1.7 --max-error 1e-6
                                                         a ctest assertion

Each run's error is what the program itself reports against the exact
solution ('Verification' section of the scene); wall time and ns per
particle-step come from the run's timing.csv.
"""
import argparse, csv, math, os, re, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

MMS = "c=100, E=1e7, rho=1000, lambda=0, mu=5e6"


def mms_1d(amplitude, ppc=2):
    def overrides(n):
        return ["Grid/cells=%d" % n,
                "Simulation/time step=%.10g" % (0.2 / n / 100),
                "Simulation/constants=G=%g, %s" % (amplitude, MMS),
                "Bodies/Body 0/particles per cell=%d" % ppc]
    return overrides


NEO = "c=100, rho=1, mu=3846.153846153846, lambda=5769.230769230769"


IN_PHASE = "px=0, py=0, pz=0"
PHASED = "px=0, py=%.17g, pz=%.17g" % (2 * math.pi / 3, 4 * math.pi / 3)


def mms_axis(amplitude, phases=IN_PHASE):
    def overrides(n):
        return ["Grid/cells=%d" % n,
                "Simulation/constants=A=%g, %s, %s" % (amplitude, NEO, phases)]
    return overrides


def bar(n):
    # L = 25 on a 27 m grid: h = 27 / n.
    return ["Grid/cells=%d" % n]


def bar_position(n):
    # Mode 1 exactly: u = (v0 / omega) sin(beta X) sin(omega t),
    # beta = pi / 50, omega = 10 beta (c = 10 m/s).
    return bar(n) + [
        "Simulation/constants=v0=0.1, beta=%.17g, omega=%.17g" % (math.pi / 50, math.pi / 5),
        "Verification/exact solution=displacement",
        "Verification/exact displacement=v0/omega*sin(beta*x)*sin(omega*t)"]


def column(n):
    # Two cells wide (the cubic B-spline needs two); slip walls make the
    # width irrelevant to the exact solution.
    h = 1.25 / n
    return ["Grid/cells=2, %d" % n, "Grid/upper corner=%.10g, 1.25" % (2 * h),
            "Bodies/Body 0/upper corner=%.10g, 1" % (2 * h)]


VORTEX = "mu=384.6153846153846, rho=1000"


def vortex(amplitude):
    def overrides(n):
        return ["Grid/cells=%d" % n, "Simulation/constants=A=%g, %s" % (amplitude, VORTEX)]
    return overrides


def disks(n):
    # A bound that never fails makes the program print its drift verdict.
    return ["Grid/cells=%d" % n, "Verification/energy change bound=1e9"]


# name: (scene, overrides(n), ladders, h(n), error label in the output,
#        what the error measures)
PROBLEMS = {
    "mms_1d_small": ("mms_1d.prm", mms_1d(1e-4),
                     {"coarse": [16, 32, 64], "full": [8, 16, 32, 64, 128, 256]},
                     lambda n: 1.0 / n, "error (max over time)",
                     "1D MMS, G = 1e-4: sqrt(sum V (u - u_exact)^2), max over time"),
    "mms_1d_large": ("mms_1d.prm", mms_1d(0.05),
                     {"coarse": [16, 32, 64], "full": [8, 16, 32, 64, 128, 256]},
                     lambda n: 1.0 / n, "error (max over time)",
                     "1D MMS, G = 0.05 (cell crossing): same norm"),
    "mms_1d_small_ppc4": ("mms_1d.prm", mms_1d(1e-4, 4),
                          {"coarse": [16, 32, 64], "full": [8, 16, 32, 64, 128, 256]},
                          lambda n: 1.0 / n, "error (max over time)",
                          "1D MMS, G = 1e-4, 4 points per cell"),
    "mms_1d_large_ppc4": ("mms_1d.prm", mms_1d(0.05, 4),
                          {"coarse": [16, 32, 64], "full": [8, 16, 32, 64, 128, 256]},
                          lambda n: 1.0 / n, "error (max over time)",
                          "1D MMS, G = 0.05, 4 points per cell"),
    "mms_2d_small": ("mms_2d.prm", mms_axis(1e-4),
                     {"coarse": [8, 16], "full": [8, 16, 32, 64]},
                     lambda n: 1.0 / n, "error (max over time)",
                     "2D axis-aligned MMS, A = 1e-4 (in phase): sqrt(sum V |u - u_exact|^2)"),
    "mms_2d": ("mms_2d.prm", mms_axis(0.05),
               {"coarse": [8, 16], "full": [8, 16, 32, 64]},
               lambda n: 1.0 / n, "error (max over time)",
               "2D axis-aligned MMS, A = 0.05 (in phase, cell crossing)"),
    "mms_2d_phased": ("mms_2d.prm", mms_axis(0.05, PHASED),
                      {"coarse": [8, 16], "full": [8, 16, 32, 64]},
                      lambda n: 1.0 / n, "error (max over time)",
                      "2D axis-aligned MMS, A = 0.05, V shifted by 2 pi/3 (starts displaced)"),
    "mms_2d_phased_small": ("mms_2d.prm", mms_axis(1e-4, PHASED),
                            {"coarse": [8, 16], "full": [8, 16, 32, 64]},
                            lambda n: 1.0 / n, "error (max over time)",
                            "2D axis-aligned MMS, A = 1e-4, V shifted by 2 pi/3"),
    "mms_3d_small": ("mms_3d.prm", mms_axis(1e-4),
                     {"coarse": [4, 8], "full": [4, 8, 16]},
                     lambda n: 1.0 / n, "error (max over time)",
                     "3D axis-aligned MMS, A = 1e-4 (in phase)"),
    "mms_3d": ("mms_3d.prm", mms_axis(0.05),
               {"coarse": [4, 8], "full": [4, 8, 16]},
               lambda n: 1.0 / n, "error (max over time)",
               "3D axis-aligned MMS, A = 0.05 (in phase, cell crossing)"),
    "mms_3d_phased": ("mms_3d.prm", mms_axis(0.05, PHASED),
                      {"coarse": [4, 8], "full": [4, 8, 16]},
                      lambda n: 1.0 / n, "error (max over time)",
                      "3D axis-aligned MMS, A = 0.05, V and W shifted by 2 pi/3 and 4 pi/3"),
    "vibrating_bar_position": ("vibrating_bar.prm", bar_position,
                               {"coarse": [27, 54], "full": [27, 54, 108, 216]},
                               lambda n: 27.0 / n, "error (max over time)",
                               "bar, sqrt(sum V (u - u_exact)^2), max over one period"),
    "vibrating_bar": ("vibrating_bar.prm", bar,
                      {"coarse": [27, 54], "full": [27, 54, 108, 216]},
                      lambda n: 27.0 / n, "error (max over time)",
                      "bar, |v_com - exact| / v0, max over one period"),
    "self_weight_column": ("self_weight_column.prm", column,
                           {"coarse": [10, 20], "full": [5, 10, 20, 40, 80]},
                           lambda n: 1.25 / n, "error at the end",
                           "column, RMS(sigma_yy - exact) / (rho g H) at rest"),
    "vortex": ("vortex.prm", vortex(0.1),
               {"coarse": [24, 48], "full": [24, 48, 96]},
               lambda n: 3.0 / n, "error (max over time)",
               "generalized vortex, A = 0.1: sqrt(sum V |u - u_exact|^2), max over time"),
    "vortex_large": ("vortex.prm", vortex(1.0),
                     {"coarse": [48], "full": [48, 96]},
                     lambda n: 3.0 / n, "error (max over time)",
                     "generalized vortex, A = 1 (shear strain up to 6)"),
    "two_disks": ("two_disks.prm", disks,
                  {"coarse": [10, 20], "full": [10, 20, 40, 80]},
                  lambda n: 1.0 / n, "max energy change",
                  "two disks, max |E(t) - E(0)| / E(0) (no exact field)"),
}

BASES = {  # short name: value of Simulation/basis
    "linear": "linear", "uGIMP": "uGIMP", "cpGIMP": "cpGIMP",
    "QBS": "quadratic B-spline", "CBS": "cubic B-spline"}
SCHEMES = {"USL", "USF", "MUSL"}
FLIP = ["Simulation/transfer=FLIP", "Simulation/FLIP fraction=1"]
# A transfer name may carry a time integration after '~' (issue 11):
# N0.6 is Newmark's gamma = 0.6; macro / macroLS run macro steps that span
# each output interval (substeps from the CFL condition, so the scenes
# with a fixed time step take the CFL step instead), reconstructed in
# closed form / by least squares.
MACRO = ["Simulation/time step=0", "Simulation/macro time step=1e300"]
TRANSFERS = {"FLIP": FLIP,
             "PIC": ["Simulation/transfer=FLIP", "Simulation/FLIP fraction=0"],
             "APIC": ["Simulation/transfer=APIC"],
             "FLIP~N0.6": FLIP + ["Simulation/Newmark gamma=0.6"],
             "FLIP~macro": FLIP + MACRO,
             "FLIP~macroLS": FLIP + MACRO + ["Simulation/macro reconstruction=least squares"]}

# The configurations of the full sweep, "basis:scheme-transfer". Any other
# combination can be named with --configs.
CONFIGS = ["linear:USL-FLIP", "linear:USL-PIC", "linear:USF-FLIP", "linear:MUSL-FLIP",
           "linear:MUSL-PIC", "linear:MUSL-APIC"] + [
    "%s:%s" % (b, c) for b in ("uGIMP", "cpGIMP", "QBS", "CBS")
    for c in ("USL-FLIP", "USF-FLIP", "MUSL-FLIP", "MUSL-APIC")]


def split_config(config):
    """basis, scheme, transfer of "basis:scheme-transfer" (basis optional)."""
    basis, _, rest = config.rpartition(":")
    scheme, transfer = rest.split("-")
    basis = basis or "linear"
    if basis not in BASES or scheme not in SCHEMES or transfer not in TRANSFERS:
        raise SystemExit("unknown configuration %r: use basis:scheme-transfer with basis "
                         "in %s, scheme in %s, transfer in %s" % (
                             config, sorted(BASES), sorted(SCHEMES), sorted(TRANSFERS)))
    return basis, scheme, transfer


def config_overrides(config):
    basis, scheme, transfer = split_config(config)
    return (["Simulation/basis=" + BASES[basis], "Simulation/update scheme=" + scheme]
            + TRANSFERS[transfer])


def config_name(row):
    return "%s:%s-%s" % (row["basis"], row["scheme"], row["transfer"])


def run(exe, problem, config, n, work):
    scene, overrides, _, h, label, _ = PROBLEMS[problem]
    out = os.path.join(work, "%s-%s-%d" % (problem, config.replace(":", "-"), n))
    args = [exe, os.path.join(HERE, scene), "-s", "Output/directory=" + out,
            "-s", "Output/progress interval=1e9"]
    for o in overrides(n) + config_overrides(config):
        args += ["-s", o]
    p = subprocess.run(args, capture_output=True, text=True)
    basis, scheme, transfer = split_config(config)
    row = {"problem": problem, "dim": "", "basis": basis,
           "transfer": transfer, "scheme": scheme,
           "cells": n, "h": h(n), "status": "ok" if p.returncode == 0 else "stopped"}
    m = re.search(r"Verification: " + re.escape(label) + r"[^=]*= *([-+0-9.eE]+|nan|inf)", p.stdout)
    row["error"] = float(m.group(1)) if m else float("nan")
    m = re.search(r"max-norm displacement error \(max over time\) = ([-+0-9.eE]+)", p.stdout)
    row["error_max_norm"] = float(m.group(1)) if m else ""
    m = re.search(r"velocity error \(max over time\) = ([-+0-9.eE]+)", p.stdout)
    row["velocity_error"] = float(m.group(1)) if m else ""
    m = re.search(r"dealii-mpm: (\d)D", p.stdout)
    row["dim"] = int(m.group(1)) if m else ""
    timing = {}
    try:
        with open(os.path.join(out, "timing.csv")) as f:
            for r in csv.reader(f):
                timing[r[0]] = r[1:]
    except OSError:
        pass
    row["particles"] = int(float(timing["particles"][0])) if "particles" in timing else ""
    row["steps"] = int(float(timing["time steps"][0])) if "time steps" in timing else ""
    row["wall_seconds"] = float(timing["steps"][0]) if "steps" in timing else float("nan")
    row["ns_per_particle_step"] = float(timing["steps"][1]) if "steps" in timing else ""
    if p.returncode != 0:
        row["diagnosis"] = p.stderr.strip().splitlines()[-1][:200] if p.stderr.strip() else ""
    return row


def fitted_order(rows):
    pts = [(math.log(r["h"]), math.log(r["error"])) for r in rows
           if r["status"] == "ok" and r["error"] > 0 and math.isfinite(r["error"])]
    if len(pts) < 2:
        return float("nan")
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx


def configs_in(rows):
    """The configurations present in rows, in the order of CONFIGS first."""
    present = set(config_name(r) for r in rows)
    return [c for c in CONFIGS if c in present] + sorted(present - set(CONFIGS))


def plots(rows, outdir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    images = {}
    for problem in PROBLEMS:
        sel = [r for r in rows if r["problem"] == problem]
        if not sel:
            continue
        fig, (a, b) = plt.subplots(1, 2, figsize=(13, 5.5))
        colours = dict(zip(BASES, ["C0", "C1", "C2", "C3", "C4"]))
        styles = {"USL-FLIP": "o-", "USL-PIC": "v:", "USF-FLIP": "s--", "MUSL-FLIP": "^-",
                  "MUSL-PIC": "<:", "MUSL-APIC": "D-.", "USL-APIC": "d-.",
                  "USL-FLIP~N0.6": "P--", "USL-FLIP~macro": "*-.",
                  "USL-FLIP~macroLS": "X:"}
        for config in configs_in(sel):
            rs = sorted([r for r in sel if config_name(r) == config
                         and r["status"] == "ok" and math.isfinite(r["error"])],
                        key=lambda r: -r["h"])
            if not rs:
                continue
            basis, scheme, transfer = split_config(config)
            style = dict(color=colours[basis], markersize=4, linewidth=1)
            fmt = styles.get("%s-%s" % (scheme, transfer), "x-")
            label = "%s (order %.2f)" % (config, fitted_order(rs))
            a.loglog([r["h"] for r in rs], [r["error"] for r in rs], fmt, label=label, **style)
            b.loglog([r["wall_seconds"] for r in rs], [r["error"] for r in rs], fmt,
                     label=config, **style)
        a.set_xlabel("cell size h"); a.set_ylabel("error"); a.invert_xaxis()
        a.set_title(PROBLEMS[problem][5], fontsize=9); a.legend(fontsize=6, ncol=2)
        b.set_xlabel("wall seconds (time steps only)"); b.set_ylabel("error")
        b.set_title("speed against error", fontsize=9)
        for ax in (a, b):
            ax.grid(True, which="both", alpha=0.3)
        fig.tight_layout()
        path = os.path.join(outdir, "verification_%s.png" % problem)
        fig.savefig(path, dpi=80)
        plt.close(fig)
        images[problem] = os.path.basename(path)
    return images


def report(rows, images, path):
    lines = ["# Verification: error against resolution and cost", "",
             "Generated by `benchmarks/verification/sweep.py --plots` (do not edit by hand);",
             "the raw results are in `doc/verification.csv`. Errors are computed by the",
             "program against the exact solution of each scene; wall seconds count the",
             "time steps only. Configurations are named basis:scheme-transfer, with the",
             "bases linear, uGIMP, cpGIMP, QBS (quadratic B-spline) and CBS (cubic",
             "B-spline), and the transfers FLIP (alpha = 1), PIC (alpha = 0) and APIC;",
             "a transfer may carry a time integration after '~': N0.6 (Newmark's",
             "gamma = 0.6), macro and macroLS (macro steps of an output interval,",
             "substeps from the CFL condition, closed-form or least-squares",
             "reconstruction).", "",
             "## Observed orders (least-squares slope of log error against log h)", "",
             ]
    problems = [p for p in PROBLEMS if any(r["problem"] == p for r in rows)]
    lines += ["| configuration | " + " | ".join(problems) + " |",
              "|---|" + "---|" * len(problems)]
    for config in configs_in(rows):
        cells = []
        for problem in problems:
            rs = [r for r in rows if r["problem"] == problem and config_name(r) == config]
            if not rs:
                cells.append("")
                continue
            stopped = sum(r["status"] != "ok" for r in rs)
            o = fitted_order(rs)
            cells.append(("%.2f" % o if math.isfinite(o) else "-") +
                         (" (%d stopped)" % stopped if stopped else ""))
        lines.append("| %s | %s |" % (config, " | ".join(cells)))
    lines += ["", "A negative order means the error grows under refinement; \"stopped\" counts",
              "runs that ended with a diagnosis (a point left the grid or inverted).", ""]
    # The reading of the results is written by hand, next to this script.
    with open(os.path.join(HERE, "findings.md")) as f:
        lines += f.read().rstrip("\n").splitlines() + [""]
    for problem, image in images.items():
        lines += ["## %s" % problem, "", PROBLEMS[problem][5] + ".", "",
                  "![%s](%s)" % (problem, image), "",
                  "| config | cells | error | velocity error | wall s | ns/particle-step |",
                  "|---|---:|---:|---:|---:|---:|"]
        for r in rows:
            if r["problem"] == problem:
                v = r.get("velocity_error", "")
                lines.append("| %s | %s | %s | %s | %.3g | %s |" % (
                    config_name(r), r["cells"],
                    ("%.3e" % r["error"]) if r["status"] == "ok" else "stopped",
                    ("%.3e" % float(v)) if v not in ("", None) and r["status"] == "ok" else "",
                    r["wall_seconds"], ("%.0f" % r["ns_per_particle_step"]) if r["ns_per_particle_step"] != "" else ""))
        lines.append("")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "dealii-mpm"))
    ap.add_argument("--problems", default=",".join(PROBLEMS))
    ap.add_argument("--configs", default=",".join(CONFIGS))
    ap.add_argument("--ladder", default="full", choices=["coarse", "full"])
    ap.add_argument("--cells", default=None,
                    help="comma-separated cell counts instead of the ladder")
    ap.add_argument("--csv", default=None, help="write the rows here")
    ap.add_argument("--plots", action="store_true", help="PNGs and doc/verification.md")
    ap.add_argument("--check", action="store_true", help="assert the bounds below")
    ap.add_argument("--from-csv", default=None,
                    help="redraw plots and report from earlier --csv files "
                    "(comma-separated; their rows are merged)")
    ap.add_argument("--min-order", type=float, default=None)
    ap.add_argument("--max-error", type=float, default=None)
    ap.add_argument("--expect-growth", action="store_true",
                    help="assert a known failure: finite errors that do not fall")
    a = ap.parse_args()
    rows = []
    if a.from_csv:
        for path in a.from_csv.split(","):
            with open(path) as f:
                for r in csv.DictReader(f):
                    for k in ("h", "error", "wall_seconds"):
                        r[k] = float(r[k]) if r[k] not in ("", None) else float("nan")
                    r["cells"] = int(r["cells"])
                    r["ns_per_particle_step"] = (float(r["ns_per_particle_step"])
                                                 if r["ns_per_particle_step"] else "")
                    rows.append(r)
        a.problems = ",".join(sorted(set(r["problem"] for r in rows), key=list(PROBLEMS).index))
    fields = ["problem", "dim", "basis", "transfer", "scheme", "cells", "h", "particles",
              "steps", "error", "error_max_norm", "velocity_error", "wall_seconds",
              "ns_per_particle_step", "status", "diagnosis"]
    # Rows are written as they come, so that an interrupted sweep keeps them.
    out = None
    if a.csv and not a.from_csv:
        out = open(a.csv, "w", newline="")
        writer = csv.DictWriter(out, fieldnames=fields, extrasaction="ignore")
        writer.writeheader()
    with tempfile.TemporaryDirectory() as work:
        for problem in a.problems.split(","):
            for config in a.configs.split(","):
                ladder = ([int(c) for c in a.cells.split(",")] if a.cells
                          else PROBLEMS[problem][2][a.ladder])
                for n in ([] if a.from_csv else ladder):
                    r = run(a.exe, problem, config, n, work)
                    rows.append(r)
                    if out:
                        writer.writerow(r)
                        out.flush()
                    print("%-20s %-10s cells %4d: error %-12.4g %s" % (
                        problem, config, n, r["error"], r["status"]), flush=True)
    if out:
        out.close()
    if a.plots:
        doc = os.path.join(ROOT, "doc")
        report(rows, plots(rows, doc), os.path.join(doc, "verification.md"))
    ok = True
    if a.check:
        for problem in a.problems.split(","):
            for config in a.configs.split(","):
                rs = [r for r in rows if r["problem"] == problem and
                      config_name(r) == "%s:%s-%s" % split_config(config)]
                order = fitted_order(rs)
                finest = rs[-1]["error"]
                print("%s %s: observed order %.3f, finest error %.4g" % (problem, config, order, finest))
                if any(r["status"] != "ok" or not math.isfinite(r["error"]) for r in rs):
                    ok = False
                    print("  FAILED: a run stopped or gave a non-finite error")
                if a.min_order is not None and not order >= a.min_order:
                    ok = False
                    print("  FAILED: order below %g" % a.min_order)
                if a.max_error is not None and not finest <= a.max_error:
                    ok = False
                    print("  FAILED: finest error above %g" % a.max_error)
                if a.expect_growth and not order < 0.5:
                    ok = False
                    print("  FAILED: expected the known failure (order < 0.5), got %.3f" % order)
    print("passed" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
