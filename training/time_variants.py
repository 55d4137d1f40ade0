#!/usr/bin/env python3
"""Export untrained variants and time cv2.dnn forward (architecture speed only; weights do not matter).

  nice -n 19 /usr/bin/python3 training/time_variants.py [--presets mnv2_w05 ...] [--runs 30]
"""
import argparse
import os
import sys
import tempfile
import time

import cv2
import numpy as np
import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from export_onnx import export  # noqa: E402
from model import build_model  # noqa: E402
from model.layers import count_parameters  # noqa: E402


def time_net(onnx_path, h, w, runs, threads=2):
    cv2.setNumThreads(threads)
    net = cv2.dnn.readNetFromONNX(onnx_path)
    img = (np.random.default_rng(0).random((480, 640, 3)) * 255).astype(np.uint8)
    ts = []
    for i in range(runs + 3):
        t0 = time.perf_counter()
        net.setInput(cv2.dnn.blobFromImage(img, 1 / 128., (w, h), (128, 128, 128), swapRB=True))
        net.forward()
        if i >= 3:
            ts.append(time.perf_counter() - t0)
    return 1e3 * np.median(ts), 1e3 * np.min(ts)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--presets', nargs='+', default=['mnv2_w05', 'mnv2_w10'])
    ap.add_argument('--aspp', nargs='+', default=['improved', 'original'])
    ap.add_argument('--size', type=int, nargs=2, default=(257, 337))
    ap.add_argument('--runs', type=int, default=20)
    ap.add_argument('--override', nargs='*', default=[], help='key=int, e.g. decoder_channels=96')
    args = ap.parse_args()
    over = {k: int(v) for k, v in (o.split('=') for o in args.override)}
    h, w = args.size
    with tempfile.TemporaryDirectory() as tmp:
        for preset in args.presets:
            for aspp in args.aspp:
                model = build_model(preset, aspp=aspp, **over).eval()
                path = os.path.join(tmp, 'm.onnx')
                export(model, path, h, w)
                med, best = time_net(path, h, w, args.runs)
                print(f'{preset} aspp={aspp} {over} {h}x{w}: params {count_parameters(model) / 1e6:.3f} M, '
                      f'cv2.dnn median {med:.1f} ms, min {best:.1f} ms (2 threads)', flush=True)


if __name__ == '__main__':
    main()
