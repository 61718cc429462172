#!/usr/bin/python3
"""Compare two lesson reports (millsim run/replay --report): a run and its
review must agree on what was removed, where, and the score. Durations may
differ (a run counts first to last frame, a replay frames / rate), and a live
run stamps a first violation when its scene thread counts (every ~20 ms).

  compare_reports.py RUN.json REVIEW.json
Exit 0 when they agree, 1 with the differences listed."""
import json
import math
import sys


def close(a, b, rel=1e-9, absolute=1e-12):
    return math.isclose(a, b, rel_tol=rel, abs_tol=absolute)


def compare(a, b):
    problems = []
    for key in ("renderer",):
        if a[key] != b[key]:
            problems.append(f"{key}: {a[key]!r} != {b[key]!r}")
    for key in ("removed_mm3", "peak_force_N", "peak_torque_Nm"):
        if not close(a[key], b[key]):
            problems.append(f"{key}: {a[key]} != {b[key]}")
    if (a["score"] is None) != (b["score"] is None) or (a["score"] is not None and not close(a["score"], b["score"])):
        problems.append(f"score: {a['score']} != {b['score']}")
    # Over-preparation and removal per tissue (reports since issue 47 part 6): the same blocks, the same sums.
    for key in ("outside_targets_mm3", "over_preparation", "deepest_cut_mm"):
        if (key in a) != (key in b) or (key in a and not close(a[key], b[key])):
            problems.append(f"{key}: {a.get(key)} != {b.get(key)}")
    ca, cb = a.get("completed_s"), b.get("completed_s")
    if (ca is None) != (cb is None) or (ca is not None and abs(ca - cb) > 0.025):
        problems.append(f"completed_s: {ca} != {cb}")
    ta = [(t["name"], t["removed_mm3"]) for t in a.get("tissues", [])]
    tb = [(t["name"], t["removed_mm3"]) for t in b.get("tissues", [])]
    if [n for n, _ in ta] != [n for n, _ in tb] or any(not close(x, y) for (_, x), (_, y) in zip(ta, tb)):
        problems.append(f"tissues: {ta} != {tb}")
    for kind in ("targets", "forbidden"):
        if [r["name"] for r in a[kind]] != [r["name"] for r in b[kind]]:
            problems.append(f"{kind}: names differ")
            continue
        for ra, rb in zip(a[kind], b[kind]):
            for key in ("removed_mm3", "fraction"):
                if key in ra and not close(ra[key], rb[key]):
                    problems.append(f"{kind} '{ra['name']}' {key}: {ra[key]} != {rb[key]}")
            if kind == "forbidden":
                fa, fb = ra["first_violation_s"], rb["first_violation_s"]
                if (fa is None) != (fb is None) or (fa is not None and abs(fa - fb) > 0.025):
                    problems.append(f"forbidden '{ra['name']}' first_violation_s: {fa} != {fb}")
                wa, wb = ra.get("thinnest_wall_mm"), rb.get("thinnest_wall_mm")
                if (wa is None) != (wb is None) or (wa is not None and not close(wa, wb)):
                    problems.append(f"forbidden '{ra['name']}' thinnest_wall_mm: {wa} != {wb}")
    return problems


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    with open(argv[1]) as f:
        a = json.load(f)
    with open(argv[2]) as f:
        b = json.load(f)
    problems = compare(a, b)
    for p in problems:
        print("differs:", p)
    if not problems:
        print(f"reports agree: removed {a['removed_mm3']:.4f} mm³, score {a['score']}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
