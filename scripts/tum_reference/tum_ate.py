#!/usr/bin/python3
"""Reference: absolute trajectory error as the TUM RGB-D benchmark computes it.

  tum_ate.py GT EST [--offset 0] [--max-diff 0.02] [--scale 1] [--alignment]
prints {"pairs": N, "rmse": .., "mean": .., "median": .., "std": .., "min": .., "max": ..}
(--alignment adds "rotation" (3x3, rows) and "translation" of gt_from_est).
"""
import argparse
import json
import sys

import numpy as np

from tum_associate import associate, read_trajectory


def horn_alignment(est, gt):
    """Rotation R and translation t minimising sum ||R est_i + t - gt_i||^2
    (closed form via SVD; est, gt are 3xN)."""
    est_mean = est.mean(axis=1, keepdims=True)
    gt_mean = gt.mean(axis=1, keepdims=True)
    est_c = est - est_mean
    gt_c = gt - gt_mean
    w = np.zeros((3, 3))
    for k in range(est.shape[1]):
        w += np.outer(est_c[:, k], gt_c[:, k])
    u, _, vt = np.linalg.svd(w.T)
    s = np.identity(3)
    if np.linalg.det(u) * np.linalg.det(vt) < 0:
        s[2, 2] = -1
    r = u @ s @ vt
    t = gt_mean - r @ est_mean
    return r, t.reshape(3)


def error_stats(e):
    e = np.asarray(e, dtype=np.float64)
    return {
        "rmse": float(np.sqrt(np.dot(e, e) / len(e))),
        "mean": float(np.mean(e)),
        "median": float(np.median(e)),
        "std": float(np.std(e)),
        "min": float(np.min(e)),
        "max": float(np.max(e)),
    }


def ate(gt_path, est_path, offset=0.0, max_diff=0.02, scale=1.0):
    stamps_gt, values_gt = read_trajectory(gt_path)
    stamps_est, values_est = read_trajectory(est_path)
    matches = associate(stamps_gt, stamps_est, offset, max_diff)
    if len(matches) < 2:
        raise RuntimeError("no overlap in time between GT and EST")
    gt = np.array([values_gt[i][0:3] for i, _ in matches]).T
    est = np.array([[v * scale for v in values_est[j][0:3]] for _, j in matches]).T
    r, t = horn_alignment(est, gt)
    residual = r @ est + t.reshape(3, 1) - gt
    errors = np.sqrt(np.sum(residual * residual, axis=0))
    result = {"pairs": len(matches)}
    result.update(error_stats(errors))
    return result, r, t


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("gt")
    parser.add_argument("est")
    parser.add_argument("--offset", type=float, default=0.0)
    parser.add_argument("--max-diff", type=float, default=0.02)
    parser.add_argument("--scale", type=float, default=1.0)
    parser.add_argument("--alignment", action="store_true")
    args = parser.parse_args(argv)
    result, r, t = ate(args.gt, args.est, args.offset, args.max_diff, args.scale)
    if args.alignment:
        result["rotation"] = r.tolist()
        result["translation"] = t.tolist()
    print(json.dumps(result))


if __name__ == "__main__":
    sys.exit(main())
