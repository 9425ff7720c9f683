#!/usr/bin/env python3
"""Dynamic load balancing (issue 13): a scene whose material travels
(tests/thrown_block.prm) on --np ranks.

1. With the scene's 'Grid/load imbalance limit' the grid is repartitioned
   during the run (at least once) and no step runs with an imbalance above
   the limit (timing.csv: rebalances, largest imbalance).
2. Without repartitioning (limit 0) the imbalance exceeds the limit: the
   scene needs the balancing.
3. The statistics of both equal the 1-rank run's to --tolerance.
4. Points that cross into another rank's tiles are sent to it by
   relocation: neither run needs deal.II's collective sort (timing.csv:
   collective sorts), which copies all the points' data.

  load_balance.py --exe build/dealii-mpm --scene tests/thrown_block.prm
      --np 2 --limit 0.2 [--tolerance 1e-10]
"""
import argparse, csv, os, subprocess, sys, tempfile


def timing(directory):
    values = {}
    rows = csv.reader(open(os.path.join(directory, "timing.csv")))
    next(rows)  # the header
    for row in rows:
        if len(row) >= 2 and row[1] != "":
            values[row[0]] = float(row[1])
    return values


def statistics(directory):
    rows = list(csv.DictReader(open(os.path.join(directory,
                                                 "statistics.csv"))))
    for r in rows:
        r.pop("wall_seconds")
    return rows


def agree(a, b, tolerance):
    if len(a) != len(b):
        return False
    for r, s in zip(a, b):
        for key in r:
            x, y = float(r[key]), float(s[key])
            if abs(x - y) > tolerance * max(abs(x), abs(y), 1.0):
                print("  differs: %s %g vs %g" % (key, x, y))
                return False
    return True


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--exe", required=True)
    parser.add_argument("--scene", required=True)
    parser.add_argument("--np", type=int, required=True)
    parser.add_argument("--limit", type=float, required=True)
    parser.add_argument("--tolerance", type=float, default=1e-10)
    a = parser.parse_args()

    def run(np, directory, limit):
        command = [a.exe, a.scene, "-s", "Output/directory=" + directory,
                   "-s", "Grid/load imbalance limit=%g" % limit]
        if np > 1:
            command = ["mpirun", "-np", str(np)] + command
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL)

    ok = True
    with tempfile.TemporaryDirectory() as tmp:
        one, balanced, static = (os.path.join(tmp, d)
                                 for d in ("one", "balanced", "static"))
        run(1, one, a.limit)
        run(a.np, balanced, a.limit)
        run(a.np, static, 0)
        b, s = timing(balanced), timing(static)
        print("%d ranks, limit %g: %d repartitions, largest imbalance %.3f; "
              "without repartitioning %.3f" % (
                  a.np, a.limit, b["rebalances"], b["largest imbalance"],
                  s["largest imbalance"]))
        ok = ok and b["rebalances"] >= 1 and \
            b["largest imbalance"] <= a.limit and \
            s["largest imbalance"] > a.limit
        print("collective sorts: %d balanced, %d static" % (
            b["collective sorts"], s["collective sorts"]))
        ok = ok and b["collective sorts"] == 0 and s["collective sorts"] == 0
        for name, directory in (("balanced", balanced), ("static", static)):
            equal = agree(statistics(one), statistics(directory), a.tolerance)
            print("%s run on %d ranks: statistics %s the 1-rank run's" % (
                name, a.np, "equal" if equal else "DIFFER from"))
            ok = ok and equal
    print("passed" if ok else "FAILED")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
