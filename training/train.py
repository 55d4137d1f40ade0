#!/usr/bin/env python3
"""Train the improved DeepLabv3+ on the CPU: cross-entropy on ground-truth / pseudo labels plus KL
distillation to the VOC teacher's cached logits, AdamW with poly LR, exact resume, eval every epoch.

  nohup nice -n 19 /usr/bin/python3 training/train.py --run mnv2_w05 > training/runs/log.txt 2>&1 &
  /usr/bin/python3 training/train.py --one-batch          # CI smoke test: one tiny step, a few seconds

Resume: rerun the same command; training/runs/<run>/last.pt (model, optimiser, step, RNG) is picked up.
Batches are a pure function of (seed, global sample index), so a resumed run sees the same data."""
import argparse
import json
import os
import random
import shutil
import sys
import tempfile
import time

import numpy as np
import torch
import torch.nn.functional as F
from torch.utils.data import DataLoader

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from datasets import IGNORE, TEACHER_DIR, TRAINING_DIR, load_classes  # noqa: E402
from model import build_model  # noqa: E402
from model.layers import count_parameters  # noqa: E402
from model.mobilenetv2 import load_teacher_backbone, load_torchvision_backbone  # noqa: E402

IMAGENET_MNV2 = os.path.join(TEACHER_DIR, '..', 'mobilenetv2-imagenet', 'mobilenet_v2_imagenet_tv.pth')


