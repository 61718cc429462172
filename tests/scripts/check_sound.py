#!/usr/bin/python3
"""check_sound.py LOG.csv SOUND.wav [--min-ratio R] [--same-as OTHER.wav]

Checks a --sound-out WAV against the frame log of the same run (millsim run or
millsim replay; issue 13, part 8):

- it is 16-bit PCM mono;
- it is as long as the run (the last frame's t plus one period), within one frame;
- its power while the burr cuts (removed volume rising) is at least R times
  (default 4) its power while the burr spins in free air (button on, no
  contact, nothing removed), each measured away from the transitions;
- it is near silent while the milling switch has been off for a while;
- with --same-as, it is byte-identical to another WAV (a replay's sound is reproducible).

Exits 1 with the reason on any failure; prints the figures either way."""
import argparse
import csv
import math
import sys
import wave

GUARD = 0.1      # s kept away from a change of state (envelopes, smoothing)
OFF_GUARD = 0.3  # s after the switch goes off before the burr must be silent


def fail(msg):
    print("check_sound: FAIL: " + msg)
    sys.exit(1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("log")
    ap.add_argument("wav")
    ap.add_argument("--min-ratio", type=float, default=4.0)
    ap.add_argument("--same-as")
    a = ap.parse_args()

    with open(a.log, newline="") as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    if len(rows) < 2:
        fail(f"{a.log}: fewer than two frames")
    t = [float(r["t"]) for r in rows]
    button = [r["button"] == "1" for r in rows]
    removed = [float(r["removed_mm3"]) for r in rows]
    contacts = [int(r["contacts"]) for r in rows]
    steps = sorted(t[i + 1] - t[i] for i in range(len(t) - 1))
    period = steps[len(steps) // 2]
    run_length = t[-1] + period

    with wave.open(a.wav, "rb") as w:
        if w.getnchannels() != 1 or w.getsampwidth() != 2:
            fail(f"{a.wav}: {w.getnchannels()} channels of {8 * w.getsampwidth()} bits, expected 16-bit mono")
        fs = w.getframerate()
        n = w.getnframes()
        raw = w.readframes(n)
    samples = memoryview(raw).cast("h")
    if len(samples) != n:
        fail(f"{a.wav}: the header says {n} samples, the data holds {len(samples)}")
    seconds = n / fs
    print(f"check_sound: {a.wav}: {n} samples at {fs} Hz = {seconds:.4f} s; the run is {run_length:.4f} s "
          f"({len(rows)} frames of {period * 1e3:.3f} ms)")
    if abs(seconds - run_length) > period + 1.0 / fs:
        fail(f"the WAV lasts {seconds:.4f} s, the run {run_length:.4f} s (more than one frame apart)")

    # Per frame: is material being removed (within 10 ms either side)?
    k = max(1, round(0.01 / period))
    cutting = [removed[min(i + k, len(rows) - 1)] > removed[max(i - k, 0)] for i in range(len(rows))]
    state = []
    for i in range(len(rows)):
        if not button[i]:
            state.append("off")
        elif cutting[i]:
            state.append("cut")
        elif contacts[i] == 0:
            state.append("air")
        else:
            state.append("touch")
    # Keep a frame only when its state held for GUARD before and after (OFF_GUARD before, for silence).
    changes = [t[0]] + [t[i] for i in range(1, len(rows)) if state[i] != state[i - 1]] + [run_length]
    power = {"cut": [0.0, 0], "air": [0.0, 0], "off": [0.0, 0]}
    c = 0
    for i in range(len(rows)):
        while c + 1 < len(changes) and changes[c + 1] <= t[i]:
            c += 1
        start, end = changes[c], changes[c + 1]
        s = state[i]
        if s not in power:
            continue
        before = OFF_GUARD if s == "off" else GUARD
        if (start > t[0] and t[i] - start < before) or end - (t[i] + period) < GUARD:
            continue
        lo, hi = round(t[i] * fs), min(round((t[i] + period) * fs), n)
        for j in range(lo, hi):
            power[s][0] += float(samples[j]) ** 2
        power[s][1] += hi - lo

    def mean(s):
        return power[s][0] / power[s][1] if power[s][1] else float("nan")

    for s in ("air", "cut", "off"):
        p = mean(s)
        db = 10 * math.log10(p / 32768.0 ** 2) if p > 0 else float("-inf")
        print(f"check_sound: {s}: {power[s][1] / fs:.3f} s, mean power {p:.1f} ({db:.1f} dBFS)")
    if power["air"][1] < 0.2 * fs or power["cut"][1] < 0.2 * fs:
        fail("the log has less than 0.2 s of steady free air or of steady cutting to compare")
    ratio = mean("cut") / mean("air") if mean("air") > 0 else float("inf")
    print(f"check_sound: power cutting / free air = {ratio:.2f} (need >= {a.min_ratio})")
    if mean("air") <= 0:
        fail("silent while spinning in free air")
    if not ratio >= a.min_ratio:
        fail(f"power while cutting is {ratio:.2f} times that in free air, expected at least {a.min_ratio}")
    if power["off"][1] and mean("off") > 0.01 * mean("air"):
        fail(f"not silent with the switch off: power {mean('off'):.1f}, free air {mean('air'):.1f}")
    if a.same_as:
        with open(a.wav, "rb") as f1, open(a.same_as, "rb") as f2:
            if f1.read() != f2.read():
                fail(f"{a.wav} and {a.same_as} differ: the sound is not reproducible")
        print(f"check_sound: identical to {a.same_as}")
    print("check_sound: ok")


if __name__ == "__main__":
    main()
