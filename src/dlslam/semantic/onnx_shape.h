#pragma once
// The input size an ONNX file declares, read from its protobuf bytes without
// OpenCV (whose 4.6 importer offers no way to ask): so that a model exported
// at another size needs no size option beside it.

#include <optional>
#include <string_view>

namespace dlslam::semantic {

struct DeclaredSize {
  int height = 0;
  int width = 0;
};

// Height and width of the model's first real input (graph inputs that are
// initializers, as older exporters list them, are skipped) when it is a
// 4-D tensor N x C x H x W with fixed H and W. nullopt for symbolic or
// missing dimensions and for bytes that are not a well-formed ONNX model:
// never throws, never reads outside `onnx_bytes`.
std::optional<DeclaredSize> DeclaredInputSize(std::string_view onnx_bytes);

}  // namespace dlslam::semantic
