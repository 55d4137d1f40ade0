"""The paper's improved DeepLabv3+ (lightweight factorized ASPP) with MobileNetV2 or ResNeSt backbones."""
from .deeplabv3plus import DeepLabV3Plus, build_model, MODEL_PRESETS  # noqa: F401
from .layers import export_friendly  # noqa: F401
