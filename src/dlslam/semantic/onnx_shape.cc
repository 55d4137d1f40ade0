#include "dlslam/semantic/onnx_shape.h"

#include <cstdint>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace dlslam::semantic {

namespace {

// The protobuf wire format, as far as reading a few nested fields needs it.
// Every read is bounds-checked; a malformed message ends the walk (ok = false).
class WireReader {
 public:
  explicit WireReader(std::string_view bytes) : bytes_(bytes) {}

  bool done() const { return pos_ >= bytes_.size() || !ok_; }
  bool ok() const { return ok_; }

  // The next field's number and wire type; false at the end or on garbage.
  bool Next(std::uint32_t* field, std::uint32_t* wire_type) {
    if (done()) return false;
    std::uint64_t key = 0;
    if (!Varint(&key) || key >> 3 == 0 || key >> 3 > std::numeric_limits<std::uint32_t>::max()) {
      return Fail();
    }
    *field = static_cast<std::uint32_t>(key >> 3);
    *wire_type = static_cast<std::uint32_t>(key & 7);
    return true;
  }
  bool Varint(std::uint64_t* value) {
    *value = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      if (pos_ >= bytes_.size()) return Fail();
      const auto byte = static_cast<std::uint8_t>(bytes_[pos_++]);
      *value |= static_cast<std::uint64_t>(byte & 0x7f) << shift;
      if ((byte & 0x80) == 0) return true;
    }
    return Fail();
  }
  bool Bytes(std::string_view* out) {
    std::uint64_t length = 0;
    if (!Varint(&length) || length > bytes_.size() - pos_) return Fail();
    *out = bytes_.substr(pos_, static_cast<std::size_t>(length));
    pos_ += static_cast<std::size_t>(length);
    return true;
  }
  // Skips a field of the given wire type (groups, long deprecated, are garbage here).
  bool Skip(std::uint32_t wire_type) {
    std::uint64_t ignored = 0;
    std::string_view ignored_bytes;
    switch (wire_type) {
      case 0: return Varint(&ignored);
      case 1: return Advance(8);
      case 2: return Bytes(&ignored_bytes);
      case 5: return Advance(4);
      default: return Fail();
    }
  }

 private:
  bool Advance(std::size_t n) {
    if (n > bytes_.size() - pos_) return Fail();
    pos_ += n;
    return true;
  }
  bool Fail() {
    ok_ = false;
    return false;
  }

  std::string_view bytes_;
  std::size_t pos_ = 0;
  bool ok_ = true;
};

constexpr std::uint32_t kLengthDelimited = 2;
constexpr std::uint32_t kVarint = 0;

// Field numbers of onnx.proto (ModelProto.graph, GraphProto.initializer /
// input, ValueInfoProto.name / type, TypeProto.tensor_type, Tensor.shape,
// TensorShapeProto.dim, Dimension.dim_value, TensorProto.name).
constexpr std::uint32_t kModelGraph = 7;
constexpr std::uint32_t kGraphInitializer = 5;
constexpr std::uint32_t kGraphInput = 11;
constexpr std::uint32_t kValueInfoName = 1;
constexpr std::uint32_t kValueInfoType = 2;
constexpr std::uint32_t kTypeTensor = 1;
constexpr std::uint32_t kTensorShape = 2;
constexpr std::uint32_t kShapeDim = 1;
constexpr std::uint32_t kDimValue = 1;
constexpr std::uint32_t kTensorProtoName = 8;

// The first length-delimited field `field` of `message`; nullopt if none.
std::optional<std::string_view> SubMessage(std::string_view message, std::uint32_t wanted) {
  WireReader reader(message);
  std::uint32_t field = 0, wire_type = 0;
  while (reader.Next(&field, &wire_type)) {
    if (field == wanted && wire_type == kLengthDelimited) {
      std::string_view sub;
      return reader.Bytes(&sub) ? std::optional(sub) : std::nullopt;
    }
    if (!reader.Skip(wire_type)) return std::nullopt;
  }
  return std::nullopt;
}

// A dimension's fixed value, or -1 (symbolic, missing, malformed).
std::int64_t DimValue(std::string_view dimension) {
  WireReader reader(dimension);
  std::uint32_t field = 0, wire_type = 0;
  while (reader.Next(&field, &wire_type)) {
    if (field == kDimValue && wire_type == kVarint) {
      std::uint64_t value = 0;
      if (!reader.Varint(&value) || value > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) return -1;
      return static_cast<std::int64_t>(value);
    }
    if (!reader.Skip(wire_type)) return -1;
  }
  return -1;
}

std::optional<DeclaredSize> SizeOfInput(std::string_view value_info) {
  const std::optional<std::string_view> type = SubMessage(value_info, kValueInfoType);
  const std::optional<std::string_view> tensor = type ? SubMessage(*type, kTypeTensor) : std::nullopt;
  const std::optional<std::string_view> shape = tensor ? SubMessage(*tensor, kTensorShape) : std::nullopt;
  if (!shape) return std::nullopt;
  std::vector<std::int64_t> dims;
  WireReader reader(*shape);
  std::uint32_t field = 0, wire_type = 0;
  while (reader.Next(&field, &wire_type)) {
    if (field == kShapeDim && wire_type == kLengthDelimited) {
      std::string_view dimension;
      if (!reader.Bytes(&dimension)) return std::nullopt;
      dims.push_back(DimValue(dimension));
    } else if (!reader.Skip(wire_type)) {
      return std::nullopt;
    }
  }
  if (!reader.ok() || dims.size() != 4 || dims[2] <= 0 || dims[3] <= 0) return std::nullopt;
  return DeclaredSize{static_cast<int>(dims[2]), static_cast<int>(dims[3])};
}

}  // namespace

std::optional<DeclaredSize> DeclaredInputSize(std::string_view onnx_bytes) {
  const std::optional<std::string_view> graph = SubMessage(onnx_bytes, kModelGraph);
  if (!graph) return std::nullopt;
  std::set<std::string, std::less<>> initializers;
  std::vector<std::string_view> inputs;
  WireReader reader(*graph);
  std::uint32_t field = 0, wire_type = 0;
  while (reader.Next(&field, &wire_type)) {
    if (wire_type == kLengthDelimited && (field == kGraphInitializer || field == kGraphInput)) {
      std::string_view message;
      if (!reader.Bytes(&message)) return std::nullopt;
      if (field == kGraphInput) {
        inputs.push_back(message);
      } else if (const std::optional<std::string_view> name = SubMessage(message, kTensorProtoName)) {
        initializers.emplace(*name);
      }
    } else if (!reader.Skip(wire_type)) {
      return std::nullopt;
    }
  }
  if (!reader.ok()) return std::nullopt;
  for (const std::string_view input : inputs) {
    const std::optional<std::string_view> name = SubMessage(input, kValueInfoName);
    if (name && initializers.count(*name) > 0) continue;
    return SizeOfInput(input);
  }
  return std::nullopt;
}

}  // namespace dlslam::semantic
