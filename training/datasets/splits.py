#!/usr/bin/env python3
"""Write the fixed train/validation split lists (training/splits/{train,val}.txt).

Each line: `<source> <image path> <mask path or ->`, paths relative to the shared data folder.
Validation (never trained on): a seeded 25 % of human-seg, all of davis-parkour (one video, kept whole),
a seeded 10 % of ccp-person and the last 100 frames of the 7-Scenes kitchen clip (negatives; frames are
consecutive, so the held-out part is one contiguous block). Training only: the 300 real Bonn crowd frames
(no masks: people from the full teacher's labels), real indoor frames of people as the robot sees them."""
import glob
import os
import random
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from datasets import SHARED_DATA, TRAINING_DIR  # noqa: E402

SEED = 8


def _pairs(source, sub):
    root = os.path.join(SHARED_DATA, 'segmentation', sub)
    out = []
    for img in sorted(glob.glob(os.path.join(root, 'images', '*.jpg'))):
        mask = os.path.join(root, 'masks', os.path.splitext(os.path.basename(img))[0] + '.png')
        if not os.path.exists(mask):
            raise FileNotFoundError(mask)
        out.append((source, os.path.relpath(img, SHARED_DATA), os.path.relpath(mask, SHARED_DATA)))
    return out


def make_splits():
    rng = random.Random(SEED)
    train, val = [], []
    human = _pairs('human-seg', 'human-seg')
    rng.shuffle(human)
    n_val = round(0.25 * len(human))
    val += human[:n_val]
    train += human[n_val:]
    val += _pairs('davis', 'davis-parkour')
    ccp = _pairs('ccp', 'ccp-person')
    rng.shuffle(ccp)
    n_val = round(0.10 * len(ccp))
    val += ccp[:n_val]
    train += ccp[n_val:]
    kitchen = sorted(glob.glob(os.path.join(SHARED_DATA, '7scenes-redkitchen-500', 'rgb', '*.jpg')),
                     key=lambda p: float(os.path.basename(p)[:-4]))
    kitchen = [('kitchen', os.path.relpath(p, SHARED_DATA), '-') for p in kitchen]
    train += kitchen[:-100]
    val += kitchen[-100:]
    bonn = sorted(glob.glob(os.path.join(SHARED_DATA, 'bonn', 'rgbd_bonn_crowd_280-579', 'rgb', '*.jpg')))
    train += [('bonn', os.path.relpath(p, SHARED_DATA), '-') for p in bonn]
    return sorted(train), sorted(val)


def read_split(name):
    path = os.path.join(TRAINING_DIR, 'splits', f'{name}.txt')
    rows = []
    with open(path) as f:
        for line_no, line in enumerate(f, 1):
            if not line.strip() or line.startswith('#'):
                continue
            parts = line.split()
            if len(parts) != 3:
                raise ValueError(f'{path}:{line_no}: expected 3 fields, got {len(parts)}')
            rows.append(tuple(parts))
    return rows


def main():
    train, val = make_splits()
    for name, rows in (('train', train), ('val', val)):
        path = os.path.join(TRAINING_DIR, 'splits', f'{name}.txt')
        with open(path, 'w') as f:
            f.write(f'# {name} split, written by training/datasets/splits.py (seed {SEED}): source image mask\n')
            f.writelines(' '.join(r) + '\n' for r in rows)
        counts = {}
        for r in rows:
            counts[r[0]] = counts.get(r[0], 0) + 1
        print(name, len(rows), counts)


if __name__ == '__main__':
    main()
