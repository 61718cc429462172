#!/usr/bin/python3
"""Checks that the forces a device emulator received are the run log's.

  check_device_forces.py RUN-LOG.csv EMULATOR-RECORD.csv

The run log has one row per haptic frame (force after the safety layer, as
sent) and ends with the stop row (zero); the emulator's record has one row
per device frame it ended (t,fx,fy,fz), the last the driver's own zero frame.
Exit 0 when every logged force equals, in order, the force the device got
(to the last bit: both print shortest round-trip or 17 digits), and the
device's last force is zero; 1 with the first difference otherwise.
"""
import csv
import sys


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1], newline="") as f:
        logged = [(float(r["fx"]), float(r["fy"]), float(r["fz"])) for r in csv.DictReader(f)]
    with open(sys.argv[2], newline="") as f:
        got = [(float(r["fx"]), float(r["fy"]), float(r["fz"])) for r in csv.DictReader(f)]
    if len(logged) < 100:
        sys.exit(f"check_device_forces: only {len(logged)} logged frames")
    # The log's frames, then its stop row; the device: one frame per haptic frame, then the zero frame of the stop.
    frames = logged[:-1]
    if len(got) != len(frames) + 1:
        sys.exit(f"check_device_forces: the device ended {len(got)} frames for {len(frames)} haptic frames (+1 stop)")
    for i, (a, b) in enumerate(zip(frames, got)):
        if a != b:
            sys.exit(f"check_device_forces: frame {i}: the log says {a}, the device got {b}")
    if got[-1] != (0.0, 0.0, 0.0) or logged[-1] != (0.0, 0.0, 0.0):
        sys.exit(f"check_device_forces: the last force is not zero (device {got[-1]}, log {logged[-1]})")
    peak = max(abs(c) for row in got for c in row)
    print(f"check_device_forces: {len(frames)} frames, every force as logged; peak component {peak:.3f} N; last zero")


main()
