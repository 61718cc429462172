#!/usr/bin/python3
"""Checks `millsim sweep` end to end (issue 46).

  sweep_check.py local APP SOURCE_DIR WORK_DIR
      8 replay cells run --local two at once; Ctrl-C after two have finished
      exits 130 and keeps them; the rerun runs only the rest; the same sweep
      run again one cell at a time gives byte-identical result files; collect
      merges 8 rows.
  sweep_check.py slurm APP SOURCE_DIR WORK_DIR
      starts munged, slurmctld and slurmd on this machine from a configuration
      in WORK_DIR (proctrack/linuxproc, task/none: no cgroups), submits the
      same 8 cells as one job array and compares every cell's files and the
      collected table with --local's; cancels a running cell with scancel and
      retries it with --retry-failed; stops the daemons it started. A daemon
      that does not start fails the test with its log: it never passes by
      skipping.
Exits 0 when every check holds, else 1 saying which did not.
"""
import filecmp
import getpass
import os
import shutil
import signal
import socket
import subprocess
import sys
import time

RENDERERS = ["LineProxyRenderer", "SurfacePointRenderer"]
RATES = [990, 995, 1000, 1005]
RESULT_FILES = ["log.csv", "report.json"]


def fail(message):
    print("FAIL: " + message, flush=True)
    sys.exit(1)


def run(cmd, **kw):
    print("$ " + " ".join(str(c) for c in cmd), flush=True)
    r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, **kw)
    sys.stdout.write(r.stdout)
    sys.stdout.write(r.stderr)
    return r


def make_folder(source, work, name, trajectory_seconds=3.0, rates=RATES, trajectory="mill-and-lean.csv", coarse=True):
    """A sweep folder holding its scene and a trajectory's first seconds; `coarse`: the phantom at 0.2 mm."""
    folder = os.path.join(work, name)
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(os.path.join(folder, "trajectories"))
    shutil.copy(os.path.join(source, "x3d/default.x3d"), folder)
    # The scene's device names mill-and-lean.csv (a replay's --trajectory takes its place).
    shutil.copy(os.path.join(source, "x3d/trajectories/mill-and-lean.csv"), os.path.join(folder, "trajectories"))
    with open(os.path.join(source, "x3d/trajectories", trajectory)) as f:
        lines = f.read().splitlines()
    header = next(i for i, l in enumerate(lines) if l.startswith("t,"))
    kept = lines[: header + 1] + [l for l in lines[header + 1 :] if float(l.split(",")[0]) <= trajectory_seconds]
    with open(os.path.join(folder, "trajectories", trajectory), "w") as f:
        f.write("\n".join(kept) + "\n")
    grid = ", ".join(str(r) for r in rates)
    with open(os.path.join(folder, "grid.json"), "w") as f:
        f.write('{\n  "sweep": "grid",\n  "verb": "replay",\n'
                '  "fixed": {"scene": "default.x3d", "trajectory": "trajectories/%s"%s},\n'
                '  "grid": {"renderer": ["%s"], "rate": [%s]},\n'
                '  "slurm": {"max_parallel": 2}\n}\n' % (trajectory, (
                    # The phantom at 0.2 mm: each cell loads in a quarter of the time.
                    ',\n            "set": ["VolumeObject.url=\\"phantom:tooth?size=128,128,88&voxel=0.0002\\"",\n'
                    '                    "VolumeObject.labelUrl=\\"phantom:tooth-labels?size=128,128,88&voxel=0.0002\\""]')
                    if coarse else "", '", "'.join(RENDERERS), grid))
    return os.path.join(folder, "grid.json")


def statuses(out):
    cells = os.path.join(out, "cells")
    if not os.path.isdir(cells):
        return {}
    found = {}
    for c in sorted(os.listdir(cells)):
        p = os.path.join(cells, c, "status.json")
        if os.path.exists(p):
            with open(p) as f:
                found[c] = f.read()
    return found


def compare_cells(a, b, what):
    cells = sorted(os.listdir(os.path.join(a, "cells")))
    if len(cells) != len(RENDERERS) * len(RATES):
        fail("%s: %d cells in %s, expected %d" % (what, len(cells), a, len(RENDERERS) * len(RATES)))
    for c in cells:
        for name in RESULT_FILES:
            x, y = os.path.join(a, "cells", c, name), os.path.join(b, "cells", c, name)
            if not os.path.exists(x) or not os.path.exists(y):
                fail("%s: cell %s has no %s in both" % (what, c, name))
            if not filecmp.cmp(x, y, shallow=False):
                fail("%s: cell %s's %s differs between %s and %s" % (what, c, name, a, b))
    print("%s: %d cells, their %s byte for byte the same" % (what, len(cells), " and ".join(RESULT_FILES)), flush=True)


