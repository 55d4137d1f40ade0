#!/usr/bin/python3
"""Reference: reading TUM trajectories and associating timestamps.

An independent Python 3 + numpy re-implementation of the TUM RGB-D benchmark's
association rule (written from the algorithm's description, see
docs/evaluation.md). DLSLAM's C++ evaluation is tested against it.

  tum_associate.py GT EST [--offset 0] [--max-diff 0.02]
prints {"pairs": N, "matches": [[gt_row, est_row], ...]} where the rows are
0-based indices of the poses in the files (comments and blank lines skipped).
"""
import argparse
import json
import sys


def read_trajectory(path):
    """Returns (stamps, values): stamps[i] a float, values[i] = [tx ty tz qx qy qz qw]."""
    stamps, values = [], []
    with open(path) as f:
        for raw in f:
            line = raw.replace(",", " ").replace("\t", " ").strip()
            if not line or line.startswith("#"):
                continue
            numbers = [float(v) for v in line.split()]
            if len(numbers) != 8:
                raise ValueError(f"{path}: expected 8 numbers per line: {raw!r}")
            stamps.append(numbers[0])
            values.append(numbers[1:])
    if any(b <= a for a, b in zip(stamps, stamps[1:])):
        raise ValueError(f"{path}: timestamps must increase")
    return stamps, values


def associate(stamps_gt, stamps_est, offset, max_diff):
    """Greedy matching: every candidate (gt, est) closer than max_diff, smallest
    difference first (ties: smaller gt stamp, then smaller est stamp), each
    stamp used at most once. Returns [(gt_row, est_row)] sorted by time."""
    candidates = []
    for i, a in enumerate(stamps_gt):
        for j, b in enumerate(stamps_est):
            d = abs(a - (b + offset))
            if d < max_diff:
                candidates.append((d, a, b, i, j))
    candidates.sort()
    gt_used, est_used = set(), set()
    matches = []
    for _, _, _, i, j in candidates:
        if i in gt_used or j in est_used:
            continue
        gt_used.add(i)
        est_used.add(j)
        matches.append((i, j))
    matches.sort()
    return matches


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("gt")
    parser.add_argument("est")
    parser.add_argument("--offset", type=float, default=0.0)
    parser.add_argument("--max-diff", type=float, default=0.02)
    args = parser.parse_args(argv)
    stamps_gt, _ = read_trajectory(args.gt)
    stamps_est, _ = read_trajectory(args.est)
    matches = associate(stamps_gt, stamps_est, args.offset, args.max_diff)
    print(json.dumps({"pairs": len(matches), "matches": [list(m) for m in matches]}))


if __name__ == "__main__":
    sys.exit(main())
