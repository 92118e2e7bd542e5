#!/usr/bin/env python3
"""tools/budget_runs.py, the runner of the validation GPU scripts: a run the
deadline catches stops cleanly (SIGTERM: grainstorm exits 3 and its logs hold
what it reached), a run within it is done, a run the deadline finds waiting
is not started, a broken scene is a failure.

    tests/tools/test_budget_runs.py BINARY
"""
import csv
import os
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import budget_runs  # noqa: E402
import chute_flow  # noqa: E402


def chute_run(binary, work, name, duration_tau):
    """A run of the chute's ci layer at 24 deg (flowing), `duration_tau` long."""
    p = dict(chute_flow.PRESETS["ci"], duration=duration_tau)
    d = os.path.join(work, name)
    os.makedirs(d)
    scene = os.path.join(d, "scene.yaml")
    with open(scene, "w") as f:
        f.write(chute_flow.scene_text(p, 24.0, "out"))
    out = os.path.join(d, "out")
    return budget_runs.Run(name, [binary, "run", scene, "--backend", "cpu", "--out", out], os.path.join(d, "run.txt")), out


def main():
    binary = sys.argv[1]
    failures = []

    def check(ok, what):
        print("%s: %s" % ("ok" if ok else "FAIL", what))
        if not ok:
            failures.append(what)

    with tempfile.TemporaryDirectory(prefix="budget_runs_") as work:
        # 1000 tau (402,000 steps, minutes on a CPU) against a 3 s deadline; a
        # second run waits behind it (one job at a time).
        long_run, long_out = chute_run(binary, work, "long", 1000.0)
        waiting, _ = chute_run(binary, work, "waiting", 1.0)
        budget_runs.run_all([long_run, waiting], budget_runs.deadline_from(3.0), jobs=1, label="test", every=1.0)
        check(long_run.status == "stopped" and long_run.returncode == 3,
              "the deadline stops the long run cleanly: status %s, exit %s (3: grainstorm's stop on a signal)"
              % (long_run.status, long_run.returncode))
        log = open(os.path.join(long_out, "run.log")).read() if os.path.exists(os.path.join(long_out, "run.log")) else ""
        check("stopped by a signal" in log, "its run.log says it stopped on a signal")
        with open(os.path.join(long_out, "average_all.csv")) as f:
            times = [float(r["time"]) for r in csv.DictReader(f)]
        tau = chute_flow.TAU
        check(len(times) >= 2 and 0 < times[-1] < 1000 * tau,
              "its measurement log holds what it reached: %d rows up to t = %.3g tau of 1000"
              % (len(times), times[-1] / tau if times else float("nan")))
        check(long_run.wall() < 3.0 + 30.0, "it stopped within the grace time (%.1f s)" % long_run.wall())
        check(waiting.status == "not started" and waiting.proc is None,
              "the run waiting for a job slot is not started: %s" % waiting.status)

        short, short_out = chute_run(binary, work, "short", 0.2)
        broken = budget_runs.Run("broken", [binary, "run", os.path.join(work, "missing.yaml"), "--backend", "cpu",
                                            "--out", os.path.join(work, "broken")], os.path.join(work, "broken.txt"))
        budget_runs.run_all([short, broken], None, label="test", every=1.0)
        check(short.status == "done" and short.returncode == 0, "a run without a deadline is done: %s" % short.status)
        check(short.progress() is not None and short.progress()[0] == short.progress()[1],
              "its last progress line reads step = total: %s" % (short.progress(),))
        check(broken.status == "failed" and broken.returncode not in (0, 3),
              "a missing scene is a failure: %s, exit %s" % (broken.status, broken.returncode))
    print("%d check(s) failed" % len(failures) if failures else "all checks passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
