#!/usr/bin/env python3
"""tools/mixer_campaign.py against numbers computed here: the seeds' mean and
spread of the Lacey index per revolution, the impeller torque averaged over
each revolution, and the snapshots kept for the top views.

    test_mixer_campaign.py TOOLS_DIR
"""
import csv
import math
import os
import subprocess
import sys
import tempfile

tool = os.path.join(sys.argv[1], "mixer_campaign.py")
failures = []


def check(what, ok):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def close(a, b, tol=1e-5):  # the CSV holds 6 significant digits
    return abs(a - b) <= tol * max(1.0, abs(b))


START, PERIOD, DT = 1.0, 2.0, 1e-3  # marking at 1 s, one revolution per 2 s
SCENE = f"""duration: 7
time_step: {{fraction_of_contact_time: 0.11}}
analysis:
  mixing:
    start: {START}
    revolution_period: {PERIOD}
"""


def write_run(campaign, name, lacey, torque_slope):
    d = os.path.join(campaign, name)
    os.makedirs(d)
    open(os.path.join(campaign, name + ".yaml"), "w").write(SCENE)
    open(os.path.join(d, "run.log"), "w").write(f"grainstorm 0.1.0: {name}.yaml, 10 particles, backend cpu, 1 rank, dt = {DT} s\n")
    with open(os.path.join(d, "mixing.csv"), "w") as f:
        f.write("time,step,revolutions,lacey,rsd,one_minus_rsd,samples,particles_per_sample,concentration\n")
        for rev, m in enumerate(lacey):
            t = START + rev * PERIOD
            f.write(f"{t},{round(t / DT)},{rev},{m},{1 - m / 2},{m / 2},10,5,0.5\n")
    # Torque about z, sampled every 0.25 s: slope * t.
    with open(os.path.join(d, "timeseries.csv"), "w") as f:
        f.write("step,time,mesh0_tz\n")
        for k in range(0, 29):
            t = 0.25 * k
            f.write(f"{round(t / DT)},{t},{torque_slope * t}\n")
    # Snapshots every 1 s, and one at 5.4 s (revolution 2.2).
    for t in (0, 1, 2, 3, 4, 5, 5.4, 6, 7):
        open(os.path.join(d, f"particles_{round(t / DT):010d}.h5"), "w").close()
    open(os.path.join(d, f"meshes_{round(5.0 / DT):010d}.h5"), "w").close()


with tempfile.TemporaryDirectory() as campaign:
    seeds = {"case_x_s1": ([0.0, 0.2, 0.5, 0.7], -1.0), "case_x_s2": ([0.0, 0.4, 0.6, 0.9], -3.0)}
    for name, (lacey, slope) in seeds.items():
        write_run(campaign, name, lacey, slope)
    out = os.path.join(campaign, "out")
    r = subprocess.run([sys.executable, tool, "analyse", campaign, "--out-dir", out, "--plot-dir", ""],
                       capture_output=True, text=True)
    check("analyse exits 0", r.returncode == 0)
    rows = list(csv.DictReader(open(os.path.join(out, "campaign_case_x.csv"))))
    check("one row per revolution", [int(x["revolutions"]) for x in rows] == [0, 1, 2, 3])
    for x in rows:
        rev = int(x["revolutions"])
        values = [seeds[n][0][rev] for n in seeds]
        mean = sum(values) / 2
        sd = math.sqrt(sum((v - mean) ** 2 for v in values))  # n - 1 = 1
        check(f"revolution {rev}: Lacey mean and sd", close(float(x["lacey_mean"]), mean) and close(float(x["lacey_sd"]), sd))
        if rev == 0:
            check("revolution 0: no torque (nothing before the marking)", x["torque_mean"] == "nan")
            continue
        # Samples at t = 0.25 k in (START + (rev-1) PERIOD, START + rev PERIOD]: slope times their mean time.
        ts = [0.25 * k for k in range(29) if START + (rev - 1) * PERIOD < 0.25 * k <= START + rev * PERIOD]
        per_seed = [slope * sum(ts) / len(ts) for _, slope in seeds.values()]
        check(f"revolution {rev}: torque over that revolution",
              close(float(x["torque_mean"]), sum(per_seed) / 2) and
              close(float(x["torque_sd"]), abs(per_seed[0] - per_seed[1]) / math.sqrt(2)))
    # The tables read back as analyse handed them to its plots (plot reads them
    # once the runs are gone): the means, spreads and ranges computed here.
    sys.path.insert(0, sys.argv[1])
    import mixer_campaign
    tables = mixer_campaign.read_tables(out, "campaign")
    check("plot reads one variant", list(tables) == ["case_x"])
    for rev, runs, lacey, orsd in tables["case_x"]:
        values = [seeds[n][0][rev] for n in seeds]
        mean = sum(values) / 2
        check(f"revolution {rev} read back", runs == 2 and close(lacey[0], mean) and
              close(lacey[1], abs(values[0] - values[1]) / math.sqrt(2)) and close(lacey[2], min(values)) and
              close(lacey[3], max(values)) and close(orsd[0], mean / 2))
    plots = os.path.join(campaign, "plots")
    r = subprocess.run([sys.executable, tool, "plot", out, "--plot-dir", plots], capture_output=True, text=True)
    check("plot exits 0", r.returncode == 0)
    try:
        import matplotlib  # noqa: F401
        check("plot draws both figures", sorted(os.listdir(plots)) == ["campaign_lacey.png",
                                                                     "campaign_one_minus_rsd.png"])
    except ImportError:
        check("plot says it has no matplotlib", "matplotlib not found" in r.stdout)
    # analyse draws every variant with a table in its output directory, not
    # only its campaign's: a second campaign of variant case_y alone.
    other = os.path.join(campaign, "other")
    os.makedirs(other)
    write_run(other, "case_y_s1", [0.0, 0.3, 0.6, 0.8], -2.0)
    r = subprocess.run([sys.executable, tool, "analyse", other, "--out-dir", out, "--plot-dir", plots],
                       capture_output=True, text=True)
    check("analyse of the second campaign exits 0", r.returncode == 0)
    check("both tables there", os.path.exists(os.path.join(out, "campaign_case_y.csv")) and
          os.path.exists(os.path.join(out, "campaign_case_x.csv")))
    if "matplotlib not found" not in r.stdout:
        check("its plots draw both variants", r.stdout.count("png: case_x, case_y") == 2)
    run_dir = os.path.join(campaign, "case_x_s1")
    r = subprocess.run([sys.executable, tool, "snapshots", run_dir, run_dir + ".yaml", "0", "2", "2.5", "9"],
                       capture_output=True, text=True)
    got = [os.path.basename(p) for p in r.stdout.split()]
    # Revolution 0 at 1 s; 2 at 5 s (5.4 s is 2.2, further), with its mesh file;
    # 2.5 at 6 s; none within a quarter revolution of 9.
    check("snapshots nearest each revolution", got == ["particles_0000001000.h5", "particles_0000005000.h5",
                                                       "meshes_0000005000.h5", "particles_0000006000.h5"])
    check("a revolution without a snapshot is named", "no snapshot within a quarter revolution of 9.0" in r.stderr)

sys.exit(1 if failures else 0)
