#!/usr/bin/env python3
"""Checkpoint and restart (issue 12).

1. A run to T/2 that checkpoints there, restarted to T, writes the same
   statistics.csv as a run straight to T: bit for bit on the same number
   of ranks (--np), to round-off (--tolerance) on --restart-np ranks.
2. A run that checkpoints at every output and is killed (SIGKILL, all
   ranks) at random moments after each new checkpoint, several times,
   each time restarted from what the kill left, still ends with the uninterrupted run's statistics bit for bit:
   the checkpoint on disk is always complete (a kill inside a checkpoint
   leaves the previous one).

  checkpoint_restart.py --exe build/dealii-mpm --scene tests/two_disks.prm
      --end-time 3 [--np 2 --restart-np 1 --tolerance 1e-12] [--kills 4]
      [-s "Grid/cells=80" ...]
"""
import argparse, os, random, signal, subprocess, sys, tempfile, time


def rows(directory):
    """statistics.csv without the wall-time column."""
    with open(os.path.join(directory, "statistics.csv")) as f:
        return [line.strip().rsplit(",", 1)[0] for line in f]


def checkpoint_time(checkpoint):
    """The time a checkpoint was taken at (where locate() would look)."""
    for d in (checkpoint, checkpoint + ".old"):
        try:
            for line in open(os.path.join(d, "state.txt")):
                kind, key, value = line.split()[:3]
                if key == "time":
                    return float.fromhex(value)
        except OSError:
            pass
    return float("nan")


def later(now, before):
    """A checkpoint time after another (nan: none written yet)."""
    return now == now and not now <= before


def same(a, b, tolerance):
    """Equal, or within a relative (and absolute) tolerance."""
    if len(a) != len(b):
        return False
    if tolerance == 0:
        return a == b
    for x, y in zip(a, b):
        for u, v in zip(x.split(","), y.split(",")):
            try:
                u, v = float(u), float(v)
            except ValueError:
                if u != v:
                    return False
                continue
            if abs(u - v) > tolerance * max(abs(u), abs(v), 1.0):
                return False
    return True


# mpirun as root (CI runs as root) and with more ranks than cores.
os.environ.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                  OMPI_MCA_rmaps_base_oversubscribe="1")


def descendants(pid):
    """The processes started by pid, recursively (mpirun's ranks)."""
    try:
        with open("/proc/%d/task/%d/children" % (pid, pid)) as f:
            children = [int(c) for c in f.read().split()]
    except OSError:
        return []
    return children + sum([descendants(c) for c in children], [])


def alive(pid):
    """Running (not gone, not a zombie)."""
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def kill_job(p):
    """SIGKILL the run and all its ranks at once, as a scheduler or a node
    failure does, and wait until none is left. Killing mpirun alone leaves
    its ranks running on (they are not in its process group), and they
    would go on writing into the directory the restart reads."""
    ranks = descendants(p.pid)
    for pid in [p.pid] + ranks:
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass
    p.wait()
    while any(alive(pid) for pid in ranks):
        time.sleep(0.05)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--exe", required=True)
    parser.add_argument("--scene", required=True)
    parser.add_argument("--end-time", type=float, required=True)
    parser.add_argument("--np", type=int, default=1)
    parser.add_argument("--restart-np", type=int, default=0)
    parser.add_argument("--tolerance", type=float, default=0)
    parser.add_argument("--kills", type=int, default=0)
    parser.add_argument("-s", action="append", default=[],
                        help="a parameter override for every run")
    a = parser.parse_args()
    restart_np = a.restart_np or a.np

    def command(np, directory, *extra):
        c = [a.exe, a.scene, "-s", "Output/directory=" + directory,
             "-s", "Output/progress interval=1e9"] + \
            sum([["-s", o] for o in a.s], []) + list(extra)
        if np > 1:
            c = ["mpirun", "-np", str(np)] + c
        return c

    def run(np, directory, *extra):
        subprocess.run(command(np, directory, *extra), check=True,
                       stdout=subprocess.DEVNULL)

    ok = True
    with tempfile.TemporaryDirectory() as tmp:
        straight, split = os.path.join(tmp, "straight"), os.path.join(tmp, "split")
        started_at = time.time()
        run(a.np, straight, "-s", "Simulation/end time=%g" % a.end_time)
        # Wall time per output (statistics.csv has a row per output).
        per_output = (time.time() - started_at) / len(rows(straight))
        half = a.end_time / 2
        run(a.np, split, "-s", "Simulation/end time=%g" % half,
            "-s", "Checkpoint/interval=%g" % half)
        run(restart_np, split, "-s", "Simulation/end time=%g" % a.end_time,
            "--restart", os.path.join(split, "checkpoint"))
        equal = same(rows(straight), rows(split), a.tolerance)
        print("restart at T/2 on %d rank(s) from %d: %s" % (
            restart_np, a.np,
            ("bit for bit" if a.tolerance == 0 else "within %g" % a.tolerance)
            if equal else "DIFFERENT"))
        ok = ok and equal

        # A checkpoint restarted by a scene with another grid
        # is refused in one line.
        r = subprocess.run(command(1, split, "-s", "Grid/cells=3",
                                   "--restart",
                                   os.path.join(split, "checkpoint")),
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                           text=True)
        refused = r.returncode == 1 and "parameter '--restart'" in r.stderr \
            and r.stderr.strip().count("\n") == 0
        print("restart by another scene: %s" % (
            "refused: " + r.stderr.strip() if refused else "NOT REFUSED"))
        ok = ok and refused

        if a.kills > 0:
            random.seed(2)
            killed = os.path.join(tmp, "killed")
            checkpoint = os.path.join(killed, "checkpoint")
            every = ["-s", "Simulation/end time=%g" % a.end_time,
                     "-s", "Checkpoint/interval=1e-9"]
            started = False
            for k in range(a.kills):
                extra = every + (["--restart", checkpoint] if started else [])
                p = subprocess.Popen(command(a.np, killed, *extra),
                                     stdout=subprocess.DEVNULL,
                                     stderr=subprocess.DEVNULL)
                # Kill at a random moment after the run has written a
                # checkpoint later than the last one (so each restart makes
                # progress however loaded the machine is): often inside
                # the next step's checkpoint.
                last = checkpoint_time(checkpoint)
                waited = 0
                while p.poll() is None and waited < 600 and \
                        not later(checkpoint_time(checkpoint), last):
                    time.sleep(0.02)
                    waited += 0.02
                time.sleep(random.uniform(0, 1.5 * per_output))
                kill_job(p)
                # On a loaded machine the run can reach its end before the
                # kill: then there is nothing left to restart.
                finished = p.returncode == 0
                started = started or os.path.exists(checkpoint) or \
                    os.path.exists(checkpoint + ".old")
                print("kill %d: checkpoint %s" % (
                    k, "at t = %g" % checkpoint_time(checkpoint)
                    if started else "not yet written") +
                    (" (the run had ended)" if finished else ""))
                if finished:
                    break
            else:
                run(a.np, killed, *(every + (["--restart", checkpoint]
                                             if started else [])))
            equal = rows(straight) == rows(killed)
            print("after %d kills and restarts: %s" % (
                a.kills, "bit for bit" if equal else "DIFFERENT"))
            ok = ok and equal
    print("passed" if ok else "FAILED")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
