"""torch Datasets: augmented training samples (deterministic per global sample index) and validation frames."""
import os

import cv2
import numpy as np
import torch
from torch.utils.data import Dataset

from . import SHARED_DATA
from .augment import (image_to_teacher_grid, labels_from, photometric, random_map, warp,
                      warp_logp)
from .teacher_cache import load_cached

# share of each source in a training batch; 'paste' = a kitchen frame with one or two people pasted in,
# 'crowd' = a kitchen frame with 2-5 smaller people (street scenes and crowds: many people, a few dozen
# pixels tall, which the first model missed most)
DEFAULT_MIX = {'human-seg': 0.35, 'ccp': 0.25, 'kitchen': 0.15, 'paste': 0.25}
PERSON_SOURCES = ('human-seg', 'ccp', 'davis')
# sources without masks whose people come from the teacher (real frames with people, unlabelled)
TEACHER_PERSON_SOURCES = ('bonn',)
# pasted sources: (scale of the person photo against the frame, how many people, placed anywhere in the
# frame or centred when smaller than it)
PASTED = {'paste': ((0.4, 1.1), lambda rng: 1 + int(rng.random() < 0.3), False),
          'crowd': ((0.15, 0.6), lambda rng: int(rng.integers(2, 6)), True),
          # one person so close that only part of them is in view (a head, a shoulder filling the
          # frame's edge): what a crowd shows a handheld camera, and what the crowd source made rarer
          'closeup': ((1.2, 3.0), lambda rng: 1, True)}


def parse_mix(text):
    """'human-seg=0.3,ccp=0.2,...' -> dict; sources: split sources plus the pasted ones (PASTED)."""
    mix = {}
    for part in text.split(','):
        name, _, weight = part.partition('=')
        if not weight or float(weight) < 0:
            raise ValueError(f'--mix: expected source=weight, got {part!r}')
        mix[name.strip()] = float(weight)
    return mix


def to_tensor(bgr):
    """BGR uint8 HxWx3 -> RGB float 3xHxW in [-1, 1): (x - 128) / 128, the teacher's and our preprocessing."""
    rgb = cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB).astype(np.float32)
    return torch.from_numpy((rgb - 128.0) / 128.0).permute(2, 0, 1).contiguous()


class Sample:
    """One split row, loaded: image, optional person mask, teacher log-probabilities."""

    def __init__(self, row):
        self.source, self.image_rel, mask_rel = row
        self.image = cv2.imread(os.path.join(SHARED_DATA, self.image_rel), cv2.IMREAD_COLOR)
        if self.image is None:
            raise IOError(f'cannot read image {self.image_rel}')
        self.mask = None
        if mask_rel != '-':
            m = cv2.imread(os.path.join(SHARED_DATA, mask_rel), cv2.IMREAD_GRAYSCALE)
            if m is None or m.shape != self.image.shape[:2]:
                raise IOError(f'bad mask {mask_rel} for {self.image_rel}')
            self.mask = m
        try:
            self.logp, self.teacher_hw = load_cached(self.image_rel)
            self.has_teacher = True
        except FileNotFoundError:
            # not cached yet (teacher_cache.py still running): uniform targets, excluded from distillation
            self.logp = np.full((3, 2, 2), np.log(1 / 3), np.float32)
            self.teacher_hw, self.has_teacher = self.image.shape[:2], False

    def warped(self, m33, out_hw):
        """(image, person mask bool or None, valid bool, teacher logp) seen through output->image map m33."""
        img = warp(self.image, m33, out_hw, cv2.INTER_LINEAR, (128, 128, 128))
        valid = warp(np.full(self.image.shape[:2], 255, np.uint8), m33, out_hw, cv2.INTER_NEAREST, 0) > 0
        person = None
        if self.mask is not None:
            person = warp(self.mask, m33, out_hw, cv2.INTER_NEAREST, 0) > 127
        grid = image_to_teacher_grid(self.image.shape[:2], self.teacher_hw, self.logp.shape[1:]) @ m33
        return img, person, valid, warp_logp(self.logp, grid, out_hw)


