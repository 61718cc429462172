#!/usr/bin/python3
"""scripts/score-procedure on synthetic section 8.2 logs whose faults are known:
a smooth run, one with 2 N force noise, one with a torque kick, one with a slow
loop, one whose shaft shakes, and one that rests on 4 N when the loop stops (its
last row zeroes the output: the loop's, not the renderer's). Each fault must
cost its criterion, and only it."""
import csv
import os
import subprocess
import sys
import tempfile

import numpy as np

HEADER = ("t,x,y,z,qw,qx,qy,qz,fx,fy,fz,tx,ty,tz,contacts,frame_us,draw_x,draw_y,draw_z,draw_qw,draw_qx,draw_qy,"
          "draw_qz,proxy_x,proxy_y,proxy_z,ip_x,ip_y,ip_z,button,removed_mm3,flags,period_us").split(",")


def write_log(path, force_noise=0.0, kick=0.0, period_us=1000.0, shaft_noise=0.0, rest=None, seed=1, hiccup=False):
    rng = np.random.default_rng(seed)
    n = 40000
    t = np.arange(n) * 1e-3
    cols = {h: np.zeros(n) for h in HEADER}
    a = np.radians(10.0) * np.sin(0.2 * t) + np.radians(shaft_noise) * rng.standard_normal(n)
    cols.update(t=t, qw=np.cos(a / 2), qz=-np.sin(a / 2), draw_qw=np.cos(a / 2), draw_qz=-np.sin(a / 2),
                fy=1.0 + 0.5 * np.sin(t) + force_noise * rng.standard_normal(n),
                tz=0.002 * np.sin(0.5 * t), period_us=np.full(n, period_us), button=(t < 20).astype(float))
    cols["tz"][30000:30005] += kick
    # A watchdog trip with its soft start at 35 s: a loop event, not the renderer's; it must not cost force.
    cols["flags"][35000:35250] = (1 << 9) | (1 << 11)
    cols["fy"][35000] = 0.0
    if hiccup:  # a late frame at 36 s, the held wrench sent (no blend after it): a loop event, not a kick
        cols["flags"][36000] = 1 << 13
        cols["tz"][36000] += 0.05
    if rest is not None:  # leaning in harder over the last half second
        cols["fy"][-500:] = np.linspace(cols["fy"][-500], rest, 500)
    # The loop's last row: the device stopped, its output zeroed (SafetyLayer's kSafetyStopped).
    cols["flags"][-1] = 1 << 12
    cols["fy"][-1] = 0.0
    np.savetxt(path, np.stack([cols[h] for h in HEADER], 1), delimiter=",", header=",".join(HEADER), comments="")


def main():
    script = sys.argv[1]
    with tempfile.TemporaryDirectory() as d:
        logs = {name: os.path.join(d, name + ".csv")
                for name in ("smooth", "noisy", "kick", "slow", "shaky", "resting")}
        write_log(logs["smooth"], hiccup=True)
        write_log(logs["noisy"], force_noise=0.2)
        write_log(logs["kick"], kick=0.05)
        write_log(logs["slow"], period_us=1250.0)
        write_log(logs["shaky"], shaft_noise=0.5)
        write_log(logs["resting"], rest=4.0)
        out = os.path.join(d, "score.csv")
        r = subprocess.run([script, *logs.values(), *sum((["--label", k] for k in logs), []), "--csv", out],
                           capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit(f"score-procedure failed: {r.stderr}")
        scores = {}
        with open(out) as f:
            for row in csv.DictReader(f):
                scores[row["algorithm"]] = {k: int(row["score_" + k]) for k in ("rate", "force", "torque", "shaft")}
        expected = {
            "smooth": dict(rate=1, force=1, torque=1, shaft=1),
            "noisy": dict(rate=1, force=3, torque=1, shaft=1),
            "kick": dict(rate=1, force=1, torque=3, shaft=1),
            "slow": dict(rate=3, force=1, torque=1, shaft=1),
            "shaky": dict(rate=1, force=1, torque=1, shaft=3),
            "resting": dict(rate=1, force=1, torque=1, shaft=1),
        }
        bad = {k: (scores[k], v) for k, v in expected.items() if scores[k] != v}
        if bad:
            sys.exit(f"unexpected scores (got, expected): {bad}\n{r.stdout}")
        # A log without the drawn pose is refused with the missing columns named.
        broken = os.path.join(d, "broken.csv")
        with open(broken, "w") as f:
            f.write("t,fx\n0,1\n0.001,1\n")
        r = subprocess.run([script, broken], capture_output=True, text=True)
        if r.returncode == 0 or "missing columns" not in r.stderr:
            sys.exit(f"a log without the needed columns was not refused clearly: rc={r.returncode} {r.stderr}")
    print("score-procedure: every synthetic fault cost its own criterion")


if __name__ == "__main__":
    main()
