#!/usr/bin/env python3
"""Save a few augmented training samples as overlays (label colours + teacher person probability) to eyeball
that images, masks and teacher targets line up.
  /usr/bin/python3 training/datasets/preview.py OUT_DIR [N] [MIX] [--extended-aug]
MIX as train.py --mix (e.g. crowd=1 for crowd samples only)."""
import os
import sys

import cv2
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from datasets.seg_dataset import TrainDataset, parse_mix  # noqa: E402
from datasets.splits import read_split  # noqa: E402
from datasets.teacher_cache import cache_path  # noqa: E402

COLOURS = np.array([[0, 0, 0], [0, 0, 255], [0, 255, 0]] + [[128, 128, 128]] * 252 + [[255, 0, 255]], np.uint8)


def main():
    args = [a for a in sys.argv[1:] if not a.startswith('--')]
    out, n = args[0], int(args[1]) if len(args) > 1 else 12
    mix = parse_mix(args[2]) if len(args) > 2 else None
    os.makedirs(out, exist_ok=True)
    rows = [r for r in read_split('train') if os.path.exists(cache_path(r[1]))]
    ds = TrainDataset(rows, seed=1, mix=mix, extended_photometric='--extended-aug' in sys.argv)
    for i in range(n):
        x, label, logp, _ = ds[i]
        img = cv2.cvtColor(((x.permute(1, 2, 0).numpy() * 128) + 128).clip(0, 255).astype(np.uint8), cv2.COLOR_RGB2BGR)
        lab = COLOURS[label.numpy()]
        prob = (np.exp(logp[1].numpy()) * 255).astype(np.uint8)
        overlay = cv2.addWeighted(img, 0.6, lab, 0.4, 0)
        cv2.imwrite(os.path.join(out, f'{i:02d}.png'), np.hstack([overlay, cv2.cvtColor(prob, cv2.COLOR_GRAY2BGR)]))


if __name__ == '__main__':
    main()
