#!/usr/bin/env python3
"""Evaluate on the validation split: our checkpoints (PyTorch) or ONNX models through cv2.dnn (ours or the
VOC teachers, whose 21 classes are mapped to ours by config/classes.json).

  /usr/bin/python3 training/evaluate.py --checkpoint training/checkpoints/mnv2_w05.pt
  /usr/bin/python3 training/evaluate.py --onnx models/x.onnx --size 257 337
  /usr/bin/python3 training/evaluate.py --onnx ../shared/data/models/deeplabv3-mnv2-voc/deeplabv3_mnv2_voc_385x513.onnx --voc --size 385 513
  /usr/bin/python3 training/evaluate.py --onnx models/x.onnx --size 209 273 --sequence k5 --every 5
      # person IoU on a sequence with ground-truth masks (mask.txt: dlslam composite or dlslam synth output)
"""
import argparse
import json
import os
import sys
import time

import cv2
import numpy as np
import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from datasets import load_classes  # noqa: E402
from datasets.seg_dataset import EvalDataset, to_tensor  # noqa: E402
from datasets.splits import read_split  # noqa: E402
from metrics import SegEvaluator, selection_score  # noqa: E402


def run_eval(predict, rows, input_hw, class_names, log_every=0):
    """predict(x 1x3xHxW tensor) -> HxW int label map at the input size."""
    ds = EvalDataset(rows, input_hw)
    ev = SegEvaluator(class_names)
    t0 = time.time()
    for i in range(len(ds)):
        x, label, source, _ = ds[i]
        pred = predict(x[None]).astype(np.uint8)
        pred = cv2.resize(pred, (label.shape[1], label.shape[0]), interpolation=cv2.INTER_NEAREST)
        ev.add(source, pred, label, has_person_gt=source != 'kitchen')
        if log_every and (i + 1) % log_every == 0:
            print(f'  eval {i + 1}/{len(ds)} {time.time() - t0:.0f} s', flush=True)
    s = ev.summary()
    s['score'] = selection_score(s)
    return s


def read_list(path):
    """TUM-style list file -> [(timestamp, relative path)]; blank and '#' lines skipped. Exits naming file:line
    for a missing file or a malformed line."""
    try:
        with open(path) as f:
            lines = f.readlines()
    except OSError as e:
        raise SystemExit(f'{path}: cannot read: {e.strerror}')
    rows = []
    for number, line in enumerate(lines, 1):
        fields = line.split()
        if not fields or line.startswith('#'):
            continue
        try:
            if len(fields) < 2:
                raise ValueError
            rows.append((float(fields[0]), fields[1]))
        except ValueError:
            raise SystemExit(f'{path}:{number}: expected "timestamp path", got {line.strip()[:60]!r}')
    return rows


def run_sequence_eval(predict, seq, input_hw, every):
    """Person IoU (pooled and mean over frames with at least 1 % person) of a sequence whose mask.txt lists
    ground-truth masks (non-zero = a moving person or object) beside rgb.txt, matched by timestamp."""
    rgb, masks = read_list(os.path.join(seq, 'rgb.txt')), read_list(os.path.join(seq, 'mask.txt'))
    by_time = {round(t, 6): m for t, m in masks}
    inter = union = false_pos = pixels = 0
    per_frame = []
    frames = 0
    for t, rel in rgb[::every]:
        if round(t, 6) not in by_time:
            continue   # a frame without a mask: not evaluated
        img = cv2.imread(os.path.join(seq, rel), cv2.IMREAD_COLOR)
        gt = cv2.imread(os.path.join(seq, by_time[round(t, 6)]), cv2.IMREAD_UNCHANGED)
        for name, loaded in ((rel, img), (by_time[round(t, 6)], gt)):
            if loaded is None:
                raise SystemExit(f'{os.path.join(seq, name)}: cannot be read as an image')
        frames += 1
        x = to_tensor(cv2.resize(img, (input_hw[1], input_hw[0]), interpolation=cv2.INTER_LINEAR))
        pred = cv2.resize(predict(x[None]).astype(np.uint8), (img.shape[1], img.shape[0]),
                          interpolation=cv2.INTER_NEAREST) == 1
        gt = gt > 0
        i, u = int((pred & gt).sum()), int((pred | gt).sum())
        inter, union = inter + i, union + u
        false_pos, pixels = false_pos + int((pred & ~gt).sum()), pixels + gt.size
        if gt.mean() >= 0.01:
            per_frame.append(i / u)
    if frames == 0:
        raise SystemExit(f'{seq}: no frame of rgb.txt has a mask in mask.txt (timestamps must match)')
    return {'frames': frames, 'person_iou_pooled': inter / max(union, 1),
            'person_iou_mean': float(np.mean(per_frame)) if per_frame else float('nan'),
            'false_positive_share': false_pos / max(pixels, 1)}


