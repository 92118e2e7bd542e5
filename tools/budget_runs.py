"""Independent grainstorm runs side by side under a wall-clock deadline.

The validation tools (silo_beverloo.py, drum.py, chute_flow.py) start their
runs through `run_all`: up to `jobs` processes at once (on one GPU: several
small scenes keep it busier than one), a timestamped progress line per run
every `every` seconds (the last `step a/b ... ETA` line grainstorm writes to
stderr), and at the deadline every run still going gets SIGTERM, which makes
grainstorm stop at the next step, flush its measurement logs and exit 3
(src/run/driver.cpp); one that has not stopped `grace` seconds later is
killed. What a stopped run wrote up to then stays there for a partial
analysis. Standard library only.
"""
import concurrent.futures
import os
import re
import signal
import subprocess
import sys
import time

T0 = time.time()
PROGRESS = re.compile(r"step (\d+)/(\d+)\s+t = (\S+) s\s+(\S+) particle-steps/s\s+ETA (\d+) s(?:\s+(\d+) particles)?")


def say(label, text):
    """A timestamped line on stderr: UTC clock and seconds since this tool started."""
    sys.stderr.write("[%s +%4.0fs] %s: %s\n" % (time.strftime("%H:%M:%S", time.gmtime()), time.time() - T0, label, text))
    sys.stderr.flush()


class Run:
    """One grainstorm command; its stdout and stderr go to `log`."""

    def __init__(self, name, cmd, log, env=None):
        self.name, self.cmd, self.log, self.env = name, cmd, log, env
        self.proc = None
        self.start = self.end = None
        self.status = "not started"   # done | stopped (by the deadline) | failed | not started
        self.returncode = None

    def progress(self):
        """(step, total, simulated time, ETA, particles or '', particle-steps/s)
        of the last progress line, or None."""
        try:
            with open(self.log, "rb") as f:
                f.seek(max(0, os.path.getsize(self.log) - 4000))
                tail = f.read().decode(errors="replace")
        except OSError:
            return None
        found = PROGRESS.findall(tail)
        if not found:
            return None
        s = found[-1]
        return int(s[0]), int(s[1]), float(s[2]), int(s[4]), s[5], float(s[3])

    def wall(self):
        return (self.end or time.time()) - self.start if self.start else 0.0

    def output(self, chars=3000):
        try:
            with open(self.log, errors="replace") as f:
                return f.read()[-chars:]
        except OSError:
            return ""


def run_all(runs, deadline=None, jobs=None, label="runs", every=15.0, grace=30.0, on_finish=None):
    """Runs `runs` (Run objects), at most `jobs` at once (default: all), in the
    given order. `deadline` (epoch seconds; None: no limit) stops what still
    runs by SIGTERM and starts no more. `on_finish(run)` is called as each one
    ends (done, stopped or failed). Returns the runs with their status set."""
    jobs = jobs or len(runs)
    waiting = list(runs)
    active = []
    last_report = 0.0
    stopping = False
    say(label, "%d run(s), %d at once%s" % (len(runs), jobs,
        ", deadline in %.0f s" % (deadline - time.time()) if deadline else ""))
    while waiting or active:
        now = time.time()
        if not stopping and deadline is not None and now >= deadline:
            stopping = True
            for r in active:
                say(label, "%s: deadline reached, SIGTERM (the run stops and flushes its logs)" % r.name)
                r.proc.send_signal(signal.SIGTERM)
            for r in waiting:
                say(label, "%s: not started (deadline)" % r.name)
            waiting = []
            stop_at = now + grace
        if stopping and now >= stop_at:
            for r in active:
                say(label, "%s: did not stop within %.0f s of SIGTERM: killed" % (r.name, grace))
                r.proc.kill()
        while waiting and len(active) < jobs and not stopping:
            r = waiting.pop(0)
            os.makedirs(os.path.dirname(os.path.abspath(r.log)), exist_ok=True)
            with open(r.log, "w") as log:
                r.proc = subprocess.Popen(r.cmd, stdout=log, stderr=subprocess.STDOUT, env=r.env)
            r.start = time.time()
            active.append(r)
            say(label, "%s: started (%d running, %d waiting)" % (r.name, len(active), len(waiting)))
        for r in list(active):
            code = r.proc.poll()
            if code is None:
                continue
            r.end, r.returncode = time.time(), code
            if code == 0:
                r.status = "done"
            elif stopping and code in (3, -signal.SIGTERM, -signal.SIGKILL):
                r.status = "stopped"
            else:
                r.status = "failed"
            active.remove(r)
            p = r.progress()
            say(label, "%s: %s (exit %d) after %.0f s%s" % (r.name, r.status, code, r.wall(),
                ", at step %d of %d, t = %.4g s" % p[:3] if p else ""))
            if r.status == "failed":
                sys.stderr.write(r.output())
            if on_finish:
                on_finish(r)
        if active and time.time() - last_report >= every:
            last_report = time.time()
            rate = 0.0
            for r in active:
                p = r.progress()
                if p:
                    step, total, t, eta, count, r_rate = p
                    rate += r_rate
                    say(label, "%s: step %d/%d (%.0f %%), t = %.4g s, ETA %d s%s, %.0f s so far" % (
                        r.name, step, total, 100.0 * step / max(total, 1), t, eta,
                        ", %s particles" % count if count else "", r.wall()))
                else:
                    say(label, "%s: setting up, %.0f s so far" % (r.name, r.wall()))
            if len(active) > 1:
                say(label, "%d runs at %.3g particle-steps/s together (each run's own rate since its start, summed)"
                    % (len(active), rate))
        if active or waiting:
            time.sleep(0.5)
    return runs


def check_plan(binary, scene):
    """(particles at the start, steps) of a scene, from `grainstorm check`."""
    out = subprocess.run([binary, "check", scene], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout
    particles = re.search(r"^particles:\s+(\d+)", out, re.M)
    steps = re.search(r"^steps:\s+(\d+)", out, re.M)
    return (int(particles.group(1)) if particles else 0), (int(steps.group(1)) if steps else 0)


def print_plan(label, binary, named_scenes):
    """Prints each run's size (particles at the start, steps) and the total
    particle-steps: what the budget has to hold."""
    total = 0.0
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, len(named_scenes))) as pool:
        plans = list(pool.map(lambda ns: check_plan(binary, ns[1]), named_scenes))
    for (name, _), (n, steps) in zip(named_scenes, plans):
        total += float(n) * steps
        say(label, "plan: %s: %d particles at the start, %d steps" % (name, n, steps))
    say(label, "plan: %.3g particle-steps in all" % total)


def deadline_from(budget_s):
    """The epoch second `budget_s` from now (None for no budget)."""
    return time.time() + budget_s if budget_s else None