class TrainDataset(Dataset):
    """Item i is a pure function of (seed, i): resuming at a step reproduces the same batches exactly."""

    def __init__(self, rows, input_hw=(257, 337), crop_hw=(257, 337), seed=0, mix=None, num_classes=3,
                 max_per_source=None, extended_photometric=False):
        self.input_hw, self.crop_hw, self.seed, self.num_classes = input_hw, crop_hw, seed, num_classes
        self.extended_photometric = extended_photometric
        self.mix = dict(mix or DEFAULT_MIX)
        by_source = {}
        for r in rows:
            by_source.setdefault(r[0], []).append(r)
        self.rows = {k: v[:max_per_source] if max_per_source else v for k, v in by_source.items()}
        self.people = [r for k in PERSON_SOURCES for r in self.rows.get(k, [])]
        self._cache = {}
        names = [k for k in self.mix if (k in PASTED and self.people and self.rows.get('kitchen'))
                 or self.rows.get(k)]
        w = np.array([self.mix[k] for k in names], np.float64)
        self.sources, self.weights = names, w / w.sum()

    def __len__(self):
        return 1 << 40   # indexed by the global sample counter

    def _sample(self, row):
        s = self._cache.get(row[1])
        if s is None:
            s = self._cache[row[1]] = Sample(row)   # all splits fit in memory (~1.5 GB)
        return s

    def __getitem__(self, index):
        rng = np.random.default_rng([self.seed, index])
        src = self.sources[rng.choice(len(self.sources), p=self.weights)]
        if src in PASTED:
            return self._pasted(rng, *PASTED[src])
        rows = self.rows[src]
        s = self._sample(rows[rng.integers(len(rows))])
        m = random_map(rng, s.image.shape[:2], self.input_hw, self.crop_hw)
        img, person, valid, logp = s.warped(m, self.crop_hw)
        return self._finish(rng, img, person, valid, logp, s.has_teacher, src in TEACHER_PERSON_SOURCES)

    def _pasted(self, rng, scale, count, anywhere):
        bg = self._sample(self.rows['kitchen'][rng.integers(len(self.rows['kitchen']))])
        img, _, valid, logp = bg.warped(random_map(rng, bg.image.shape[:2], self.input_hw, self.crop_hw),
                                        self.crop_hw)
        person = np.zeros(self.crop_hw, bool)
        has_teacher = bg.has_teacher
        for _ in range(count(rng)):
            p = self._sample(self.people[rng.integers(len(self.people))])
            # the person photo at `scale` of the frame, anywhere: no border padding visible, only its mask
            m = random_map(rng, p.image.shape[:2], self.input_hw, self.crop_hw, scale=scale, anywhere=anywhere)
            p_img, p_mask, p_valid, p_logp = p.warped(m, self.crop_hw)
            alpha = cv2.GaussianBlur((p_mask & p_valid).astype(np.float32), (0, 0), 0.8)[..., None]
            img = (alpha * p_img + (1 - alpha) * img).astype(np.uint8)
            inside = alpha[..., 0] > 0.5
            person |= inside
            logp = np.where(inside[None], p_logp, logp)
            has_teacher = has_teacher and p.has_teacher
        return self._finish(rng, img, person, valid, logp, has_teacher)

    def _finish(self, rng, img, person, valid, logp, has_teacher, teacher_person=False):
        label = labels_from(person, valid, logp, self.num_classes, teacher_person)
        return to_tensor(photometric(rng, img, self.extended_photometric)), torch.from_numpy(label.astype(np.int64)), \
            torch.from_numpy(np.ascontiguousarray(logp)), torch.tensor(float(has_teacher))


class EvalDataset(Dataset):
    """Validation frames as deployed: whole image squashed to the input size. Returns the input tensor,
    the full-resolution label map (person from ground truth, chair from the teacher, 255 = none) and
    whether the frame has a ground-truth person mask."""

    def __init__(self, rows, input_hw=(257, 337)):
        self.rows, self.input_hw = rows, input_hw

    def __len__(self):
        return len(self.rows)

    def __getitem__(self, i):
        s = Sample(self.rows[i])
        hw = s.image.shape[:2]
        x = to_tensor(cv2.resize(s.image, (self.input_hw[1], self.input_hw[0]), interpolation=cv2.INTER_LINEAR))
        grid = image_to_teacher_grid(hw, s.teacher_hw, s.logp.shape[1:])
        logp = warp_logp(s.logp, grid, hw)
        label = labels_from(s.mask > 127 if s.mask is not None else None, np.ones(hw, bool), logp, 3)
        return x, label, s.source, s.image_rel

