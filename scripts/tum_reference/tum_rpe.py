#!/usr/bin/python3
"""Reference: relative pose error with a fixed delta, as the TUM RGB-D
benchmark computes it (its --fixed_delta mode), using every pair (no random
sub-sampling).

  tum_rpe.py GT EST [--delta 1] [--delta-unit s|m|rad|deg|f] [--offset 0] [--scale 1]
prints {"pairs": N, "translation": {rmse mean median std min max},
        "rotation_deg": {rmse mean median std min max}}
"""
import argparse
import json
import sys

import numpy as np

from tum_associate import read_trajectory
from tum_ate import error_stats


def pose_matrix(v):
    """4x4 matrix of [tx ty tz qx qy qz qw]; the quaternion is normalised."""
    x, y, z, w = np.array(v[3:7], dtype=np.float64) / np.linalg.norm(v[3:7])
    m = np.identity(4)
    m[0:3, 0:3] = [
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ]
    m[0:3, 3] = v[0:3]
    return m


def relative(a, b):
    """inv(a) * b."""
    return np.linalg.inv(a) @ b


def translation_norm(m):
    return float(np.linalg.norm(m[0:3, 3]))


def rotation_angle(m):
    c = (np.trace(m[0:3, 0:3]) - 1.0) / 2.0
    return float(np.arccos(min(1.0, max(-1.0, c))))


def closest_index(values, target):
    """Binary search that keeps the closest of the probed elements."""
    lo, hi = 0, len(values)
    best, best_diff = 0, abs(values[0] - target)
    while lo < hi:
        mid = (lo + hi) // 2
        d = abs(values[mid] - target)
        if d < best_diff:
            best, best_diff = mid, d
        if values[mid] == target:
            return mid
        if values[mid] > target:
            hi = mid
        else:
            lo = mid + 1
    return best


def cumulative(poses, step):
    out = [0.0]
    for k in range(len(poses) - 1):
        out.append(out[-1] + step(relative(poses[k + 1], poses[k])))
    return out


def rpe(gt_path, est_path, delta=1.0, unit="s", offset=0.0, scale=1.0):
    stamps_gt, values_gt = read_trajectory(gt_path)
    stamps_est, values_est = read_trajectory(est_path)
    gt = [pose_matrix(v) for v in values_gt]
    est = [pose_matrix(v) for v in values_est]
    n = len(stamps_est)

    overlap = set()
    for t in stamps_est:
        t_gt = stamps_gt[closest_index(stamps_gt, t + offset)]
        overlap.add(closest_index(stamps_est, t_gt - offset))
    if len(overlap) < 2:
        raise RuntimeError("no overlap in time between GT and EST")

    if unit == "s":
        index = list(stamps_est)
    elif unit == "f":
        index = list(range(n))
    elif unit == "m":
        index = cumulative(est, translation_norm)
    elif unit == "rad":
        index = cumulative(est, rotation_angle)
    elif unit == "deg":
        index = cumulative(est, lambda m: rotation_angle(m) * 180.0 / np.pi)
    else:
        raise ValueError(f"unknown delta unit {unit!r}")

    pairs = []
    for i in range(n):
        j = closest_index(index, index[i] + delta)
        if j != n - 1:
            pairs.append((i, j))

    gt_steps = [b - a for a, b in zip(stamps_gt, stamps_gt[1:])]
    max_gap = 2 * float(np.median(gt_steps))

    trans, rot = [], []
    for i, j in pairs:
        gi = closest_index(stamps_gt, stamps_est[i] + offset)
        gj = closest_index(stamps_gt, stamps_est[j] + offset)
        if (abs(stamps_gt[gi] - (stamps_est[i] + offset)) > max_gap or
                abs(stamps_gt[gj] - (stamps_est[j] + offset)) > max_gap):
            continue
        est_motion = relative(est[j], est[i])
        est_motion[0:3, 3] *= scale
        error = relative(est_motion, relative(gt[gj], gt[gi]))
        trans.append(translation_norm(error))
        rot.append(rotation_angle(error))
    if len(trans) < 2:
        raise RuntimeError("fewer than 2 pose pairs with ground truth")

    rot_stats = error_stats(rot)
    return {
        "pairs": len(trans),
        "translation": error_stats(trans),
        # Statistics on radians, then converted (the order the TUM tool uses).
        "rotation_deg": {k: v * 180.0 / np.pi for k, v in rot_stats.items()},
    }


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("gt")
    parser.add_argument("est")
    parser.add_argument("--delta", type=float, default=1.0)
    parser.add_argument("--delta-unit", default="s", choices=["s", "m", "rad", "deg", "f"])
    parser.add_argument("--offset", type=float, default=0.0)
    parser.add_argument("--scale", type=float, default=1.0)
    args = parser.parse_args(argv)
    print(json.dumps(rpe(args.gt, args.est, args.delta, args.delta_unit, args.offset, args.scale)))


if __name__ == "__main__":
    sys.exit(main())
