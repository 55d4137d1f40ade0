#!/usr/bin/env python3
"""Count parameters and multiply-accumulates (conv + linear, by forward hooks) per part of each variant.

  /usr/bin/python3 training/count_flops.py [--size 257 337]"""
import argparse
import os
import sys

import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from model import MODEL_PRESETS, build_model  # noqa: E402
from model.layers import count_parameters  # noqa: E402


def count_macs(model, x):
    """MACs of every Conv2d by the top-level part it belongs to (backbone, aspp, low_level, decoder, classifier)."""
    macs = {}
    hooks = []
    for name, m in model.named_modules():
        if isinstance(m, torch.nn.Conv2d):
            part = name.split('.')[0]

            def hook(mod, inp, out, part=part):
                k = mod.kernel_size[0] * mod.kernel_size[1] * mod.in_channels // mod.groups
                macs[part] = macs.get(part, 0) + out.numel() // out.shape[0] * k
            hooks.append(m.register_forward_hook(hook))
    with torch.no_grad():
        model.eval()(x)
    for h in hooks:
        h.remove()
    return macs


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--size', type=int, nargs=2, default=(257, 337))
    args = ap.parse_args()
    x = torch.zeros(1, 3, *args.size)
    print(f'| variant | ASPP | params total (M) | ASPP params (M) | GMACs total | backbone | ASPP | decoder |')
    print('|---|---|---|---|---|---|---|---|')
    for preset in MODEL_PRESETS:
        for aspp in ('improved', 'original'):
            m = build_model(preset, aspp=aspp)
            macs = count_macs(m, x)
            dec = macs.get('low_level', 0) + macs.get('decoder', 0) + macs.get('classifier', 0)
            print(f'| {preset} | {aspp} | {count_parameters(m) / 1e6:.3f} | {count_parameters(m.aspp) / 1e6:.3f} | '
                  f'{sum(macs.values()) / 1e9:.3f} | {macs["backbone"] / 1e9:.3f} | {macs["aspp"] / 1e9:.3f} | '
                  f'{dec / 1e9:.3f} |')
    # the paper's setting: 256-channel head on a 2048-channel ResNet/ResNeSt output
    from model.aspp import ImprovedASPP, OriginalASPP
    for c_in in (320, 2048):
        o, i = count_parameters(OriginalASPP(c_in, 256)), count_parameters(ImprovedASPP(c_in, 256))
        print(f'ASPP alone, {c_in} -> 256 channels: original {o / 1e6:.3f} M, improved {i / 1e6:.3f} M '
              f'({100 * (1 - i / o):.0f} % fewer)')


if __name__ == '__main__':
    main()
