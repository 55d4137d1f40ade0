#!/usr/bin/python3
"""Writes the evaluation fixtures: tests/fixtures/eval/<case>/{gt.txt,est.txt}
and the reference results expected_*.json computed by scripts/tum_reference.

Deterministic (seeded). Run from anywhere:
  /usr/bin/python3 scripts/make_eval_fixtures.py
The trajectories imitate a TUM recording: motion-capture ground truth at
100 Hz with slight timestamp jitter, a 30 Hz estimate with frame jitter, drift,
noise, dropped frames and quaternion sign flips, expressed in a different world
frame (so the alignment matters), some with a clock offset or a wrong scale.
"""
import json
import os
import shutil
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "tum_reference"))
from tum_associate import associate, read_trajectory  # noqa: E402
from tum_ate import ate  # noqa: E402
from tum_rpe import rpe  # noqa: E402

OUT = os.path.join(HERE, "..", "tests", "fixtures", "eval")


def hat(w):
    return np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


def exp_so3(w):
    theta = np.linalg.norm(w)
    if theta < 1e-12:
        return np.identity(3) + hat(w)
    k = hat(np.asarray(w) / theta)
    return np.identity(3) + np.sin(theta) * k + (1 - np.cos(theta)) * k @ k


def quaternion(r):
    """[qx qy qz qw] of a rotation matrix (qw >= 0)."""
    w = np.sqrt(max(0.0, 1 + np.trace(r))) / 2
    x = np.sqrt(max(0.0, 1 + r[0, 0] - r[1, 1] - r[2, 2])) / 2
    y = np.sqrt(max(0.0, 1 - r[0, 0] + r[1, 1] - r[2, 2])) / 2
    z = np.sqrt(max(0.0, 1 - r[0, 0] - r[1, 1] + r[2, 2])) / 2
    x = np.copysign(x, r[2, 1] - r[1, 2])
    y = np.copysign(y, r[0, 2] - r[2, 0])
    z = np.copysign(z, r[1, 0] - r[0, 1])
    q = np.array([x, y, z, w])
    return q / np.linalg.norm(q)


def handheld_motion(t):
    """World_from_cam of a person walking a camera around a room (up to ~50 deg)."""
    p = np.array([1.2 * np.sin(0.21 * t + 0.3) + 0.25 * np.sin(0.93 * t),
                  0.9 * np.sin(0.17 * t + 1.1) + 0.15 * np.sin(1.3 * t + 0.4),
                  1.4 + 0.12 * np.sin(0.5 * t + 2.0)])
    w = np.array([0.35 * np.sin(0.31 * t), 0.25 * np.sin(0.23 * t + 1.0),
                  0.85 * np.sin(0.11 * t + 2.0)])
    return exp_so3([-np.pi / 2, 0, 0]) @ exp_so3(w), p


def spinning_motion(t):
    """Mostly rotating in place with bursts of translation: m, rad and f pick
    different pose pairs."""
    yaw = 0.45 * t + 0.35 * np.sin(0.9 * t)
    pitch = 0.3 * np.sin(0.7 * t + 0.5)
    burst = 0.5 * (1 - np.cos(np.pi * np.clip((t - 3.0) / 3.0, 0.0, 1.0)))
    p = np.array([0.8 * burst + 0.05 * np.sin(1.7 * t), 0.4 * burst * burst, 1.3 + 0.03 * np.sin(t)])
    return exp_so3([-np.pi / 2, 0, 0]) @ exp_so3([0, yaw, 0]) @ exp_so3([pitch, 0, 0]), p


def write(path, stamps, rotations, positions, decimals, rng=None):
    with open(path, "w") as f:
        f.write("# timestamp tx ty tz qx qy qz qw\n")
        for t, r, p in zip(stamps, rotations, positions):
            q = quaternion(r)
            if rng is not None and rng.random() < 0.3:
                q = -q  # q and -q are the same rotation; writers differ
            values = " ".join(f"{v:.{decimals}f}" for v in list(p) + list(q))
            f.write(f"{t:.6f} {values}\n")


def make_case(name, seed, motion, duration, t0, gt_gaps=(), est_offset=0.0, est_scale=1.0,
              gt_step=0.01, est_span=(0.5, 0.7)):
    """est_span: the estimate starts est_span[0] s after the ground truth and ends
    est_span[1] s after it (negative: before, so RPE's last-pose rule matters)."""
    rng = np.random.default_rng(seed)
    # Ground truth: motion capture on its own clock.
    n_gt = int(duration / gt_step)
    gt_t = np.arange(n_gt) * gt_step + rng.uniform(-3e-4, 3e-4, n_gt)
    keep = np.ones(n_gt, dtype=bool)
    for a, b in gt_gaps:
        keep &= ~((gt_t >= a) & (gt_t < b))
    gt_t = gt_t[keep]
    gt_r, gt_p = [], []
    for t in gt_t:
        r, p = motion(t)
        gt_r.append(r)
        gt_p.append(p + rng.normal(0, 3e-4, 3))
    # Estimate: 30 Hz camera, starting late.
    cam_t = np.arange(est_span[0], duration + est_span[1], 1 / 30.0)
    cam_t = cam_t + rng.uniform(-2e-3, 2e-3, len(cam_t))
    keep = rng.random(len(cam_t)) > 0.05
    lost = rng.uniform(0.3, 0.7) * duration
    keep &= ~((cam_t > lost) & (cam_t < lost + 0.6))
    cam_t = cam_t[keep]
    world_a = exp_so3([0.3, -0.5, 1.9])  # est world in gt world: ~115 deg
    world_a_t = np.array([2.0, -1.0, 0.5])
    drift_v = rng.normal(0, 0.004, 3)  # m/s
    drift_w = rng.normal(0, np.radians(0.15), 3)  # rad/s
    est_r, est_p = [], []
    for t in cam_t:
        r, p = motion(t)
        r = r @ exp_so3(rng.normal(0, np.radians(0.25), 3))
        p = p + rng.normal(0, 0.004, 3)
        d_r = exp_so3(drift_w * (t - 0.5))
        r, p = d_r @ r, d_r @ p + drift_v * (t - 0.5)
        est_r.append(world_a.T @ r)
        est_p.append(world_a.T @ (p - world_a_t) / est_scale)
    case_dir = os.path.join(OUT, name)
    os.makedirs(case_dir, exist_ok=True)
    write(os.path.join(case_dir, "gt.txt"), t0 + gt_t, gt_r, gt_p, 4)
    write(os.path.join(case_dir, "est.txt"), t0 + cam_t - est_offset, est_r, est_p, 6, rng)
    return case_dir