def collected_without_timings(app, sweep, out):
    r = run([app, "sweep", "collect", sweep, "--out", out])
    if r.returncode != 0:
        fail("collect of %s exited %d" % (out, r.returncode))
    with open(os.path.join(out, "results.csv")) as f:
        rows = [l.split(",") for l in f.read().splitlines()]
    header = rows[0]
    drop = {i for i, name in enumerate(header) if name in ("host", "cell_seconds")}
    return [[v for i, v in enumerate(row) if i not in drop] for row in rows]


def check_local(app, source, work):
    sweep = make_folder(source, work, "local")
    out = os.path.join(work, "local", "grid.sweep")
    # Interrupted once two cells have finished.
    p = subprocess.Popen([app, "sweep", sweep, "--local", "-j", "2"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         text=True)
    deadline = time.time() + 120
    while len(statuses(out)) < 2:
        if p.poll() is not None:
            fail("the sweep ended (exit %s) before it could be interrupted:\n%s" % (p.returncode, p.stdout.read()))
        if time.time() > deadline:
            p.kill()
            fail("two cells did not finish within 120 s")
        time.sleep(0.05)
    # One executor at a time on a results folder.
    second = run([app, "sweep", sweep, "--local"])
    if second.returncode == 0 or "is in use by another `millsim sweep`" not in second.stderr:
        p.kill()
        fail("a second --local on the same results folder was not refused (exit %d)" % second.returncode)
    p.send_signal(signal.SIGINT)
    text = p.communicate(timeout=60)[0]
    print(text, flush=True)
    if p.returncode != 130:
        fail("an interrupted sweep exited %d, expected 130" % p.returncode)
    if "interrupted (Ctrl-C)" not in text:
        fail("an interrupted sweep did not say so")
    kept = statuses(out)
    if not 2 <= len(kept) < len(RENDERERS) * len(RATES):
        fail("after Ctrl-C %d cells have a status; expected at least 2 and not all" % len(kept))
    r = run([app, "sweep", sweep, "--local", "-j", "2"])
    if r.returncode != 0:
        fail("the rerun exited %d" % r.returncode)
    if "%d done before, %d to run here" % (len(kept), 8 - len(kept)) not in r.stdout:
        fail("the rerun did not run only the %d cells left" % (8 - len(kept)))
    after = statuses(out)
    for cell, status in kept.items():
        if after.get(cell) != status:
            fail("cell %s finished before Ctrl-C and was run again" % cell)
    # The same cells alone, one at a time, in another folder.
    alone = os.path.join(work, "local", "alone.sweep")
    r = run([app, "sweep", sweep, "--local", "-j", "1", "--out", alone])
    if r.returncode != 0:
        fail("the sweep run one cell at a time exited %d" % r.returncode)
    compare_cells(out, alone, "two at once against one at a time")
    a, b = collected_without_timings(app, sweep, out), collected_without_timings(app, sweep, alone)
    if len(a) != 9:
        fail("collect merged %d rows, expected a header and 8" % len(a))
    if a != b:
        fail("the collected tables differ beyond host and cell_seconds")
    print("local: all checks hold", flush=True)


# --- a single-node Slurm cluster on this machine -------------------------------------------------

def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Cluster:
    def __init__(self, work):
        self.dir = os.path.join(work, "cluster")
        shutil.rmtree(self.dir, ignore_errors=True)
        for d in ("state", "spool", "munge", "log"):
            os.makedirs(os.path.join(self.dir, d))
        self.procs = []
        self.host = socket.gethostname().split(".")[0]
        self.env = dict(os.environ, SLURM_CONF=os.path.join(self.dir, "slurm.conf"))

    def log(self, name):
        p = os.path.join(self.dir, "log", name)
        return open(p).read() if os.path.exists(p) else "(no log)"

    def start(self):
        for tool in ("munged", "slurmctld", "slurmd", "sbatch", "squeue", "scancel", "sinfo"):
            if not shutil.which(tool) and not os.path.exists("/usr/sbin/" + tool):
                fail("%s is not installed: the slurm tests need munge, slurmctld, slurmd and slurm-client "
                     "(scripts/setup installs them)" % tool)
        m = os.path.join(self.dir, "munge")
        key = os.path.join(m, "munge.key")
        with open(key, "wb") as f:
            f.write(os.urandom(1024))
        os.chmod(key, 0o400)
        os.chmod(m, 0o700)
        self.socket = os.path.join(m, "munge.socket")
        r = run(["/usr/sbin/munged", "--force", "--key-file", key, "--socket", self.socket,
                 "--pid-file", os.path.join(m, "munged.pid"), "--log-file", os.path.join(self.dir, "log/munged.log"),
                 "--seed-file", os.path.join(m, "munged.seed")])
        if r.returncode != 0:
            fail("munged did not start: " + self.log("munged.log"))
        self.munge_pid = int(open(os.path.join(m, "munged.pid")).read())
        d = self.dir
        conf = "\n".join([
            "ClusterName=millsimtest",
            "SlurmctldHost=%s(127.0.0.1)" % self.host,
            # Whoever runs the test (root on CI): the daemons need no other account.
            "SlurmUser=%s" % getpass.getuser(), "SlurmdUser=%s" % getpass.getuser(),
            "SlurmctldPort=%d" % free_port(), "SlurmdPort=%d" % free_port(),
            "AuthType=auth/munge", "CredType=cred/munge", "AuthInfo=socket=%s" % self.socket,
            "StateSaveLocation=%s/state" % d, "SlurmdSpoolDir=%s/spool" % d,
            "SlurmctldPidFile=%s/slurmctld.pid" % d, "SlurmdPidFile=%s/slurmd.pid" % d,
            "SlurmctldLogFile=%s/log/slurmctld.log" % d, "SlurmdLogFile=%s/log/slurmd.log" % d,
            "ProctrackType=proctrack/linuxproc", "TaskPlugin=task/none",
            "JobAcctGatherType=jobacct_gather/none", "AccountingStorageType=accounting_storage/none",
            "JobCompType=jobcomp/none", "MpiDefault=none", "ReturnToService=2",
            "SchedulerType=sched/builtin", "SelectType=select/cons_tres", "SelectTypeParameters=CR_CPU",
            "SlurmdParameters=config_overrides", "MinJobAge=5", "KillWait=5",
            "NodeName=%s NodeAddr=127.0.0.1 CPUs=2 RealMemory=1000 State=UNKNOWN" % self.host,
            "PartitionName=test Nodes=%s Default=YES MaxTime=INFINITE State=UP" % self.host,
        ]) + "\n"
        with open(self.env["SLURM_CONF"], "w") as f:
            f.write(conf)
        for daemon, log in (("slurmctld", "slurmctld.log"), ("slurmd", "slurmd.log")):
            args = ["/usr/sbin/" + daemon, "-D", "-f", self.env["SLURM_CONF"]]
            if daemon == "slurmd":
                args += ["-N", self.host]
            else:
                args += ["-i"]  # ignore state a previous run left
            out = open(os.path.join(self.dir, "log", daemon + ".out"), "w")
            self.procs.append((daemon, subprocess.Popen(args, env=self.env, stdout=out, stderr=subprocess.STDOUT)))
            time.sleep(0.5)
            if self.procs[-1][1].poll() is not None:
                fail("%s exited at once (%s):\n%s\n%s" % (daemon, self.procs[-1][1].returncode, self.log(log),
                                                          self.log(daemon + ".out")))
        deadline = time.time() + 60
        while True:
            r = subprocess.run(["sinfo", "-h", "-N", "-o", "%T"], env=self.env, capture_output=True, text=True)
            if r.returncode == 0 and r.stdout.strip() in ("idle", "mixed", "allocated"):
                break
            if time.time() > deadline:
                fail("the node did not become idle within 60 s (sinfo: %r %r)\nslurmctld:\n%s\nslurmd:\n%s" % (
                    r.stdout, r.stderr, self.log("slurmctld.log")[-3000:], self.log("slurmd.log")[-3000:]))
            time.sleep(0.5)
        print("cluster up: node %s idle" % self.host, flush=True)

    def stop(self):
        for name, p in reversed(self.procs):
            if p.poll() is None:
                p.terminate()
                try:
                    p.wait(timeout=20)
                except subprocess.TimeoutExpired:
                    p.kill()
        if getattr(self, "munge_pid", None):
            try:
                os.kill(self.munge_pid, signal.SIGTERM)
            except ProcessLookupError:
                pass


def check_slurm(app, source, work):
    cluster = Cluster(work)
    try:
        cluster.start()
        env = cluster.env
        sweep = make_folder(source, work, "slurm")
        local_out = os.path.join(work, "slurm", "local.sweep")
        r = run([app, "sweep", sweep, "--local", "--out", local_out])
        if r.returncode != 0:
            fail("the local run exited %d" % r.returncode)
        slurm_out = os.path.join(work, "slurm", "slurm.sweep")
        r = run([app, "sweep", sweep, "--slurm", "--wait", "--timeout", "300", "--out", slurm_out], env=env)
        if r.returncode != 0:
            fail("the Slurm run exited %d\nslurmctld:\n%s" % (r.returncode, cluster.log("slurmctld.log")[-3000:]))
        if "submitted job" not in r.stdout:
            fail("no job was submitted")
        for c, status in statuses(slurm_out).items():
            if '"executor": "slurm job' not in status:
                fail("cell %s did not run as a Slurm task: %s" % (c, status))
        compare_cells(local_out, slurm_out, "--local against --slurm")
        if collected_without_timings(app, sweep, local_out) != collected_without_timings(app, sweep, slurm_out):
            fail("the collected tables of --local and --slurm differ beyond host and cell_seconds")
        # A cell cancelled while it runs is a failed cell; --retry-failed runs only it again.
        # Cells of a few seconds (the §8.2 procedure at the phantom's 0.1 mm): one is still running when cancelled.
        long_sweep = make_folder(source, work, "cancel", trajectory_seconds=40.0, rates=[1000],
                                 trajectory="section-8-2.csv", coarse=False)
        out = os.path.join(work, "cancel", "grid.sweep")
        r = run([app, "sweep", long_sweep, "--slurm", "--out", out], env=env)
        if r.returncode != 0:
            fail("submitting the sweep to cancel exited %d" % r.returncode)
        job = open(os.path.join(out, "slurm", "jobs.txt")).read().split()[-1]
        deadline = time.time() + 120
        while True:
            q = subprocess.run(["squeue", "-h", "-r", "-j", job, "-o", "%K %T"], env=env, capture_output=True, text=True)
            running = [l.split()[0] for l in q.stdout.splitlines() if l.endswith("RUNNING")]
            if running:
                break
            if time.time() > deadline:
                fail("no cell of job %s started within 120 s" % job)
            time.sleep(0.1)
        victim = running[0]
        # Cancel once the cell's command has started (its folder is made after the task blocks SIGTERM for
        # itself): a task cancelled before that dies without a status, which is another case.
        started = os.path.join(out, "cells", "%04d" % int(victim), "command.txt")
        deadline = time.time() + 60
        while not os.path.exists(started):
            if time.time() > deadline:
                fail("cell %s's command did not start within 60 s of its task running" % victim)
            time.sleep(0.02)
        run(["scancel", "%s_%s" % (job, victim)], env=env)
        r = run([app, "sweep", long_sweep, "--slurm", "--wait", "--timeout", "300", "--out", out], env=env)
        status = run([app, "sweep", "status", long_sweep, "--out", out], env=env)
        cell = "%04d" % int(victim)
        if ("failed: cell %s (exit 143" % cell) not in status.stdout:
            fail("the cancelled cell %s is not listed as failed with exit 143 (SIGTERM)" % cell)
        if status.returncode == 0:
            fail("status exits 0 with a failed cell")
        r = run([app, "sweep", long_sweep, "--slurm", "--retry-failed", "--wait", "--timeout", "300", "--out", out], env=env)
        if r.returncode != 0 or "1 to submit" not in r.stdout:
            fail("--retry-failed did not submit exactly the cancelled cell and finish (exit %d)" % r.returncode)
        print("slurm: all checks hold", flush=True)
    finally:
        cluster.stop()


def main():
    if len(sys.argv) != 5 or sys.argv[1] not in ("local", "slurm"):
        print(__doc__)
        sys.exit(2)
    mode, app, source, work = sys.argv[1:]
    os.makedirs(work, exist_ok=True)
    (check_local if mode == "local" else check_slurm)(app, source, work)


if __name__ == "__main__":
    main()
