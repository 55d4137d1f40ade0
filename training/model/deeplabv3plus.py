"""DeepLabv3+ with the paper's improved ASPP; backbone and head chosen by a preset or by arguments."""
import torch
import torch.nn as nn
import torch.nn.functional as F

from .aspp import build_aspp
from .layers import ConvBNAct, SeparableConv
from .mobilenetv2 import MobileNetV2Backbone
from .resnest import ResNeStBackbone

# name -> constructor arguments. The default (mnv2_w05), trained at 257x337, is shipped exported at 209x273
# (< 30 ms per frame in cv2.dnn; docs/semantic.md, "Input size").
MODEL_PRESETS = {
    'mnv2_w05': dict(backbone='mobilenetv2', width_mult=0.5, aspp_channels=128, decoder_channels=64),
    'mnv2_w10': dict(backbone='mobilenetv2', width_mult=1.0, aspp_channels=256, decoder_channels=128),
    'resnest26_w05': dict(backbone='resnest', resnest_layers=(2, 2, 2, 2), resnest_width=32,
                          aspp_channels=256, decoder_channels=128),
}


class DeepLabV3Plus(nn.Module):
    def __init__(self, num_classes=3, backbone='mobilenetv2', width_mult=1.0, resnest_layers=(2, 2, 2, 2),
                 resnest_width=32, aspp='improved', aspp_channels=256, low_level_channels=48,
                 decoder_channels=256):
        super().__init__()
        if backbone == 'mobilenetv2':
            self.backbone = MobileNetV2Backbone(width_mult)
        elif backbone == 'resnest':
            self.backbone = ResNeStBackbone(resnest_layers, resnest_width)
        else:
            raise ValueError(f'unknown backbone {backbone!r} (mobilenetv2 | resnest)')
        self.aspp = build_aspp(aspp, self.backbone.out_channels, aspp_channels)
        self.low_level = ConvBNAct(self.backbone.low_level_channels, low_level_channels, 1, act='relu')
        self.decoder = nn.Sequential(
            SeparableConv(aspp_channels + low_level_channels, decoder_channels),
            SeparableConv(decoder_channels, decoder_channels))
        self.classifier = nn.Conv2d(decoder_channels, num_classes, 1)

    def forward(self, x):
        size = x.shape[-2:]
        low, high = self.backbone(x)
        # align_corners=True: with 16k+1 input sizes the stride-16/4/1 grids share their corners exactly
        y = F.interpolate(self.aspp(high), size=low.shape[-2:], mode='bilinear', align_corners=True)
        y = self.decoder(torch.cat([y, self.low_level(low)], dim=1))
        return F.interpolate(self.classifier(y), size=size, mode='bilinear', align_corners=True)


def build_model(preset='mnv2_w05', num_classes=3, **overrides):
    if preset not in MODEL_PRESETS:
        raise ValueError(f'unknown preset {preset!r}: {sorted(MODEL_PRESETS)}')
    args = dict(MODEL_PRESETS[preset])
    args.update({k: v for k, v in overrides.items() if v is not None})
    return DeepLabV3Plus(num_classes=num_classes, **args)
