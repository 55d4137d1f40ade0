"""MobileNetV2 at output stride 16 (last stride-2 stage dilated), returning stride-4 and stride-16 features.

Weights load from two sources (see load_*): torchvision's layout (ImageNet classifier, BN kept) and the
converted DeepLab VOC teacher (BN folded into conv biases; mapped to conv + identity BN + bias)."""
import torch
import torch.nn as nn

from .layers import ConvBNAct


def make_divisible(v, divisor=8):
    new_v = max(divisor, int(v + divisor / 2) // divisor * divisor)
    if new_v < 0.9 * v:
        new_v += divisor
    return new_v


class InvertedResidual(nn.Module):
    def __init__(self, c_in, c_out, stride, dilation, expand_ratio):
        super().__init__()
        hidden = make_divisible(c_in * expand_ratio) if expand_ratio != 1 else c_in
        layers = [ConvBNAct(c_in, hidden, 1, act='relu6')] if expand_ratio != 1 else []
        layers += [ConvBNAct(hidden, hidden, 3, stride, dilation, groups=hidden, act='relu6'),
                   ConvBNAct(hidden, c_out, 1, act=None)]
        self.conv = nn.Sequential(*layers)
        self.use_res = stride == 1 and c_in == c_out

    def forward(self, x):
        y = self.conv(x)
        return x + y if self.use_res else y


class MobileNetV2Backbone(nn.Module):
    # (expand t, channels c, repeats n, stride s), as in the MobileNetV2 paper
    CFG = [(1, 16, 1, 1), (6, 24, 2, 2), (6, 32, 3, 2), (6, 64, 4, 2),
           (6, 96, 3, 1), (6, 160, 3, 2), (6, 320, 1, 1)]
    LOW_LEVEL_BLOCK = 2   # output of blocks[2] has stride 4

    def __init__(self, width_mult=1.0):
        super().__init__()
        # channel rounding of the source weights: multiples of 8 at width 1.0, of 4 for the 0.5 teacher
        div = 8 if width_mult >= 1.0 else 4
        c_in = make_divisible(32 * width_mult, div)
        self.stem = ConvBNAct(3, c_in, 3, 2, act='relu6')
        blocks, cur_stride, rate = [], 2, 1
        for t, c, n, s in self.CFG:
            c_out = make_divisible(c * width_mult, div)
            for i in range(n):
                stride, dil = (s if i == 0 else 1), rate
                if stride == 2 and cur_stride == 16:
                    stride, rate = 1, rate * 2   # output stride 16: dilate from here on
                else:
                    cur_stride *= stride
                blocks.append(InvertedResidual(c_in, c_out, stride, dil, t))
                c_in = c_out
        self.blocks = nn.Sequential(*blocks)
        self.low_level_channels = self.blocks[self.LOW_LEVEL_BLOCK].conv[-1][0].out_channels
        self.out_channels = c_in

    def forward(self, x):
        x = self.stem(x)
        low = None
        for i, b in enumerate(self.blocks):
            x = b(x)
            if i == self.LOW_LEVEL_BLOCK:
                low = x
        return low, x

    def conv_bn_units(self):
        """ConvBNAct units in forward order (the order both weight sources list their convs in)."""
        return [m for m in self.modules() if isinstance(m, ConvBNAct)]


def _set_identity_bn(bn, bias):
    bn.weight.data.fill_(1.0)
    bn.bias.data.copy_(bias)
    bn.running_mean.zero_()
    bn.running_var.fill_(1.0 - bn.eps)   # (x - 0) / sqrt(1 - eps + eps) = x exactly


def load_teacher_backbone(backbone, path):
    """Teacher state_dict (backbone.stem / backbone.blocks.N.{expand,depthwise,project}, folded BN)."""
    sd = torch.load(path, map_location='cpu')
    names = [k[:-len('.weight')] for k in sd if k.startswith('backbone.') and k.endswith('.weight')]
    units = backbone.conv_bn_units()
    if len(names) != len(units):
        raise ValueError(f'{path}: {len(names)} backbone convs, model has {len(units)}')
    for name, unit in zip(names, units):
        w = sd[name + '.weight']
        if w.shape != unit[0].weight.shape:
            raise ValueError(f'{path}: {name} has shape {tuple(w.shape)}, model {tuple(unit[0].weight.shape)}')
        unit[0].weight.data.copy_(w)
        _set_identity_bn(unit[1], sd[name + '.bias'])
    return len(units)


def load_torchvision_backbone(backbone, path):
    """torchvision mobilenet_v2 state_dict (features.*; BN tensors kept); features.18 and the classifier are unused."""
    sd = torch.load(path, map_location='cpu')
    conv_keys = [k for k in sd if k.startswith('features.') and k.endswith('.weight') and sd[k].dim() == 4]
    units = backbone.conv_bn_units()
    if len(conv_keys) < len(units):
        raise ValueError(f'{path}: {len(conv_keys)} convs, model needs {len(units)}')
    keys = list(sd)
    for ck, unit in zip(conv_keys, units):
        w = sd[ck]
        if w.shape != unit[0].weight.shape:
            raise ValueError(f'{path}: {ck} has shape {tuple(w.shape)}, model {tuple(unit[0].weight.shape)}')
        unit[0].weight.data.copy_(w)
        bn_prefix = keys[keys.index(ck) + 1].rsplit('.', 1)[0]   # the BN registered right after the conv
        for attr in ('weight', 'bias', 'running_mean', 'running_var'):
            getattr(unit[1], attr).data.copy_(sd[f'{bn_prefix}.{attr}'])
    return len(units)
