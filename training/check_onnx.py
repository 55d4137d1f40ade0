#!/usr/bin/env python3
"""Load an exported ONNX with cv2.dnn, compare its logits with the PyTorch checkpoint on real validation
images (max |diff| must be < 1e-3), and time blobFromImage + forward at the model's input size.

  /usr/bin/python3 training/check_onnx.py --checkpoint training/checkpoints/mnv2_w05.pt --onnx models/x.onnx [--size H W]
Exit code 1 if the difference bound fails."""
import argparse
import os
import sys
import time

import cv2
import numpy as np
import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from datasets import SHARED_DATA  # noqa: E402
from datasets.splits import read_split  # noqa: E402
from export_onnx import load_checkpoint_model  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--checkpoint', required=True)
    ap.add_argument('--onnx', required=True)
    ap.add_argument('--images', type=int, default=12, help='validation images to compare on')
    ap.add_argument('--runs', type=int, default=30, help='timed forward passes')
    ap.add_argument('--threads', type=int, default=2)
    ap.add_argument('--tolerance', type=float, default=1e-3)
    ap.add_argument('--size', type=int, nargs=2, metavar=('H', 'W'),
                    help="the ONNX model's input size; default: the checkpoint's training input size")
    args = ap.parse_args()
    torch.set_num_threads(args.threads)
    cv2.setNumThreads(args.threads)
    model, ck = load_checkpoint_model(args.checkpoint)
    h, w = args.size or ck['model_config']['input_hw']
    net = cv2.dnn.readNetFromONNX(args.onnx)
    rows = [r for r in read_split('val') if r[0] != 'kitchen']
    rows = rows[::max(1, len(rows) // args.images)][:args.images]
    worst, agree = 0.0, []
    for _, image_rel, _ in rows:
        bgr = cv2.imread(os.path.join(SHARED_DATA, image_rel), cv2.IMREAD_COLOR)
        blob = cv2.dnn.blobFromImage(bgr, 1 / 128.0, (w, h), (128, 128, 128), swapRB=True)
        net.setInput(blob)
        out = net.forward()
        with torch.no_grad():
            ref = model(torch.from_numpy(blob)).numpy()
        worst = max(worst, float(np.abs(out - ref).max()))
        agree.append(float((out.argmax(1) == ref.argmax(1)).mean()))
    print(f'{len(rows)} validation images: cv2.dnn vs PyTorch max |logit diff| {worst:.2e}, '
          f'argmax agreement {np.mean(agree) * 100:.3f} %')
    bgr = cv2.imread(os.path.join(SHARED_DATA, rows[0][1]), cv2.IMREAD_COLOR)
    bgr = cv2.resize(bgr, (640, 480))
    times = []
    for i in range(args.runs + 3):
        t0 = time.perf_counter()
        net.setInput(cv2.dnn.blobFromImage(bgr, 1 / 128.0, (w, h), (128, 128, 128), swapRB=True))
        net.forward()
        if i >= 3:
            times.append(1e3 * (time.perf_counter() - t0))
    load = os.getloadavg()[0]
    print(f'cv2.dnn {h}x{w}, {args.threads} threads, 640x480 frame, blobFromImage + forward: median '
          f'{np.median(times):.1f} ms, min {np.min(times):.1f} ms over {args.runs} runs (load average {load:.1f})')
    if not worst < args.tolerance:
        print(f'FAIL: max |diff| {worst:.2e} >= {args.tolerance}')
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
