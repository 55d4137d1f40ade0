"""A light ResNeSt (split attention, radix 2, cardinality 1, deep stem, avg-down), dilated to output stride 16.

Written from the ResNeSt paper (Zhang et al., 2020). Radix 2 / cardinality 1 only: the softmax over the two
splits is computed as sigmoid(a0 - a1), which is the same and exports to ONNX nodes OpenCV 4.6 reads."""
import torch
import torch.nn as nn

from .layers import ConvBNAct


class SplitAttentionConv(nn.Module):
    """3x3 conv producing radix=2 splits, fused by channel attention computed from their sum."""

    def __init__(self, channels, dilation=1):
        super().__init__()
        self.channels = channels
        self.conv = ConvBNAct(channels, 2 * channels, 3, dilation=dilation, groups=2, act='relu')
        inter = max(channels * 2 // 4, 32)
        self.pool = nn.AdaptiveAvgPool2d(1)
        self.fc1 = ConvBNAct(channels, inter, 1, act='relu')
        self.fc2 = nn.Conv2d(inter, 2 * channels, 1, bias=True)

    def forward(self, x):
        y = self.conv(x)
        c = self.channels
        s0, s1 = y[:, :c], y[:, c:]
        a = self.fc2(self.fc1(self.pool(s0 + s1)))
        w0 = torch.sigmoid(a[:, :c] - a[:, c:])   # softmax over the two splits
        return s1 + w0 * (s0 - s1)                # = w0 * s0 + (1 - w0) * s1


class Bottleneck(nn.Module):
    expansion = 4

    def __init__(self, c_in, planes, stride=1, dilation=1):
        super().__init__()
        c_out = planes * self.expansion
        self.conv1 = ConvBNAct(c_in, planes, 1, act='relu')
        self.splat = SplitAttentionConv(planes, dilation)
        # ResNeSt's "avd": the stride is taken by a 3x3 average pool after the split-attention conv
        self.avd = nn.AvgPool2d(3, stride, padding=1) if stride > 1 else nn.Identity()
        self.conv3 = ConvBNAct(planes, c_out, 1, act=None)
        if stride > 1 or c_in != c_out:
            # avg-down shortcut: average pool for the stride, then 1x1 conv
            pool = nn.AvgPool2d(stride, stride, ceil_mode=True, count_include_pad=False) if stride > 1 \
                else nn.Identity()
            self.shortcut = nn.Sequential(pool, ConvBNAct(c_in, c_out, 1, act=None))
        else:
            self.shortcut = nn.Identity()
        self.relu = nn.ReLU(inplace=True)

    def forward(self, x):
        y = self.conv3(self.avd(self.splat(self.conv1(x))))
        return self.relu(y + self.shortcut(x))


class ResNeStBackbone(nn.Module):
    """layers=(2,2,2,2) is ResNeSt-26; base_width 64 is the paper's width, 32 halves every channel count."""

    def __init__(self, layers=(2, 2, 2, 2), base_width=32):
        super().__init__()
        stem = base_width // 2
        self.stem = nn.Sequential(                       # deep stem: three 3x3 convs instead of one 7x7
            ConvBNAct(3, stem, 3, 2, act='relu'),
            ConvBNAct(stem, stem, 3, act='relu'),
            ConvBNAct(stem, 2 * stem, 3, act='relu'),
            nn.MaxPool2d(3, 2, padding=1))
        c_in = 2 * stem
        stages = []
        # (planes, stride, dilation): layer4 keeps stride 16 and dilates instead
        for i, (planes, stride, dil) in enumerate([(base_width, 1, 1), (2 * base_width, 2, 1),
                                                   (4 * base_width, 2, 1), (8 * base_width, 1, 2)]):
            blocks = []
            for j in range(layers[i]):
                blocks.append(Bottleneck(c_in, planes, stride if j == 0 else 1, dil))
                c_in = planes * Bottleneck.expansion
            stages.append(nn.Sequential(*blocks))
        self.layer1, self.layer2, self.layer3, self.layer4 = stages
        self.low_level_channels = base_width * Bottleneck.expansion
        self.out_channels = c_in

    def forward(self, x):
        low = self.layer1(self.stem(x))
        return low, self.layer4(self.layer3(self.layer2(low)))
