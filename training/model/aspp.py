"""ASPP heads: the paper's improved (factorized, depthwise-separable, rates 4/8/12/16) and the original."""
import torch
import torch.nn as nn
import torch.nn.functional as F

from .layers import ConvBNAct


class ImagePooling(nn.Module):
    """Global average pool -> 1x1 conv (bias) -> ReLU -> broadcast back to the input size.
    No BatchNorm here: on a 1x1 map it would normalise over the batch only (unstable at batch 4-8)."""

    def __init__(self, c_in, c_out):
        super().__init__()
        self.pool = nn.AdaptiveAvgPool2d(1)
        self.conv = nn.Conv2d(c_in, c_out, 1, bias=True)

    def forward(self, x):
        y = F.relu(self.conv(self.pool(x)))
        # nearest 1x1 -> HxW is a broadcast; exports to an ONNX Resize that OpenCV 4.6 reads
        return F.interpolate(y, size=x.shape[-2:], mode='nearest')


class FactorizedAtrousBranch(nn.Module):
    """Depthwise 3x1 (dilation d) -> depthwise 1x3 (dilation d) -> pointwise 1x1 -> BN -> ReLU."""

    def __init__(self, c_in, c_out, dilation):
        super().__init__()
        d = dilation
        self.dw_3x1 = nn.Conv2d(c_in, c_in, (3, 1), padding=(d, 0), dilation=(d, 1), groups=c_in, bias=False)
        self.dw_1x3 = nn.Conv2d(c_in, c_in, (1, 3), padding=(0, d), dilation=(1, d), groups=c_in, bias=False)
        self.pointwise = ConvBNAct(c_in, c_out, 1, act='relu')

    def forward(self, x):
        return self.pointwise(self.dw_1x3(self.dw_3x1(x)))


class _ASPPBase(nn.Module):
    def __init__(self, branches, c_in, c_out, dropout):
        super().__init__()
        self.branches = nn.ModuleList([ConvBNAct(c_in, c_out, 1, act='relu')] + branches)
        self.image_pool = ImagePooling(c_in, c_out)
        n = len(self.branches) + 1
        self.project = ConvBNAct(n * c_out, c_out, 1, act='relu')
        self.dropout = nn.Dropout(dropout)
        self.out_channels = c_out

    def forward(self, x):
        maps = [b(x) for b in self.branches] + [self.image_pool(x)]
        return self.dropout(self.project(torch.cat(maps, dim=1)))


class ImprovedASPP(_ASPPBase):
    """The paper's head: 1x1, four factorized depthwise-separable atrous branches, image pooling: 6 maps."""

    def __init__(self, c_in, c_out=256, rates=(4, 8, 12, 16), dropout=0.1):
        super().__init__([FactorizedAtrousBranch(c_in, c_out, r) for r in rates], c_in, c_out, dropout)


class OriginalASPP(_ASPPBase):
    """DeepLabv3's head: 1x1, three full 3x3 atrous convs (rates 6/12/18), image pooling: 5 maps."""

    def __init__(self, c_in, c_out=256, rates=(6, 12, 18), dropout=0.1):
        super().__init__([ConvBNAct(c_in, c_out, 3, dilation=r, act='relu') for r in rates],
                         c_in, c_out, dropout)


def build_aspp(kind, c_in, c_out):
    if kind == 'improved':
        return ImprovedASPP(c_in, c_out)
    if kind == 'original':
        return OriginalASPP(c_in, c_out)
    raise ValueError(f'unknown ASPP kind {kind!r} (improved | original)')
