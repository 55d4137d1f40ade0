"""Segmentation metrics: confusion matrices, IoU per class, person IoU pooled and mean per image."""
import numpy as np


def confusion(pred, label, num_classes, ignore=255):
    keep = label != ignore
    idx = label[keep].astype(np.int64) * num_classes + pred[keep].astype(np.int64)
    return np.bincount(idx, minlength=num_classes * num_classes).reshape(num_classes, num_classes)


def iou_per_class(conf):
    inter = np.diag(conf).astype(np.float64)
    union = conf.sum(0) + conf.sum(1) - inter
    with np.errstate(invalid='ignore', divide='ignore'):
        return np.where(union > 0, inter / np.maximum(union, 1), np.nan)


class SegEvaluator:
    """Accumulates per source: class confusion (person from ground truth, chair from the teacher), per-image
    person IoU on frames with a ground-truth mask, and the person false-positive rate on frames without people."""

    def __init__(self, class_names):
        self.names = list(class_names)
        self.n = len(self.names)
        self.conf = {}
        self.person_ious = {}
        self.fp = {}

    def add(self, source, pred, label, has_person_gt):
        c = confusion(pred, label, self.n)
        self.conf[source] = self.conf.get(source, 0) + c
        gt, pr = label == 1, pred == 1
        if has_person_gt:
            union = np.count_nonzero(gt | pr)
            self.person_ious.setdefault(source, []).append(np.count_nonzero(gt & pr) / union if union else 1.0)
        else:
            f = self.fp.setdefault(source, [0, 0])
            f[0] += np.count_nonzero(pr)
            f[1] += pr.size

    def summary(self):
        out = {}
        total = sum(self.conf.values())
        ious = iou_per_class(total)
        out['all'] = {'mIoU': float(np.nanmean(ious)), **{f'IoU_{n}': float(v) for n, v in zip(self.names, ious)}}
        for src, conf in sorted(self.conf.items()):
            d = {}
            if src in self.person_ious:
                pooled = iou_per_class(conf)[1]
                d.update(person_iou_pooled=float(pooled), person_iou_mean=float(np.mean(self.person_ious[src])),
                         person_iou_median=float(np.median(self.person_ious[src])), n=len(self.person_ious[src]))
            if src in self.fp:
                d.update(person_false_positive_rate=self.fp[src][0] / max(1, self.fp[src][1]))
            out[src] = d
        return out


def selection_score(summary):
    """Checkpoint selection: human-seg matters most (the shipped model is checked on more of it)."""
    parts = [(0.5, 'human-seg'), (0.25, 'davis'), (0.25, 'ccp')]
    got = [(w, summary[s]['person_iou_mean']) for w, s in parts if s in summary and 'person_iou_mean' in summary[s]]
    return sum(w * v for w, v in got) / sum(w for w, _ in got) if got else float('nan')
