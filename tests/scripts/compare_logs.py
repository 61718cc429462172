#!/usr/bin/python3
"""Compares two MillSim frame logs cell by cell, as text (the logs print
shortest round-trip numbers, so equal text is equal bits).

  compare_logs.py A.csv B.csv [--ignore COLUMN ...] [--min-rows N]
  compare_logs.py --self-test

Exit 0 when every row and every column but the ignored ones is the same;
1 with the first difference (row, column, both values) otherwise.
"""
import argparse
import sys


def read(path):
    with open(path, newline="") as f:
        lines = f.read().splitlines()
    if not lines:
        raise SystemExit(f"compare_logs: {path} is empty")
    return lines[0].split(","), [line.split(",") for line in lines[1:]]


def compare(a_header, a_rows, b_header, b_rows, ignore, min_rows):
    """Returns None when equal, else a message naming the first difference."""
    if a_header != b_header:
        return f"the headers differ: {','.join(a_header)} vs {','.join(b_header)}"
    if len(a_rows) < min_rows:
        return f"{len(a_rows)} rows, expected at least {min_rows}"
    if len(a_rows) != len(b_rows):
        return f"{len(a_rows)} rows vs {len(b_rows)}"
    keep = [i for i, name in enumerate(a_header) if name not in ignore]
    for n, (ra, rb) in enumerate(zip(a_rows, b_rows), start=2):
        for i in keep:
            if ra[i] != rb[i]:
                return f"line {n}, column '{a_header[i]}': {ra[i]} vs {rb[i]}"
    return None


def self_test():
    header = ["t", "fx", "frame_us"]
    rows = [["0", "0.5", "12"], ["0.001", "0.25", "13"]]
    assert compare(header, rows, header, [r[:] for r in rows], set(), 2) is None
    changed = [r[:] for r in rows]
    changed[1][2] = "99"
    assert compare(header, rows, header, changed, {"frame_us"}, 2) is None, "an ignored column must not count"
    changed[1][1] = "0.25000000000000006"  # one ulp
    assert "line 3, column 'fx'" in compare(header, rows, header, changed, {"frame_us"}, 2)
    assert "rows vs" in compare(header, rows, header, rows[:1], set(), 1)
    assert "expected at least" in compare(header, rows, header, rows, set(), 3)
    print("compare_logs: self-test passed")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("a", nargs="?")
    p.add_argument("b", nargs="?")
    p.add_argument("--ignore", nargs="*", default=[])
    p.add_argument("--min-rows", type=int, default=1)
    p.add_argument("--self-test", action="store_true")
    args = p.parse_args()
    if args.self_test:
        self_test()
        return 0
    ah, ar = read(args.a)
    bh, br = read(args.b)
    diff = compare(ah, ar, bh, br, set(args.ignore), args.min_rows)
    if diff:
        print(f"compare_logs: {args.a} and {args.b} differ: {diff}")
        return 1
    print(f"compare_logs: {len(ar)} rows equal")
    return 0


if __name__ == "__main__":
    sys.exit(main())
