#!/usr/bin/env python3
"""A restart continues the physics of its checkpoint (issue 32, class 6).

The two disks run to t = 0.5 with a checkpoint there. Restarted:
  - with another Young's modulus: refused, naming the entry and both values
    (before: accepted silently);
  - with an end time that has passed: refused, naming the end time and the
    checkpoint's time (before: "Finished 0 steps", exit 0);
  - with other output fields: refused, naming 'Output/fields' and the
    checkpoint's (before: "another grid or other point fields");
  - with another output interval (0.5, 0.1) and a later end time: runs,
    and writes its frames at that interval's times after the checkpoint's
    (0.6, 0.7, ... for 0.1; before, 0.75 and then one frame every step).

  restart_hygiene.py --exe build/dealii-mpm --scene tests/two_disks.prm
"""
import argparse, os, re, subprocess, sys, tempfile


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--exe", required=True)
    parser.add_argument("--scene", required=True)
    a = parser.parse_args()
    ok = True

    def run(directory, *extra):
        return subprocess.run(
            [a.exe, a.scene, "-s", "Output/directory=" + directory,
             "-s", "Output/progress interval=1e9", "-s", "Grid/cells=20"]
            + list(extra), capture_output=True, text=True)

    def expect(what, result, pattern):
        nonlocal ok
        last = result.stderr.strip().splitlines()[-1] if result.stderr.strip() else ""
        good = result.returncode != 0 and re.search(pattern, last) is not None
        print(("ok   " if good else "FAIL ") + what + ": " + last)
        ok = ok and good

    with tempfile.TemporaryDirectory() as tmp:
        first = os.path.join(tmp, "first")
        r = run(first, "-s", "Simulation/end time=0.5",
                "-s", "Checkpoint/interval=0.5")
        if r.returncode != 0:
            print(r.stderr)
            sys.exit(1)
        checkpoint = os.path.join(first, "checkpoint")
        E = "Bodies/Body 1/linear elastic/Young's modulus"
        expect("changed material constant",
               run(first, "--restart", checkpoint,
                   "-s", "Simulation/end time=1", "-s", E + "=2000"),
               re.escape("differs in '%s' ('1000' there, '2000' here)" % E))
        expect("end time passed",
               run(first, "--restart", checkpoint,
                   "-s", "Simulation/end time=0.25"),
               re.escape("'Simulation/end time' = '0.25': is not after the "
                         "time of the checkpoint") + ".*t = 0.5")
        expect("output fields",
               run(first, "--restart", checkpoint,
                   "-s", "Simulation/end time=1",
                   "-s", "Output/fields=velocity"),
               re.escape("'Output/fields' = 'velocity': needs other point "
                         "data than the checkpoint stores; restart with its "
                         "'Output/fields' = 'velocity, displacement,"))
        # Allowed: another output interval and a later end time. The
        # frames carry on at the new interval's multiples after the
        # checkpoint's time (before, the checkpoint's next output time,
        # 0.75, was kept, and then frame counter x interval: 0.1 wrote a
        # frame every step until the counter caught up).
        for interval, expected in (("0.5", [1.0]),
                                   ("0.1", [0.6, 0.7, 0.8, 0.9, 1.0])):
            r = run(first, "--restart", checkpoint,
                    "-s", "Simulation/end time=1",
                    "-s", "Output/interval=" + interval)
            with open(os.path.join(first, "statistics.csv")) as f:
                times = [float(row.split(",")[1])
                         for row in f.read().strip().splitlines()[1:]]
            after = [t for t in times if t > 0.5 + 1e-12]
            good = r.returncode == 0 and len(after) == len(expected) and \
                all(abs(t - e) < 1e-12 for t, e in zip(after, expected))
            print(("ok   " if good else "FAIL ") +
                  "output interval %s after the restart: frames at %s" %
                  (interval, after))
            ok = ok and good
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
