#!/usr/bin/python3
"""The window tests (ctest label `window`), run under tests/window/with-xvfb.sh.

  window_check.py view-and-swap MILLSIM SCENE OUTDIR
  window_check.py swap MILLSIM SCENE OUTDIR
  window_check.py mouse MILLSIM SCENE OUTDIR
  window_check.py real-ct MILLSIM SCENE OUTDIR
  window_check.py stall MILLSIM SCENE OUTDIR
  window_check.py key-sensor MILLSIM SCENE OUTDIR
  window_check.py cut-caps MILLSIM SCENE OUTDIR

Each starts `millsim run` with a window, drives it with xdotool as a person
would, and checks what the window showed (captured with ImageMagick's
`import`) and what the frame log recorded. Exit 0 when every check holds,
1 naming each one that failed.
"""
import csv
import os
import re
import subprocess
import sys
import time

import matplotlib.image
import numpy as np

failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def xdo(*args):
    return subprocess.run(["xdotool", *map(str, args)], check=True, capture_output=True, text=True).stdout.strip()


def start(millsim, scene, out, *extra, env=None):
    log = os.path.join(out, "log.csv")
    cmd = [millsim, "run", scene, "--log", log, "--screenshot", os.path.join(out, "final.png"), "--size", "640x480",
           *extra]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            env=dict(os.environ, **(env or {})))
    # The window appears once the renderers are compiled and the meshes built:
    # about 5 s alone, but a loaded 2-core box once took over 60 s.
    deadline = time.time() + 150
    window = ""
    while time.time() < deadline and proc.poll() is None:
        found = subprocess.run(["xdotool", "search", "--onlyvisible", "--pid", str(proc.pid)], capture_output=True,
                               text=True).stdout.split()
        if found:
            window = found[0]
            break
        time.sleep(0.2)
    if not window:
        output = proc.communicate(timeout=60)[0] if proc.poll() is None else proc.stdout.read()
        print(output)
        sys.exit("window_check: no window of millsim appeared within 150 s")
    time.sleep(0.8)  # a few frames drawn
    return proc, window, log


def finish(proc):
    output, _ = proc.communicate(timeout=120)
    print(output)
    check(proc.returncode == 0, f"millsim run exited 0 (got {proc.returncode})")
    return output


def capture(window, path):
    subprocess.run(["import", "-window", window, path], check=True, capture_output=True)
    return matplotlib.image.imread(path)[..., :3]


def differing(a, b):
    if a.shape != b.shape:
        return 1.0
    return float(np.mean(np.any(np.abs(a - b) > 0.06, axis=-1)))


