#!/usr/bin/env python3
"""Turn a training checkpoint into the small shipped one: fp16 weights + model config + its validation eval.

  /usr/bin/python3 training/ship_checkpoint.py training/runs/mnv2_w05/best.pt training/checkpoints/mnv2_w05.pt"""
import sys

import torch


def main():
    src, dst = sys.argv[1], sys.argv[2]
    ck = torch.load(src, map_location='cpu')
    small = {'model': {k: v.half() if v.is_floating_point() else v for k, v in ck['model'].items()},
             'model_config': ck['model_config'], 'step': ck['step'], 'eval': ck.get('eval'),
             'args': ck.get('args')}
    torch.save(small, dst)
    print(f'{dst}: step {ck["step"]}, fp16 weights')


if __name__ == '__main__':
    main()
