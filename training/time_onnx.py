#!/usr/bin/env python3
"""Time several ONNX models in cv2.dnn round-robin (one forward of each in turn), so that all of them see
the same background load on a shared machine. Per frame: blobFromImage from a 640x480 BGR frame + forward.
Reports wall time and the process's CPU time per frame; with --threads 1 the CPU time is the network's whole
compute and moves much less with the load of other jobs than the wall time does.

  /usr/bin/python3 training/time_onnx.py models/a.onnx:257x337 teacher.onnx:385x513 [--runs 40]"""
import argparse
import os
import time

import cv2
import numpy as np


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('models', nargs='+', help='PATH:HxW')
    ap.add_argument('--runs', type=int, default=40)
    ap.add_argument('--threads', type=int, default=2)
    args = ap.parse_args()
    cv2.setNumThreads(args.threads)
    nets = []
    for spec in args.models:
        path, size = spec.rsplit(':', 1)
        h, w = (int(v) for v in size.split('x'))
        nets.append((os.path.basename(path), cv2.dnn.readNetFromONNX(path), h, w, [], []))
    frame = (np.random.default_rng(0).random((480, 640, 3)) * 255).astype(np.uint8)
    loads = []
    for i in range(args.runs + 3):
        for name, net, h, w, times, cpu_times in nets:
            t0, c0 = time.perf_counter(), time.process_time()
            net.setInput(cv2.dnn.blobFromImage(frame, 1 / 128.0, (w, h), (128, 128, 128), swapRB=True))
            net.forward()
            if i >= 3:
                times.append(1e3 * (time.perf_counter() - t0))
                cpu_times.append(1e3 * (time.process_time() - c0))
        loads.append(os.getloadavg()[0])
    for name, _, h, w, times, cpu_times in nets:
        print(f'{name} {h}x{w}: wall median {np.median(times):.1f} ms, min {np.min(times):.1f} ms, '
              f'p25 {np.percentile(times, 25):.1f} ms; CPU median {np.median(cpu_times):.1f} ms, '
              f'min {np.min(cpu_times):.1f} ms ({args.runs} runs, {args.threads} threads)')
    print(f'load average during the runs: {min(loads):.1f} .. {max(loads):.1f}')


if __name__ == '__main__':
    main()
