#!/usr/bin/python3
"""Where does a trajectory's error come from? Rigid and Sim(3) alignment of an
estimate to ground truth (TUM files, poses matched by timestamp), the error
per block of frames, path lengths, and the rotation angle per window of
frames for both (a systematic under- or over-estimate of rotation shows up
there). Used for docs/slam-core.md.

usage: scripts/trajectory_segments.py GT EST [--block 50] [--window 30]
"""
import argparse

import numpy as np


def load(path):
    poses = {}
    for line in open(path):
        if line.startswith('#') or not line.strip():
            continue
        v = [float(x) for x in line.split()]
        poses[round(v[0], 4)] = np.array(v[1:8])
    return poses


def rotation(q):
    x, y, z, w = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def align(est, gt, with_scale):
    """s, R, t minimising |gt - (s R est + t)| (Umeyama)."""
    me, mg = est.mean(0), gt.mean(0)
    u, d, vt = np.linalg.svd((gt - mg).T @ (est - me))
    s_fix = np.eye(3)
    s_fix[2, 2] = np.sign(np.linalg.det(u @ vt))
    r = u @ s_fix @ vt
    s = (d * np.diag(s_fix)).sum() / ((est - me) ** 2).sum() if with_scale else 1.0
    return s, r, mg - s * r @ me


def angle_deg(ra, rb):
    return np.degrees(np.arccos(np.clip((np.trace(ra.T @ rb) - 1) / 2, -1, 1)))


def main():
    p = argparse.ArgumentParser()
    p.add_argument('gt')
    p.add_argument('est')
    p.add_argument('--block', type=int, default=50, help='frames per error block')
    p.add_argument('--window', type=int, default=30, help='frames per rotation window')
    a = p.parse_args()
    gt, est = load(a.gt), load(a.est)
    ts = sorted(set(gt) & set(est))
    g = np.array([gt[t][:3] for t in ts])
    e = np.array([est[t][:3] for t in ts])
    s, r, t = align(e, g, False)
    err = np.linalg.norm(g - (e @ r.T + t), axis=1)
    print('poses %d, ATE rigid %.4f m' % (len(ts), np.sqrt((err ** 2).mean())))
    s2, r2, t2 = align(e, g, True)
    err2 = np.linalg.norm(g - (s2 * e @ r2.T + t2), axis=1)
    print('ATE Sim(3) %.4f m, scale %.4f' % (np.sqrt((err2 ** 2).mean()), s2))
    for b in range(0, len(ts), a.block):
        blk = slice(b, min(len(ts), b + a.block))
        print('frames %4d-%4d: error mean %.4f max %.4f m; path gt %.3f est %.3f m' % (
            b, blk.stop - 1, err[blk].mean(), err[blk].max(),
            np.linalg.norm(np.diff(g[blk], axis=0), axis=1).sum(),
            np.linalg.norm(np.diff(e[blk], axis=0), axis=1).sum()))
    rg = [rotation(gt[t][3:]) for t in ts]
    re = [rotation(est[t][3:]) for t in ts]
    w = a.window
    ang_g = [angle_deg(rg[i], rg[i + w]) for i in range(0, len(ts) - w, w)]
    ang_e = [angle_deg(re[i], re[i + w]) for i in range(0, len(ts) - w, w)]
    print('rotation per %d frames: gt %.2f deg, est %.2f deg (ratio %.3f)' % (
        w, np.mean(ang_g), np.mean(ang_e), np.sum(ang_e) / np.sum(ang_g)))


if __name__ == '__main__':
    main()
