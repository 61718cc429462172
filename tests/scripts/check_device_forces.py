#!/usr/bin/python3
"""Checks that the wrenches a device emulator received are the run log's.

  check_device_forces.py RUN-LOG.csv EMULATOR-RECORD.csv [--torque sent|not-sent]

The run log has one row per haptic frame (the wrench after the safety layer)
and ends with the stop row (zero); the emulator's record has one row per
device frame it ended (t,fx,fy,fz[,tx,ty,tz]), the last the driver's own zero
frame. Exit 0 when every logged force equals, in order, the force the device
got (to the last bit: both print shortest round-trip or 17 digits), and the
device's last force is zero; 1 with the first difference otherwise.

--torque sent: the record's torques are the log's, to the last bit.
--torque not-sent: the device outputs force only: every torque it got is
zero, the log holds the rendered torque, and each frame with a non-zero one
carries the flag that says it was not sent (kSafetyTorqueNotOutput, 1 << 14);
at least one frame must have had torque, or the check proves nothing.
"""
import csv
import sys

TORQUE_NOT_OUTPUT = 1 << 14


def main():
    args = sys.argv[1:]
    torque = None
    if "--torque" in args:
        i = args.index("--torque")
        torque = args[i + 1]
        del args[i:i + 2]
        if torque not in ("sent", "not-sent"):
            sys.exit(__doc__)
    if len(args) != 2:
        sys.exit(__doc__)
    with open(args[0], newline="") as f:
        log = list(csv.DictReader(f))
    with open(args[1], newline="") as f:
        rec = list(csv.DictReader(f))
    f3 = lambda r, k: tuple(float(r[k + a]) for a in "xyz")
    logged = [f3(r, "f") for r in log]
    got = [f3(r, "f") for r in rec]
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
    said = f"{len(frames)} frames, every force as logged; peak component {peak:.3f} N; last zero"
    if torque:
        if "tx" not in rec[0]:
            sys.exit("check_device_forces: --torque needs a record with tx,ty,tz")
        tlog = [f3(r, "t") for r in log[:-1]]
        tgot = [f3(r, "t") for r in rec]
        if torque == "sent":
            for i, (a, b) in enumerate(zip(tlog, tgot)):
                if a != b:
                    sys.exit(f"check_device_forces: frame {i}: the log's torque is {a}, the device got {b}")
            if tgot[-1] != (0.0, 0.0, 0.0):
                sys.exit(f"check_device_forces: the last torque is not zero ({tgot[-1]})")
            said += f"; every torque as logged, peak component {max(abs(c) for row in tgot for c in row):.4f} N·m"
        else:
            for i, b in enumerate(tgot):
                if b != (0.0, 0.0, 0.0):
                    sys.exit(f"check_device_forces: device frame {i}: a force-only device was sent torque {b}")
            held = 0
            for i, (r, t) in enumerate(zip(log[:-1], tlog)):
                if t != (0.0, 0.0, 0.0):
                    held += 1
                    if not int(r["flags"]) & TORQUE_NOT_OUTPUT:
                        sys.exit(f"check_device_forces: frame {i}: torque {t} logged without the not-sent flag")
            if held == 0:
                sys.exit("check_device_forces: no frame had torque: nothing shows that torque is held back")
            said += f"; no torque sent, {held} frames of rendered torque logged and flagged"
    print("check_device_forces: " + said)


main()
