#!/usr/bin/env python3
"""Run the full-width DeepLabv3 VOC teacher once over every split image and cache its logits.

For each image: the teacher input keeps the aspect ratio approximately (longer side 513, sizes 16k+1,
RGB (x - 128) / 128, as its model card says); the cache keeps the stride-16 logits, before the teacher's
own bilinear upsampling, reduced to our classes as log-probabilities (logsumexp over each class's VOC ids,
everything else merged into background). Tiny files (~3 x 25 x 33 float16); the data loader warps them
with the same geometry as the image (datasets/augment.py).

  nice -n 19 /usr/bin/python3 training/datasets/teacher_cache.py
"""
import os
import sys
import time

import cv2
import numpy as np
import torch

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from datasets import CACHE_DIR, SHARED_DATA, TEACHER_DIR, load_classes  # noqa: E402
from datasets.splits import read_split  # noqa: E402


def teacher_input_size(h, w, longer=513):
    """(H, W) of the form 16k+1 with the longer side `longer` and about the image's aspect ratio."""
    def snap(v):
        return 16 * max(1, round((v - 1) / 16)) + 1
    if h >= w:
        return longer, snap(longer * w / h)
    return snap(longer * h / w), longer


def load_teacher(width_mult=1.0):
    sys.path.insert(0, TEACHER_DIR)
    from deeplabv3_mnv2 import load_voc_model   # Apache-2.0 module shipped with the weights, not copied here
    name = 'deeplabv3_mnv2_voc.pth' if width_mult == 1.0 else 'deeplabv3_mnv2_dm05_voc.pth'
    return load_voc_model(os.path.join(TEACHER_DIR, name), width_mult)


class GridLogits(torch.nn.Module):
    """The teacher without its final upsampling: 21 x H/16 x W/16 logits."""

    def __init__(self, teacher):
        super().__init__()
        self.t = teacher

    def forward(self, x):
        return self.t.classifier(self.t.aspp(self.t.backbone(x)))


class CvTeacher:
    """The teacher's grid logits through cv2.dnn (about twice as fast as PyTorch here); one ONNX per size."""

    def __init__(self, teacher, tmp_dir):
        self.model, self.tmp, self.nets = GridLogits(teacher).eval(), tmp_dir, {}

    def __call__(self, blob, size):
        if size not in self.nets:
            import deeplabv3_mnv2 as t
            path = os.path.join(self.tmp, f'teacher_{size[0]}x{size[1]}.onnx')
            t.EXPORT_FRIENDLY_RELU6 = True
            try:
                torch.onnx.export(self.model, torch.zeros(1, 3, *size), path, opset_version=11)
            finally:
                t.EXPORT_FRIENDLY_RELU6 = False
            self.nets[size] = cv2.dnn.readNetFromONNX(path)
        net = self.nets[size]
        net.setInput(blob)
        return torch.from_numpy(net.forward()[0].copy())


def teacher_grid_logits(teacher, bgr, size):
    """21 x G_h x G_w logits at stride 16 (the teacher's classifier output before upsampling).
    teacher: the PyTorch module or a CvTeacher."""
    th, tw = size
    blob = cv2.dnn.blobFromImage(bgr, 1 / 128.0, (tw, th), (128, 128, 128), swapRB=True)
    if isinstance(teacher, CvTeacher):
        return teacher(blob, size)
    with torch.no_grad():
        return GridLogits(teacher)(torch.from_numpy(blob))[0]


def reduce_to_classes(logits21, classes):
    """Log-probabilities of our classes: logsumexp over each class's VOC ids, the rest -> background."""
    logp = torch.log_softmax(logits21, dim=0)
    used = {v for c in classes for v in c['voc_ids']}
    rest = [i for i in range(logits21.shape[0]) if i not in used]
    out = [torch.logsumexp(logp[rest], dim=0)]
    out += [torch.logsumexp(logp[c['voc_ids']], dim=0) for c in classes[1:]]
    return torch.stack(out)


def cache_path(image_rel):
    return os.path.join(CACHE_DIR, os.path.splitext(image_rel)[0] + '.npz')


def load_cached(image_rel):
    """(log-probs C x G_h x G_w float32, teacher input (H, W))."""
    with np.load(cache_path(image_rel)) as z:
        return z['logp'].astype(np.float32), tuple(int(v) for v in z['teacher_input'])


def main():
    torch.set_num_threads(2)
    classes = load_classes()
    import tempfile
    cv2.setNumThreads(2)
    tmp = tempfile.TemporaryDirectory()
    teacher = CvTeacher(load_teacher(), tmp.name)
    rows = read_split('train') + read_split('val')
    if '--reverse' in sys.argv:   # a second process can work from the other end
        rows = rows[::-1]
    t0, done = time.time(), 0
    for i, (_, image_rel, _) in enumerate(rows):
        out = cache_path(image_rel)
        if os.path.exists(out):
            if '--reverse' in sys.argv and done:
                break   # met the forward process
            continue
        bgr = cv2.imread(os.path.join(SHARED_DATA, image_rel), cv2.IMREAD_COLOR)
        if bgr is None:
            raise IOError(f'cannot read {image_rel}')
        size = teacher_input_size(*bgr.shape[:2])
        logp = reduce_to_classes(teacher_grid_logits(teacher, bgr, size), classes)
        os.makedirs(os.path.dirname(out), exist_ok=True)
        np.savez(out + '.tmp.npz', logp=logp.numpy().astype(np.float16), teacher_input=np.array(size))
        os.replace(out + '.tmp.npz', out)
        done += 1
        if done % 50 == 0:
            print(f'{i + 1}/{len(rows)} {(time.time() - t0) / done:.2f} s/image', flush=True)
    print(f'cached {done} new images in {time.time() - t0:.0f} s -> {CACHE_DIR}')


if __name__ == '__main__':
    main()
