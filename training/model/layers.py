"""Small building blocks shared by the backbones, the ASPP heads and the decoder."""
import contextlib

import torch.nn as nn
import torch.nn.functional as F

# OpenCV 4.6's ONNX importer rejects the opset-11 `Clip` node (min/max as inputs) that
# nn.ReLU6 / torch.clamp export to. While this flag is set (export time only), ReLU6 is
# written as relu(x) - relu(x - 6): identical values, exported as Relu/Sub nodes.
_EXPORT_FRIENDLY = False


@contextlib.contextmanager
def export_friendly():
    """Use ONNX/OpenCV-friendly forms of the activations inside this block."""
    global _EXPORT_FRIENDLY
    old, _EXPORT_FRIENDLY = _EXPORT_FRIENDLY, True
    try:
        yield
    finally:
        _EXPORT_FRIENDLY = old


class ReLU6(nn.Module):
    """min(max(x, 0), 6); see export_friendly() for why it is not nn.ReLU6."""

    def forward(self, x):
        if _EXPORT_FRIENDLY:
            return F.relu(x) - F.relu(x - 6.0)
        return F.relu6(x)


def make_act(kind):
    if kind == 'relu6':
        return ReLU6()
    if kind == 'relu':
        return nn.ReLU(inplace=True)
    if kind is None or kind == 'none':
        return nn.Identity()
    raise ValueError(f'unknown activation {kind!r}')


class ConvBNAct(nn.Sequential):
    """Conv2d (no bias) + BatchNorm2d + activation. Padding keeps the size for odd kernels."""

    def __init__(self, c_in, c_out, kernel=1, stride=1, dilation=1, groups=1, act='relu'):
        kh, kw = (kernel, kernel) if isinstance(kernel, int) else kernel
        pad = (dilation * (kh - 1) // 2, dilation * (kw - 1) // 2)
        super().__init__(
            nn.Conv2d(c_in, c_out, (kh, kw), stride, pad, dilation=dilation, groups=groups, bias=False),
            nn.BatchNorm2d(c_out),
            make_act(act))


class SeparableConv(nn.Sequential):
    """Depthwise 3x3 (BN, ReLU) then pointwise 1x1 (BN, ReLU): the DeepLabv3+ decoder conv."""

    def __init__(self, c_in, c_out, dilation=1):
        super().__init__(
            ConvBNAct(c_in, c_in, 3, dilation=dilation, groups=c_in, act='relu'),
            ConvBNAct(c_in, c_out, 1, act='relu'))


def count_parameters(module):
    return sum(p.numel() for p in module.parameters())