def torch_predictor(model):
    def predict(x):
        with torch.no_grad():
            return model(x)[0].argmax(0).numpy()
    return predict


def voc_to_ours(classes):
    lut = np.zeros(256, np.uint8)
    for c in classes:
        for v in c['voc_ids']:
            lut[v] = c['id']
    return lut


def onnx_predictor(path, voc, classes, threads=2):
    cv2.setNumThreads(threads)
    net = cv2.dnn.readNetFromONNX(path)
    lut = voc_to_ours(classes) if voc else None

    def predict(x):
        net.setInput(x.numpy())   # same (x - 128) / 128 RGB blob as blobFromImage(bgr, 1/128, size, 128, swapRB)
        pred = net.forward()[0].argmax(0).astype(np.uint8)
        return lut[pred] if voc else pred
    return predict


def format_summary(s):
    lines = [f"score {s['score']:.4f}  mIoU {s['all']['mIoU']:.4f}  " +
             '  '.join(f'{k} {v:.4f}' for k, v in s['all'].items() if k.startswith('IoU_'))]
    for src, d in s.items():
        if src in ('all', 'score'):
            continue
        lines.append(f'  {src}: ' + '  '.join(f'{k} {v:.4f}' if isinstance(v, float) else f'{k} {v}'
                                               for k, v in d.items()))
    return '\n'.join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--checkpoint')
    ap.add_argument('--onnx')
    ap.add_argument('--voc', action='store_true', help='the ONNX model outputs the 21 VOC classes (teachers)')
    ap.add_argument('--size', type=int, nargs=2, default=(257, 337), metavar=('H', 'W'))
    ap.add_argument('--split', default='val')
    ap.add_argument('--sequence', help='instead of the split: a sequence folder with mask.txt (ground-truth masks)')
    ap.add_argument('--every', type=int, default=1, help='with --sequence: every k-th frame')
    ap.add_argument('--json', help='also write the summary here')
    args = ap.parse_args()
    torch.set_num_threads(2)
    classes = load_classes()
    names = [c['name'] for c in classes]
    if args.checkpoint:
        from export_onnx import load_checkpoint_model
        predict = torch_predictor(load_checkpoint_model(args.checkpoint)[0])
    elif args.onnx:
        predict = onnx_predictor(args.onnx, args.voc, classes)
    else:
        ap.error('give --checkpoint or --onnx')
    if args.sequence:
        s = run_sequence_eval(predict, args.sequence, tuple(args.size), max(1, args.every))
        print(f"{args.sequence}: " + '  '.join(f'{k} {v:.4f}' if isinstance(v, float) else f'{k} {v}'
                                            for k, v in s.items()))
    else:
        s = run_eval(predict, read_split(args.split), tuple(args.size), names, log_every=100)
        print(format_summary(s))
    if args.json:
        with open(args.json, 'w') as f:
            json.dump(s, f, indent=1)


if __name__ == '__main__':
    main()
