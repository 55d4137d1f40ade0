#!/usr/bin/env python3
"""Export a trained DeepLabv3+ checkpoint to ONNX (fixed input size) for OpenCV 4.6's dnn module.

  /usr/bin/python3 training/export_onnx.py --checkpoint training/checkpoints/mnv2_w05.pt --out models/x.onnx
"""
import argparse
import inspect
import os
import sys

import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from model import build_model, export_friendly  # noqa: E402


def load_checkpoint_model(path):
    """Rebuild the model from the config stored in a checkpoint (full training state or the shipped fp16 one)."""
    ckpt = torch.load(path, map_location='cpu')
    cfg = ckpt['model_config']
    model = build_model(cfg['preset'], num_classes=cfg['num_classes'], aspp=cfg.get('aspp', 'improved'))
    model.load_state_dict({k: v.float() for k, v in ckpt['model'].items()})
    return model.eval(), ckpt


def inline_identity_initializers(onnx_model):
    """The exporter shares equal constant tensors (e.g. zero biases) through Identity nodes, which
    OpenCV 4.6 cannot parse; give each user its own copy of the initializer instead."""
    import onnx
    graph = onnx.load(onnx_model) if isinstance(onnx_model, str) else onnx_model
    g = graph.graph
    inits = {t.name: t for t in g.initializer}
    for node in [n for n in g.node if n.op_type == 'Identity' and n.input[0] in inits]:
        copy = onnx.TensorProto()
        copy.CopyFrom(inits[node.input[0]])
        copy.name = node.output[0]
        g.initializer.append(copy)
        g.node.remove(node)
    return graph


def export(model, path, height, width, opset=11):
    kwargs = dict(opset_version=opset, input_names=['input'], output_names=['logits'], do_constant_folding=True)
    if 'dynamo' in inspect.signature(torch.onnx.export).parameters:
        kwargs['dynamo'] = False   # torch 2.x: the classic TorchScript exporter (torch 1.13 has no such argument)
    with export_friendly(), torch.no_grad():
        torch.onnx.export(model.eval(), torch.zeros(1, 3, height, width), path, **kwargs)
    import onnx
    onnx.save(inline_identity_initializers(path), path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--checkpoint', required=True)
    ap.add_argument('--out', required=True)
    ap.add_argument('--height', type=int, default=257, help='input height (16k+1), default 257')
    ap.add_argument('--width', type=int, default=337, help='input width (16k+1), default 337')
    ap.add_argument('--opset', type=int, default=11)
    args = ap.parse_args()
    model, _ = load_checkpoint_model(args.checkpoint)
    export(model, args.out, args.height, args.width, args.opset)
    import onnx
    onnx.checker.check_model(onnx.load(args.out))
    ops = sorted({n.op_type for n in onnx.load(args.out).graph.node})
    print(f'wrote {args.out} ({os.path.getsize(args.out) / 1e6:.2f} MB), ops: {", ".join(ops)}')


if __name__ == '__main__':
    main()