def read_log(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return rows


def lit_fraction(img):
    # Pixels well away from the dark background (0.1, 0.12, 0.15).
    return float(np.mean(np.max(img, axis=-1) > 0.35))


def view_and_swap(millsim, scene, out):
    proc, window, log = start(millsim, scene, out, "--duration", "7")
    title = xdo("getwindowname", window)
    check("MillSim" in title, f"the window's title names MillSim ('{title}')")
    before = capture(window, os.path.join(out, "before.png"))
    check(lit_fraction(before) > 0.03, f"the window shows the tooth ({lit_fraction(before):.1%} of pixels lit)")
    # Left-drag across the middle of the window turns the scene about its centre.
    xdo("mousemove", "--window", window, 320, 300)
    xdo("mousedown", 1)
    for x in range(330, 520, 10):
        xdo("mousemove", "--window", window, x, 300)
        time.sleep(0.02)
    xdo("mouseup", 1)
    time.sleep(0.6)
    turned = capture(window, os.path.join(out, "turned.png"))
    check(differing(before, turned) > 0.02, f"a left-drag changes the view ({differing(before, turned):.1%} of pixels)")
    xdo("key", "--window", window, "Next")  # Page Down: the next Viewpoint
    time.sleep(0.6)
    paged = capture(window, os.path.join(out, "paged.png"))
    check(differing(turned, paged) > 0.02, f"Page Down changes the viewpoint ({differing(turned, paged):.1%} of pixels)")
    xdo("key", "--window", window, "3")
    finish(proc)
    rows = read_log(log)
    check(len(rows) > 3000, f"the log has a row per haptic frame ({len(rows)} rows)")
    names = [r["renderer"] for r in rows]
    check(names[0] == "SurfacePointRenderer", f"the run starts with the scene's renderer ({names[0]})")
    if "BarbicRenderer" not in names:
        check(False, "key 3 swaps to BarbicRenderer (no row names it)")
    else:
        first = names.index("BarbicRenderer")
        check(all(n == "BarbicRenderer" for n in names[first:]), "every row after the swap names BarbicRenderer")
    final = matplotlib.image.imread(os.path.join(out, "final.png"))[..., :3]
    check(lit_fraction(final) > 0.03, "the --screenshot of the window is not blank")


def swap(millsim, scene, out):
    # The burr is held pressed into the tooth (tests/data/window/press.x3d), where
    # SurfacePointRenderer and BarbicRenderer disagree by 0.6 N (2.89 against 2.30 N).
    proc, window, log = start(millsim, scene, out, "--duration", "5")
    time.sleep(2.0)
    xdo("key", "--window", window, "3")
    finish(proc)
    rows = read_log(log)
    names = [r["renderer"] for r in rows]
    if "BarbicRenderer" not in names:
        check(False, "key 3 swaps to BarbicRenderer (no row names it)")
        return
    first = names.index("BarbicRenderer")
    check(first > 1500 and len(rows) - first > 500, f"the swap came mid-press (frame {first} of {len(rows)})")
    force = np.array([[float(r["fx"]), float(r["fy"]), float(r["fz"])] for r in rows])
    # Frames the safety layer changed (bits 8-13: zeroed, ramped, blended, clamped) are
    # its doing, not the swap's: a loaded host stalls the loop (CI: 92 trips in 5 s),
    # so only steps between two frames it left alone are judged.
    clean = np.array([int(r["flags"]) & 0x3F00 == 0 for r in rows])
    pair = clean[1:] & clean[:-1]
    steps = np.linalg.norm(np.diff(force, axis=0), axis=1)
    before, after = np.arange(first - 20, first), np.arange(first + 110, first + 130)
    window = np.arange(first - 1, first + 110)
    enough = clean[before].sum() >= 10 and clean[after].sum() >= 10 and pair[window].sum() >= 80
    check(enough, f"the safety layer left enough frames around the swap to judge it "
                  f"({clean[before].sum()}/20 before, {clean[after].sum()}/20 after, {pair[window].sum()}/111 steps)")
    if not enough:
        return
    jump = np.linalg.norm(force[after[clean[after]]].mean(axis=0) - force[before[clean[before]]].mean(axis=0))
    usual = np.max(steps[first - 500:first - 1][pair[first - 500:first - 1]], initial=0.0)
    fade = steps[window][pair[window]].max()
    check(jump > 0.2, f"the two renderers' forces differ ({jump:.3f} N), so the swap is a real test")
    # A 100-frame linear cross-fade spreads the jump over 100 steps; allow 10.
    check(fade <= 0.1 * jump + 2.0 * usual + 1e-3,
          f"the swap's largest force step {fade:.4f} N is within the cross-fade's bound "
          f"(0.1 x jump {jump:.3f} N + 2 x the largest step before {usual:.4f} N)")


def mouse(millsim, scene, out):
    proc, window, log = start(millsim, scene, out, "--duration", "8")
    # Sweep the cursor along the top of the window, then into the tooth with the button held.
    for x in range(100, 560, 20):
        xdo("mousemove", "--window", window, x, 120)
        time.sleep(0.03)
    xdo("mousemove", "--window", window, 320, 200)
    time.sleep(0.2)
    xdo("mousedown", 1)
    for i in range(60):
        xdo("mousemove", "--window", window, 310 + (i % 5) * 4, 200 + i)
        time.sleep(0.04)
    xdo("mouseup", 1)
    finish(proc)
    rows = read_log(log)
    x = np.array([float(r["x"]) for r in rows])
    check(x.max() - x.min() > 0.005, f"the logged device position follows the cursor (x spans {1e3 * (x.max() - x.min()):.1f} mm)")
    pressed = sum(r["button"] == "1" for r in rows)
    check(pressed > 100, f"the left button is the milling switch ({pressed} frames with button 1)")
    removed = float(rows[-1]["removed_mm3"])
    check(removed > 0.0, f"milling with the button held removes material ({removed:.3f} mm³)")


def real_ct(millsim, scene, out):
    # x3d/lessons/real-ct.x3d as its comments tell a person to mill: the cursor on an upper front
    # tooth, Ctrl+wheel to take the burr in, Space held to mill, a small sweep across the tooth.
    proc, window, log = start(millsim, scene, out, "--duration", "9")
    xdo("mousemove", "--window", window, 320, 253)
    time.sleep(0.3)
    for _ in range(12):
        xdo("keydown", "ctrl", "click", "5", "keyup", "ctrl")
        time.sleep(0.05)
    time.sleep(0.3)
    xdo("keydown", "space")
    for i in range(40):
        xdo("mousemove", "--window", window, 314 + (i % 4) * 4, 253)
        time.sleep(0.05)
    xdo("keyup", "space")
    output = finish(proc)
    rows = read_log(log)
    # Until the cursor is first moved, the burr stays where the MouseDevice starts it (the window puts
    # the cursor on it): SDL's report of where the cursor was when the window appeared moved it.
    opened = re.search(r"first frame ([0-9.]+) ms after start", output)
    opened_ms = float(opened.group(1)) if opened else 0.0
    still = 0
    for r in rows:
        if abs(float(r["x"])) > 1e-6 or abs(float(r["y"]) + 0.0026) > 1e-6 or abs(float(r["z"]) - 0.008) > 1e-6:
            break
        still += 1
    # The first move comes 0.8 s after the window shows (start()); the haptic loop starts once the
    # meshes are built, so a slower start leaves fewer frames before it, never more. The bug this
    # guards against moved the burr at the loop's first frames (0 frames there). A bound that grew
    # with the start-up time (opened_ms + 400) failed on a loaded box with the fix in place, for the
    # build before the Session as for the one after (799 frames with the first frame at 558 ms).
    check(still > 300, f"the burr stays at the scene's start until the mouse moves ({still} frames there; "
          f"the window's first frame at {opened_ms:.0f} ms)")
    touching = sum(int(r["contacts"]) > 0 for r in rows)
    check(touching > 100, f"the burr, wheeled in, meets the scan's teeth ({touching} frames in contact)")
    removed = float(rows[-1]["removed_mm3"])
    check(removed > 0.05, f"milling with Space held cuts the tooth ({removed:.3f} mm³; about 0.4 by hand)")


def stall(millsim, scene, out):
    # The window thread sleeps 400 ms per frame; the haptic thread must not care.
    proc, window, log = start(millsim, scene, out, "--duration", "4", env={"MILLSIM_TEST_STALL_WINDOW_MS": "400"})
    output = finish(proc)
    rows = read_log(log)
    # Never a haptic gap near the window's 400 ms: a loaded host stalls the
    # loop for 10-30 ms (CI: 29 % of deadlines missed), so a frame count says
    # more about the host than about the window, and one 400 ms block would
    # still leave 90 % of the frames.
    longest = max(float(r["period_us"]) for r in rows[1:]) / 1e3 if len(rows) > 1 else float("inf")
    check(len(rows) >= 0.5 * 4000 and longest < 100.0,
          f"with the window stalled 400 ms per frame the haptic loop still ran {len(rows)} of 4000 frames, "
          f"the longest period {longest:.1f} ms")
    window_frames = [l for l in output.splitlines() if l.strip().startswith("window:")]
    check(bool(window_frames) and int(window_frames[0].split()[1]) <= 15,
          f"and the window really was stalled ({window_frames[0].strip() if window_frames else 'no window line'})")


def green_fraction(img):
    return float(np.mean((img[..., 1] > 0.5) & (img[..., 0] < 0.3) & (img[..., 2] < 0.3)))


def key_sensor(millsim, scene, out):
    # tests/data/window/key-switch.x3d: a key press reaches the KeySensor, whose
    # routes set the Switch to nothing, and the window stops drawing the green box.
    proc, window, log = start(millsim, scene, out, "--duration", "6")
    before = capture(window, os.path.join(out, "before.png"))
    check(green_fraction(before) > 0.01, f"the green box is drawn at first ({green_fraction(before):.3f} of the window)")
    xdo("key", "--window", window, "t")
    time.sleep(1.5)
    after = capture(window, os.path.join(out, "after.png"))
    check(green_fraction(after) < 0.001, f"after a key press it is not ({green_fraction(after):.4f} of the window)")
    finish(proc)


def dentin_fraction(img):
    # The dentin's colour (0.93 0.82 0.55), lit from the front: yellow, blue well under green.
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    return float(np.mean((r > 0.7) & (g > 0.6) & (b < g - 0.15)))


def cut_caps(millsim, scene, out):
    # x3d/lessons/cut-plane.x3d: the cut through the tooth is capped by its
    # section, the dentin in its colour; K shows the uncapped inside instead, and back.
    proc, window, log = start(millsim, scene, out, "--duration", "8")
    capped = capture(window, os.path.join(out, "capped.png"))
    check(dentin_fraction(capped) > 0.01, f"the cut shows the dentin's section ({dentin_fraction(capped):.3f} of the window)")
    xdo("key", "--window", window, "k")
    time.sleep(1.0)
    open_cut = capture(window, os.path.join(out, "uncapped.png"))
    check(dentin_fraction(open_cut) < 0.3 * dentin_fraction(capped),
          f"K takes the caps off ({dentin_fraction(open_cut):.3f} of the window dentin-coloured)")
    xdo("key", "--window", window, "k")
    time.sleep(1.0)
    again = capture(window, os.path.join(out, "capped-again.png"))
    check(dentin_fraction(again) > 0.7 * dentin_fraction(capped),
          f"and K again puts them back ({dentin_fraction(again):.3f})")
    finish(proc)


if __name__ == "__main__":
    if len(sys.argv) != 5 or sys.argv[1] not in ("view-and-swap", "swap", "mouse", "real-ct", "stall", "key-sensor",
                                                 "cut-caps"):
        sys.exit(__doc__)
    mode, millsim, scene, out = sys.argv[1:]
    os.makedirs(out, exist_ok=True)
    for name in os.listdir(out):
        os.remove(os.path.join(out, name))
    {"view-and-swap": view_and_swap, "swap": swap, "mouse": mouse, "real-ct": real_ct, "stall": stall,
     "key-sensor": key_sensor, "cut-caps": cut_caps}[mode](millsim, scene, out)
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
