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


def fuse_relu6_for_opencv(onnx_model):
    """relu(x) - relu(x - 6) (the export-friendly ReLU6, four layers in OpenCV) -> one Clip node with
    min/max attributes, which OpenCV 4.6 reads as its ReLU6 layer and fuses into the convolution before
    it: the same logits to the bit, 22 % less inference time (22.4 -> 17.4 ms on the shipped model, one
    thread). Clip-11 takes min/max as inputs, which OpenCV 4.6 refuses; with attributes (the opset-6
    form) onnx.checker and ONNX Runtime refuse the file instead: it is an OpenCV-dnn model
    (export with --portable for the spec-valid form). Returns the number of ReLU6 fused."""
    from onnx import helper, numpy_helper
    g = onnx_model.graph
    constants = {n.output[0]: n for n in g.node if n.op_type == 'Constant'}
    producer = {o: n for n in g.node for o in n.output}

    def six(name):
        node = constants.get(name)
        if node is not None:
            return float(numpy_helper.to_array(node.attribute[0].t)) == 6.0
        init = next((t for t in g.initializer if t.name == name), None)
        return init is not None and float(numpy_helper.to_array(init)) == 6.0

    replaced, dropped = {}, set()
    for n in g.node:
        if n.op_type != 'Sub' or n.input[0] not in producer or n.input[1] not in producer:
            continue
        a, c = producer[n.input[0]], producer[n.input[1]]
        if a.op_type != 'Relu' or c.op_type != 'Relu' or c.input[0] not in producer:
            continue
        b = producer[c.input[0]]
        if b.op_type != 'Sub' or b.input[0] != a.input[0] or not six(b.input[1]):
            continue
        replaced[id(n)] = helper.make_node('Clip', [a.input[0]], [n.output[0]], name=n.name + '_relu6',
                                           min=0.0, max=6.0)
        dropped.update({id(a), id(b), id(c)})
        if b.input[1] in constants:
            dropped.add(id(constants[b.input[1]]))
    nodes = [replaced.get(id(n), n) for n in g.node if id(n) not in dropped]
    # A dropped Relu or Sub that something else still read would leave that input dangling.
    known = {t.name for t in g.initializer} | {i.name for i in g.input} | {o for n in nodes for o in n.output}
    dangling = sorted({i for n in nodes for i in n.input if i and i not in known})
    if dangling:
        raise ValueError(f'fusing ReLU6 would orphan {dangling[:3]}: export with --portable')
    del g.node[:]
    g.node.extend(nodes)
    return len(replaced)


def export(model, path, height, width, opset=11, portable=False):
    kwargs = dict(opset_version=opset, input_names=['input'], output_names=['logits'], do_constant_folding=True)
    if 'dynamo' in inspect.signature(torch.onnx.export).parameters:
        kwargs['dynamo'] = False   # torch 2.x: the classic TorchScript exporter (torch 1.13 has no such argument)
    with export_friendly(), torch.no_grad():
        torch.onnx.export(model.eval(), torch.zeros(1, 3, height, width), path, **kwargs)
    import onnx
    graph = inline_identity_initializers(path)
    if not portable:
        fuse_relu6_for_opencv(graph)
    onnx.save(graph, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--checkpoint')
    ap.add_argument('--out', required=True)
    ap.add_argument('--height', type=int, default=257, help='input height (16k+1), default 257')
    ap.add_argument('--width', type=int, default=337, help='input width (16k+1), default 337')
    ap.add_argument('--opset', type=int, default=11)
    ap.add_argument('--portable', action='store_true',
                    help='keep ReLU6 as relu(x) - relu(x - 6): valid ONNX for any runtime, 22 %% slower in OpenCV')
    ap.add_argument('--fuse-only', metavar='ONNX',
                    help='instead of exporting: fuse the ReLU6 of an exported model (--out gets the result)')
    args = ap.parse_args()
    import onnx
    if args.fuse_only:
        graph = onnx.load(args.fuse_only)
        print(f'fused {fuse_relu6_for_opencv(graph)} ReLU6')
        onnx.save(graph, args.out)
        return
    if not args.checkpoint:
        ap.error('--checkpoint is required (or --fuse-only ONNX)')
    model, _ = load_checkpoint_model(args.checkpoint)
    export(model, args.out, args.height, args.width, args.opset, args.portable)
    if args.portable:
        onnx.checker.check_model(onnx.load(args.out))
    ops = sorted({n.op_type for n in onnx.load(args.out).graph.node})
    print(f'wrote {args.out} ({os.path.getsize(args.out) / 1e6:.2f} MB), ops: {", ".join(ops)}')


if __name__ == '__main__':
    main()