def parse_args(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--run', default='mnv2_w05', help='run name: logs and checkpoints in training/runs/<run>/')
    ap.add_argument('--runs-dir', default=os.path.join(TRAINING_DIR, 'runs'))
    ap.add_argument('--preset', default='mnv2_w05', help='mnv2_w05 | mnv2_w10 | resnest26_w05')
    ap.add_argument('--aspp', default='improved', help='improved | original')
    ap.add_argument('--init', default='teacher', help='teacher | imagenet | none (mobilenetv2 backbones)')
    ap.add_argument('--input', type=int, nargs=2, default=(257, 337), metavar=('H', 'W'),
                    help='deployment input size (16k+1)')
    ap.add_argument('--crop', type=int, nargs=2, default=(193, 257), metavar=('H', 'W'), help='training crop')
    ap.add_argument('--batch', type=int, default=8)
    ap.add_argument('--mix', help='share of each source per batch, e.g. human-seg=0.3,ccp=0.2,kitchen=0.1,'
                    'paste=0.15,crowd=0.15,bonn=0.1 (default: datasets/seg_dataset.py DEFAULT_MIX)')
    ap.add_argument('--extended-aug', action='store_true', help='also motion blur and low light')
    ap.add_argument('--steps', type=int, default=6000, help='total optimiser steps (poly LR horizon)')
    ap.add_argument('--epoch-steps', type=int, default=250, help='steps between evaluations')
    ap.add_argument('--ckpt-every', type=int, default=50, help='steps between resume checkpoints')
    ap.add_argument('--lr', type=float, default=2e-3, help='new layers; the pretrained backbone gets lr * 0.1')
    ap.add_argument('--backbone-lr-mult', type=float, default=0.1)
    ap.add_argument('--weight-decay', type=float, default=1e-4)
    ap.add_argument('--warmup', type=int, default=50)
    ap.add_argument('--distill', type=float, default=0.5, help='weight of KL(teacher || student)')
    ap.add_argument('--freeze-steps', type=int, default=1000, help='early backbone layers frozen for this long')
    ap.add_argument('--freeze-units', type=int, default=18,
                    help='number of leading backbone conv units frozen (mnv2: 18 = stem..stride-8 stage)')
    ap.add_argument('--max-val', type=int, default=0, help='evaluate on at most this many val frames (0 = all)')
    ap.add_argument('--workers', type=int, default=1)
    ap.add_argument('--threads', type=int, default=2)
    ap.add_argument('--seed', type=int, default=0)
    ap.add_argument('--max-minutes', type=float, default=0, help='stop cleanly (checkpoint) after this long')
    ap.add_argument('--resume-from', help='a committed full training state (training/checkpoints/*_state.pt): '
                    'copied to runs/<run>/last.pt when that does not exist, then resumed exactly')
    ap.add_argument('--init-weights', help='start a new run from the model weights of this checkpoint '
                    '(e.g. a second, unfrozen fine-tuning phase); overrides --init')
    ap.add_argument('--stop-after', type=int, default=0, help='stop after this many steps in this invocation')
    ap.add_argument('--one-batch', action='store_true', help='smoke test: one tiny step + resume check')
    return ap.parse_args(argv)


def init_backbone(model, args):
    if args.init == 'none' or not args.preset.startswith('mnv2'):
        return 'random'
    if args.init == 'teacher':
        name = 'deeplabv3_mnv2_voc.pth' if model.backbone.out_channels == 320 else 'deeplabv3_mnv2_dm05_voc.pth'
        path = os.path.join(TEACHER_DIR, name)
        load_teacher_backbone(model.backbone, path)
    elif args.init == 'imagenet':
        path = IMAGENET_MNV2
        load_torchvision_backbone(model.backbone, path)
    else:
        raise ValueError(f'unknown --init {args.init!r}')
    return path


def backbone_units(model):
    return [m for m in model.backbone.modules() if m.__class__.__name__ == 'ConvBNAct']


def set_frozen(model, n_units, frozen):
    for unit in backbone_units(model)[:n_units]:
        for p in unit.parameters():
            p.requires_grad_(not frozen)


def freeze_backbone_bn(model):
    """Pretrained backbone BN keeps its statistics (batch 8 of small crops would only add noise)."""
    for m in model.backbone.modules():
        if isinstance(m, torch.nn.BatchNorm2d):
            m.eval()


def make_optimizer(model, args, pretrained):
    bb = list(model.backbone.parameters())
    bb_ids = {id(p) for p in bb}
    rest = [p for p in model.parameters() if id(p) not in bb_ids]
    mult = args.backbone_lr_mult if pretrained else 1.0
    return torch.optim.AdamW([{'params': bb, 'lr_mult': mult}, {'params': rest, 'lr_mult': 1.0}],
                             lr=args.lr, weight_decay=args.weight_decay)


def lr_at(step, args):
    warm = min(1.0, (step + 1) / max(1, args.warmup))
    return args.lr * warm * (1 - step / args.steps) ** 0.9


def loss_fn(logits, label, teacher_logp, distill, teacher_weight=None):
    ce = F.cross_entropy(logits, label, ignore_index=IGNORE)
    if distill <= 0:
        return ce, ce.detach(), torch.zeros(())
    valid = (label != IGNORE).float()
    if teacher_weight is not None:   # samples without cached teacher logits take no part in distillation
        valid = valid * teacher_weight.view(-1, 1, 1)
    log_s = F.log_softmax(logits, dim=1)
    kl = (teacher_logp.exp() * (teacher_logp - log_s)).sum(1)
    kl = (kl * valid).sum() / valid.sum().clamp(min=1)
    return ce + distill * kl, ce.detach(), kl.detach()


def save_checkpoint(path, model, opt, step, best, args, extra=None):
    state = {'model': model.state_dict(), 'optimizer': opt.state_dict(), 'step': step, 'best': best,
             'torch_rng': torch.get_rng_state(), 'numpy_rng': np.random.get_state(), 'py_rng': random.getstate(),
             'model_config': model_config(args), 'args': vars(args)}
    state.update(extra or {})
    tmp = path + '.tmp'
    torch.save(state, tmp)
    os.replace(tmp, path)


def model_config(args):
    return {'preset': args.preset, 'aspp': args.aspp, 'num_classes': len(load_classes()),
            'input_hw': list(args.input), 'classes': [c['name'] for c in load_classes()],
            'normalisation': 'RGB, (pixel - 128) / 128'}


class SyntheticDataset(torch.utils.data.Dataset):
    """Random tensors of the right shapes: the smoke test without the shared data / teacher cache (CI)."""

    def __init__(self, crop, num_classes, seed):
        self.crop, self.n, self.seed = crop, num_classes, seed

    def __getitem__(self, i):
        g = torch.Generator().manual_seed(self.seed * 100003 + i)
        h, w = self.crop
        return (torch.rand(3, h, w, generator=g) * 2 - 1, torch.randint(0, self.n, (h, w), generator=g),
                torch.log_softmax(torch.randn(self.n, h, w, generator=g), 0), torch.tensor(1.0))


def available_rows(split):
    """Split rows whose image and teacher cache exist (all of them after datasets/teacher_cache.py)."""
    from datasets import SHARED_DATA
    from datasets.splits import read_split
    from datasets.teacher_cache import cache_path
    return [r for r in read_split(split)
            if os.path.exists(cache_path(r[1])) and os.path.exists(os.path.join(SHARED_DATA, r[1]))]


def data_loader(args, start_step):
    from datasets.seg_dataset import TrainDataset
    from datasets.splits import read_split
    n = len(load_classes())
    if args.one_batch:
        rows = available_rows('train')
        ds = TrainDataset(rows, tuple(args.input), tuple(args.crop), args.seed, num_classes=n) if rows \
            else SyntheticDataset(tuple(args.crop), n, args.seed)
        print(f'one-batch data: {"real" if rows else "synthetic"}', flush=True)
    else:
        from datasets.seg_dataset import parse_mix
        ds = TrainDataset(read_split('train'), tuple(args.input), tuple(args.crop), args.seed, num_classes=n,
                          mix=parse_mix(args.mix) if args.mix else None,
                          extended_photometric=args.extended_aug)
    order = range(start_step * args.batch, args.steps * args.batch)
    # its own generator: creating the iterator must not draw from the global RNG (dropout), or a resumed
    # run would see different dropout masks from an uninterrupted one
    return DataLoader(ds, batch_size=args.batch, sampler=order, num_workers=args.workers,
                      persistent_workers=args.workers > 0, generator=torch.Generator().manual_seed(args.seed))


def evaluate(model, args):
    from datasets.splits import read_split
    from evaluate import format_summary, run_eval, torch_predictor
    rows = available_rows('val') if args.one_batch else read_split('val')
    if not rows:
        return {'score': -0.5}, 'no validation data (smoke test without shared data)'
    if args.max_val and args.max_val < len(rows):   # evenly spread, so every source stays represented
        rows = [rows[i] for i in np.linspace(0, len(rows) - 1, args.max_val).round().astype(int)]
    model.eval()
    s = run_eval(torch_predictor(model), rows, tuple(args.input), [c['name'] for c in load_classes()])
    model.train()
    freeze_backbone_bn(model)
    return s, format_summary(s)


def train(args):
    torch.set_num_threads(args.threads)
    torch.manual_seed(args.seed)
    run_dir = os.path.join(args.runs_dir, args.run)
    os.makedirs(run_dir, exist_ok=True)
    last, best_path = os.path.join(run_dir, 'last.pt'), os.path.join(run_dir, 'best.pt')
    model = build_model(args.preset, num_classes=len(load_classes()), aspp=args.aspp)
    step, best = 0, -1.0
    if args.resume_from and not os.path.exists(last):
        shutil.copyfile(args.resume_from, last)
    if os.path.exists(last):
        ck = torch.load(last, map_location='cpu')
        model.load_state_dict(ck['model'])
        pretrained = ck['args']['init'] != 'none' and args.preset.startswith('mnv2')
        opt = make_optimizer(model, args, pretrained)
        opt.load_state_dict(ck['optimizer'])
        step, best = ck['step'], ck['best']
        torch.set_rng_state(ck['torch_rng'])
        np.random.set_state(ck['numpy_rng'])
        random.setstate(ck['py_rng'])
        print(f'resumed {last} at step {step} (best score {best:.4f})', flush=True)
    else:
        if args.init_weights:
            model.load_state_dict({k: v.float() if v.is_floating_point() else v
                                   for k, v in torch.load(args.init_weights, map_location='cpu')['model'].items()})
            src, pretrained = args.init_weights + ' (whole model)', True
        else:
            src = init_backbone(model, args)
            pretrained = src != 'random'
        opt = make_optimizer(model, args, pretrained)
        print(f'new run {run_dir}: {args.preset} aspp={args.aspp} backbone init {src}; '
              f'{count_parameters(model) / 1e6:.3f} M parameters', flush=True)
        with open(os.path.join(run_dir, 'args.json'), 'w') as f:
            json.dump(vars(args), f, indent=1)
    model.train()
    freeze_backbone_bn(model)
    frozen = pretrained and step < args.freeze_steps
    set_frozen(model, args.freeze_units, frozen)
    t0, t_log, start, seen = time.time(), time.time(), step, 0
    sums = np.zeros(3)
    for x, label, teacher_logp, teacher_w in data_loader(args, step):
        if frozen and step >= args.freeze_steps:
            set_frozen(model, args.freeze_units, False)
            frozen = False
            print(f'step {step}: early backbone layers unfrozen', flush=True)
        lr = lr_at(step, args)
        for g in opt.param_groups:
            g['lr'] = lr * g['lr_mult']
        loss, ce, kl = loss_fn(model(x), label, teacher_logp, args.distill, teacher_w)
        opt.zero_grad(set_to_none=True)
        loss.backward()
        opt.step()
        step += 1
        seen += 1
        sums += [loss.item(), ce.item(), kl.item()]
        if step % 10 == 0 or args.one_batch:
            n = max(1, min(seen, 10))
            print(f'step {step}/{args.steps} loss {sums[0] / n:.4f} ce {sums[1] / n:.4f} kl {sums[2] / n:.4f} '
                  f'lr {lr:.2e} {(time.time() - t_log) / n:.2f} s/step', flush=True)
            sums[:], t_log, seen = 0, time.time(), 0
        out_of_time = (args.max_minutes and (time.time() - t0) / 60 > args.max_minutes) or \
            (args.stop_after and step - start >= args.stop_after)
        if step % args.epoch_steps == 0 or step == args.steps:
            s, text = evaluate(model, args)
            print(f'eval at step {step}:\n{text}', flush=True)
            with open(os.path.join(run_dir, 'eval.jsonl'), 'a') as f:
                f.write(json.dumps({'step': step, **s}) + '\n')
            if s['score'] > best:
                best = s['score']
                save_checkpoint(best_path, model, opt, step, best, args, {'eval': s})
                print(f'new best {best:.4f} -> {best_path}', flush=True)
        if step % args.ckpt_every == 0 or step == args.steps or out_of_time:
            save_checkpoint(last, model, opt, step, best, args)
        if out_of_time:
            break
    print(f'stopped at step {step} after {(time.time() - t0) / 60:.1f} min ({step - start} steps)', flush=True)
    return model, step


def one_batch(argv):
    """Tiny runs in a temp dir: 2 steps straight vs 1 step + checkpoint + resume for 1 step; the weights
    must match exactly (exact resume), and an evaluation must run."""
    tmp = tempfile.mkdtemp(prefix='dlslam_one_batch_')
    try:
        base = ['--runs-dir', tmp, '--crop', '65', '81', '--batch', '2', '--steps', '2', '--epoch-steps', '2',
                '--max-val', '2', '--workers', '0', '--one-batch', '--input', '129', '161'] + argv
        straight, step = train(parse_args(base + ['--run', 'straight']))
        assert step == 2, step
        _, step = train(parse_args(base + ['--run', 'resumed', '--stop-after', '1']))
        assert step == 1, step
        resumed, step = train(parse_args(base + ['--run', 'resumed']))
        assert step == 2, step
        for k, v in straight.state_dict().items():
            assert torch.equal(v, resumed.state_dict()[k]), f'resume is not exact: {k}'
        assert all(torch.isfinite(p).all() for p in resumed.parameters())
        assert os.path.exists(os.path.join(tmp, 'resumed', 'best.pt'))
        print('one-batch smoke test OK (2 steps straight == 1 step + resume + 1 step)')
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == '__main__':
    if '--one-batch' in sys.argv:
        one_batch([a for a in sys.argv[1:] if a != '--one-batch'])
    else:
        train(parse_args())