def expect(case_dir, file_name, kind, **params):
    gt = os.path.join(case_dir, "gt.txt")
    est = os.path.join(case_dir, "est.txt")
    if kind == "associate":
        stamps_gt, _ = read_trajectory(gt)
        stamps_est, _ = read_trajectory(est)
        m = associate(stamps_gt, stamps_est, params["offset"], params["max_diff"])
        result = {"pairs": len(m), "matches": [list(x) for x in m]}
        tool = "tum_associate.py"
    elif kind == "ate":
        result, r, t = ate(gt, est, params["offset"], params["max_diff"], params["scale"])
        result["rotation"] = r.tolist()
        result["translation"] = t.tolist()
        tool = "tum_ate.py --alignment"
    else:
        result = rpe(gt, est, params["delta"], params["delta_unit"], params["offset"],
                     params["scale"])
        tool = "tum_rpe.py"
    flags = " ".join(f"--{k.replace('_', '-')} {v}" for k, v in params.items())
    doc = {"command": f"scripts/tum_reference/{tool} gt.txt est.txt {flags}", "kind": kind,
           "params": params, "result": result}
    with open(os.path.join(case_dir, file_name), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


def expect_all(case_dir, offset=0.0, scale=1.0, units=(("s", "s", 1.0), ("f", "f", 10.0))):
    expect(case_dir, "expected_associate.json", "associate", max_diff=0.02, offset=offset)
    expect(case_dir, "expected_ate.json", "ate", max_diff=0.02, offset=offset, scale=scale)
    for label, unit, delta in units:
        expect(case_dir, f"expected_rpe_{label}.json", "rpe", delta=delta, delta_unit=unit,
               offset=offset, scale=scale)


def main():
    if os.path.isdir(OUT):
        shutil.rmtree(OUT)
    # Handheld, realistic TUM timestamps, estimate in another world frame.
    d = make_case("handheld", 1, handheld_motion, 24.0, 1305031102.175304)
    expect_all(d, units=(("s", "s", 1.0), ("s_short", "s", 0.1), ("m", "m", 0.5),
                         ("f", "f", 10.0)))
    # Clock offset between estimate and ground truth: with and without --offset.
    d = make_case("offset", 2, handheld_motion, 8.0, 1341846313.592026, est_offset=0.35,
                  est_span=(0.5, -0.5))
    expect_all(d, offset=0.35)
    expect(d, "expected_ate_no_offset.json", "ate", max_diff=0.02, offset=0.0, scale=1.0)
    expect(d, "expected_rpe_s_no_offset.json", "rpe", delta=1.0, delta_unit="s", offset=0.0,
           scale=1.0)
    # Monocular-like estimate at 1/2.5 of the true scale.
    d = make_case("scale", 3, handheld_motion, 8.0, 1311868164.363181, est_scale=2.5,
                  est_span=(0.5, -0.5))
    expect_all(d, scale=2.5)
    expect(d, "expected_ate_unscaled.json", "ate", max_diff=0.02, offset=0.0, scale=1.0)
    # Rotation-heavy: every delta unit picks different pairs; f with a half
    # delta exercises the tie-breaking of the closest-index search.
    d = make_case("spin", 4, spinning_motion, 10.0, 1000.0, est_span=(0.3, -0.3))
    expect_all(d, units=(("s", "s", 1.0), ("m", "m", 0.2), ("rad", "rad", 0.5),
                         ("deg", "deg", 20.0), ("f", "f", 10.0), ("f_half", "f", 2.5)))
    # Motion-capture dropouts: unmatched frames and RPE pairs without ground truth.
    d = make_case("gaps", 5, handheld_motion, 8.0, 1305031910.765238,
                  gt_gaps=((1.2, 1.9), (3.0, 3.3), (5.5, 6.6)))
    expect_all(d, units=(("s", "s", 1.0), ("deg", "deg", 10.0), ("f", "f", 5.0)))
    total = sum(os.path.getsize(os.path.join(r, f)) for r, _, fs in os.walk(OUT) for f in fs)
    print(f"wrote {OUT} ({total / 1024:.0f} KiB)")


if __name__ == "__main__":
    main()
