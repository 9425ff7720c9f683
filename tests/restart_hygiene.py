#!/usr/bin/env python3
"""A restart continues the physics of its checkpoint (issue 32, class 6).

The two disks run to t = 0.5 with a checkpoint there. Restarted:
  - with another Young's modulus: refused, naming the entry and both values
    (before: accepted silently);
  - with an end time that has passed: refused, naming the end time and the
    checkpoint's time (before: "Finished 0 steps", exit 0);
  - with other output fields: refused, naming 'Output/fields' and the
    checkpoint's (before: "another grid or other point fields");
  - with another output interval and a later end time: runs, and its last
    row equals that of the uninterrupted run bit for bit.

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
        # Allowed: another output interval and a later end time.
        straight = os.path.join(tmp, "straight")
        # (The restart keeps the checkpoint's next output time, 0.75, so
        # its steps are cut as the scene's own interval, 0.25, cuts them.)
        run(straight, "-s", "Simulation/end time=1")
        # (A restart writes on in the run's own output directory.)
        later = first
        r = run(later, "--restart", checkpoint, "-s", "Simulation/end time=1",
                "-s", "Output/interval=0.5")
        rows = []
        for d in (straight, later):
            with open(os.path.join(d, "statistics.csv")) as f:
                rows.append(f.read().strip().splitlines()[-1].split(",")[:-1])
        good = r.returncode == 0 and rows[0] == rows[1]
        print(("ok   " if good else "FAIL ") +
              "another output interval: the last row as the straight run's")
        ok = ok and good
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
