#include "dlslam/map/map_file.h"

#include <fmt/format.h>

#include <bit>
#include <cstring>
#include <type_traits>

#include "dlslam/io/file_util.h"
#include "dlslam/util/check.h"
#include "dlslam/util/crc32.h"

namespace dlslam {

namespace {

static_assert(std::endian::native == std::endian::little, "map files are written in the host's byte order");

constexpr char kMagic[8] = {'D', 'L', 'S', 'L', 'A', 'M', 'M', 'P'};
constexpr std::size_t kHeaderBytes = 24;
constexpr std::uintmax_t kMaxMapFileBytes = 1ull << 34;  // 16 GiB
// Bounds that a sane map never reaches; a count beyond them is a corrupt file.
constexpr std::uint64_t kMaxKeypoints = 1u << 20;
constexpr std::uint64_t kMaxName = 4096;
constexpr int kDescriptorBytes = 32;

class Writer {
 public:
  template <class T>
  void Put(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const std::size_t at = out_.size();
    out_.resize(at + sizeof(T));
    std::memcpy(out_.data() + at, &value, sizeof(T));
  }
  void PutBytes(const void* data, std::size_t n) { out_.append(static_cast<const char*>(data), n); }
  void PutString(const std::string& s) {
    Put<std::uint32_t>(static_cast<std::uint32_t>(s.size()));
    PutBytes(s.data(), s.size());
  }
  void PutPose(const SE3d& pose) {
    const Eigen::Quaterniond& q = pose.so3().quaternion();
    for (double v : {q.x(), q.y(), q.z(), q.w()}) Put(v);
    for (int i = 0; i < 3; ++i) Put(pose.translation()[i]);
  }
  void PutVector(const Eigen::Vector3d& v) {
    for (int i = 0; i < 3; ++i) Put(v[i]);
  }
  std::string& bytes() { return out_; }

 private:
  std::string out_;
};

class Reader {
 public:
  Reader(std::string_view bytes, std::size_t offset, const std::filesystem::path& file)
      : bytes_(bytes), at_(offset), file_(file) {}

  template <class T>
  T Get(const char* what) {
    static_assert(std::is_trivially_copyable_v<T>);
    Need(sizeof(T), what);
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  const char* Take(std::size_t n, const char* what) {
    Need(n, what);
    const char* p = bytes_.data() + at_;
    at_ += n;
    return p;
  }
  std::uint64_t Count(std::uint64_t max, const char* what) {
    const std::size_t at = at_;
    const auto n = Get<std::uint64_t>(what);
    if (n > max) throw InputError(file_, 0, "{} count {} at offset {} is over {}: the file is corrupt", what, n, at, max);
    return n;
  }
  std::string GetString(const char* what) {
    const auto n = Get<std::uint32_t>(what);
    if (n > kMaxName) throw InputError(file_, 0, "{} of {} bytes at offset {}: the file is corrupt", what, n, at_ - 4);
    return std::string(Take(n, what), n);
  }
  SE3d GetPose(const char* what) {
    const std::size_t at = at_;
    double q[4], t[3];
    for (double& v : q) v = Get<double>(what);
    for (double& v : t) v = Get<double>(what);
    const Eigen::Quaterniond quaternion(q[3], q[0], q[1], q[2]);
    const double norm = quaternion.norm();
    if (!std::isfinite(norm) || std::abs(norm - 1.0) > 1e-6 || !Eigen::Vector3d(t[0], t[1], t[2]).allFinite()) {
      throw InputError(file_, 0, "{} at offset {} is not a pose (quaternion norm {}): the file is corrupt", what, at,
                       norm);
    }
    return SE3d(quaternion, Eigen::Vector3d(t[0], t[1], t[2]));
  }
  Eigen::Vector3d GetVector(const char* what) {
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) v[i] = Get<double>(what);
    return v;
  }
  std::size_t offset() const { return at_; }

 private:
  void Need(std::size_t n, const char* what) {
    if (bytes_.size() - at_ < n) {
      throw InputError(file_, 0, "truncated: {} needs {} bytes at offset {}, the payload ends at {}", what, n, at_,
                       bytes_.size());
    }
  }

  std::string_view bytes_;
  std::size_t at_;
  const std::filesystem::path& file_;
};

void PutCamera(Writer& w, const CameraIntrinsics& c, const ScalePyramid& pyramid) {
  w.PutString(c.name);
  w.Put<std::int32_t>(c.width);
  w.Put<std::int32_t>(c.height);
  for (double v : {c.fx, c.fy, c.cx, c.cy, c.k1, c.k2, c.p1, c.p2, c.k3, c.depth_factor, c.bf}) w.Put(v);
  w.Put<std::int32_t>(pyramid.levels);
  w.Put(pyramid.scale_factor);
}

MapFileHeader GetCamera(Reader& r, const std::filesystem::path& file) {
  MapFileHeader h;
  const std::size_t at = r.offset();
  CameraIntrinsics& c = h.camera;
  c.name = r.GetString("camera name");
  c.width = r.Get<std::int32_t>("camera width");
  c.height = r.Get<std::int32_t>("camera height");
  for (double* v : {&c.fx, &c.fy, &c.cx, &c.cy, &c.k1, &c.k2, &c.p1, &c.p2, &c.k3, &c.depth_factor, &c.bf}) {
    *v = r.Get<double>("camera intrinsics");
  }
  h.pyramid.levels = r.Get<std::int32_t>("pyramid levels");
  h.pyramid.scale_factor = r.Get<double>("pyramid scale");
  try {
    c.Check();
    h.pyramid.Check();
  } catch (const Error& e) {
    throw InputError(file, 0, "the camera at offset {} is not one: {}", at, e.what());
  }
  return h;
}

void PutKeyFrame(Writer& w, const KeyFrame& kf) {
  const Frame& f = *kf.frame;
  w.Put(kf.id);
  w.Put(f.timestamp());
  w.PutPose(kf.cam_from_world);
  w.Put(kf.parent);
  w.Put<std::uint64_t>(f.size());
  for (const FrameKeypoint& k : f.keypoints()) {
    w.Put(k.uv.x());
    w.Put(k.uv.y());
    w.Put(k.raw_uv.x());
    w.Put(k.raw_uv.y());
    w.Put(k.depth);
    w.Put(k.right_u);
    w.Put<std::int32_t>(k.octave);
    w.Put(k.angle);
    w.Put(k.response);
  }
  for (std::size_t i = 0; i < f.size(); ++i) w.PutBytes(f.descriptor(i), kDescriptorBytes);
  for (MapPointId p : kf.points) w.Put(p);
  w.Put<std::uint64_t>(kf.covisibility.size());
  for (const auto& [other, shared] : kf.covisibility) {
    w.Put(other);
    w.Put<std::int32_t>(shared);
  }
  w.Put<std::uint64_t>(kf.loop_edges.size());
  for (KeyFrameId other : kf.loop_edges) w.Put(other);
}

KeyFrame GetKeyFrame(Reader& r, const MapFileHeader& h, std::uint64_t max_keyframes,
                     const std::filesystem::path& file) {
  KeyFrame kf;
  kf.id = r.Get<std::uint64_t>("keyframe id");
  const double timestamp = r.Get<double>("keyframe timestamp");
  kf.cam_from_world = r.GetPose("keyframe pose");
  kf.parent = r.Get<std::uint64_t>("keyframe parent");
  const std::size_t keypoints_at = r.offset();
  const std::uint64_t n = r.Count(kMaxKeypoints, "keypoint");
  std::vector<FrameKeypoint> keypoints(n);
  for (FrameKeypoint& k : keypoints) {
    k.uv.x() = r.Get<double>("keypoint");
    k.uv.y() = r.Get<double>("keypoint");
    k.raw_uv.x() = r.Get<float>("keypoint");
    k.raw_uv.y() = r.Get<float>("keypoint");
    k.depth = r.Get<double>("keypoint");
    k.right_u = r.Get<double>("keypoint");
    k.octave = r.Get<std::int32_t>("keypoint");
    k.angle = r.Get<float>("keypoint");
    k.response = r.Get<float>("keypoint");
    if (!k.uv.allFinite() || !k.raw_uv.allFinite() || !std::isfinite(k.depth) || k.depth < 0 ||
        !std::isfinite(k.right_u) || k.octave < 0 || k.octave >= h.pyramid.levels) {
      throw InputError(file, 0, "keyframe {}: a keypoint in the block at offset {} is not one (octave {}, depth {})",
                       kf.id, keypoints_at, k.octave, k.depth);
    }
  }
  cv::Mat descriptors(static_cast<int>(n), kDescriptorBytes, CV_8UC1);
  if (n > 0) std::memcpy(descriptors.data, r.Take(n * kDescriptorBytes, "descriptors"), n * kDescriptorBytes);
  kf.points.resize(n);
  for (MapPointId& p : kf.points) p = r.Get<std::uint64_t>("keypoint's map point");
  const std::uint64_t covisible = r.Count(max_keyframes, "covisibility edge");
  for (std::uint64_t i = 0; i < covisible; ++i) {
    const auto other = r.Get<std::uint64_t>("covisibility edge");
    kf.covisibility[other] = r.Get<std::int32_t>("covisibility edge");
  }
  const std::uint64_t loops = r.Count(max_keyframes, "loop edge");
  for (std::uint64_t i = 0; i < loops; ++i) kf.loop_edges.insert(r.Get<std::uint64_t>("loop edge"));
  kf.frame = std::make_shared<const Frame>(
      Frame::FromKeypoints(timestamp, std::move(keypoints), std::move(descriptors), h.camera, h.pyramid));
  return kf;
}

void PutPoint(Writer& w, const MapPoint& p) {
  w.Put(p.id);
  w.PutVector(p.position);
  w.PutBytes(p.descriptor.data(), p.descriptor.size());
  w.PutVector(p.normal);
  w.Put(p.min_distance);
  w.Put(p.max_distance);
  w.Put(p.reference_keyframe);
  w.Put(p.first_keyframe);
  w.Put<std::int32_t>(p.times_visible);
  w.Put<std::int32_t>(p.times_found);
  w.Put<std::uint64_t>(p.observations.size());
  for (const auto& [kf, keypoint] : p.observations) {
    w.Put(kf);
    w.Put<std::int32_t>(keypoint);
  }
}

MapPoint GetPoint(Reader& r, std::uint64_t max_keyframes) {
  MapPoint p;
  p.id = r.Get<std::uint64_t>("point id");
  p.position = r.GetVector("point position");
  std::memcpy(p.descriptor.data(), r.Take(p.descriptor.size(), "point descriptor"), p.descriptor.size());
  p.normal = r.GetVector("point normal");
  p.min_distance = r.Get<double>("point distances");
  p.max_distance = r.Get<double>("point distances");
  p.reference_keyframe = r.Get<std::uint64_t>("point reference keyframe");
  p.first_keyframe = r.Get<std::uint64_t>("point first keyframe");
  p.times_visible = r.Get<std::int32_t>("point counters");
  p.times_found = r.Get<std::int32_t>("point counters");
  const std::uint64_t n = r.Count(max_keyframes, "observation");
  for (std::uint64_t i = 0; i < n; ++i) {
    const auto kf = r.Get<std::uint64_t>("observation");
    p.observations[kf] = r.Get<std::int32_t>("observation");
  }
  return p;
}

}  // namespace

std::string SerializeMap(const MapContents& contents, const MapFileHeader& header) {
  Writer w;
  w.PutBytes(kMagic, sizeof kMagic);
  w.Put<std::uint32_t>(kMapFileVersion);
  w.Put<std::uint32_t>(0);
  w.Put<std::uint64_t>(0);  // payload size, set below
  PutCamera(w, header.camera, header.pyramid);
  w.Put(contents.next_keyframe_id);
  w.Put(contents.next_point_id);
  w.Put<std::uint64_t>(contents.keyframes.size());
  for (const KeyFrame& kf : contents.keyframes) PutKeyFrame(w, kf);
  w.Put<std::uint64_t>(contents.points.size());
  for (const MapPoint& p : contents.points) PutPoint(w, p);
  w.Put<std::uint64_t>(contents.culled.size());
  for (const CulledKeyFrame& c : contents.culled) {
    w.Put(c.id);
    w.Put(c.parent);
    w.PutPose(c.cam_from_parent);
  }
  w.Put<std::uint64_t>(contents.anchors.size());
  for (KeyFrameId a : contents.anchors) w.Put(a);
  std::string& out = w.bytes();
  const std::uint64_t payload = out.size() - kHeaderBytes;
  std::memcpy(out.data() + 16, &payload, sizeof payload);
  const std::uint32_t crc = Crc32(std::string_view(out));
  out.append(reinterpret_cast<const char*>(&crc), sizeof crc);
  return out;
}

MapFileHeader ParseMap(std::string_view bytes, const std::filesystem::path& file, Map* map) {
  DLSLAM_CHECK(map != nullptr);
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
    throw InputError(file, 0, "not a DLSLAM map (offset 0: magic \"DLSLAMMP\" expected)");
  }
  if (bytes.size() < kHeaderBytes + 4) throw InputError(file, 0, "truncated: {} bytes, the header alone is {}", bytes.size(), kHeaderBytes + 4);
  std::uint32_t version = 0;
  std::memcpy(&version, bytes.data() + 8, sizeof version);
  if (version != kMapFileVersion && version != 1) {
    throw InputError(file, 0, "unsupported map version {} (offset 8); this build reads versions 1 to {}", version,
                     kMapFileVersion);
  }
  std::uint64_t payload = 0;
  std::memcpy(&payload, bytes.data() + 16, sizeof payload);
  if (payload > bytes.size() || bytes.size() - 4 - kHeaderBytes < payload) {
    throw InputError(file, 0, "truncated: {} bytes, the header (offset 16) announces a payload of {}", bytes.size(),
                     payload);
  }
  if (bytes.size() != kHeaderBytes + payload + 4) {
    throw InputError(file, 0, "{} bytes after the checksum at offset {}", bytes.size() - (kHeaderBytes + payload + 4),
                     kHeaderBytes + payload);
  }
  std::uint32_t stored = 0;
  std::memcpy(&stored, bytes.data() + kHeaderBytes + payload, sizeof stored);
  const std::uint32_t crc = Crc32(bytes.substr(0, kHeaderBytes + payload));
  if (crc != stored) {
    throw InputError(file, 0, "checksum mismatch (stored {:08x} at offset {}, computed {:08x}): the file is corrupt",
                     stored, kHeaderBytes + payload, crc);
  }
  Reader r(bytes.substr(0, kHeaderBytes + payload), kHeaderBytes, file);
  const MapFileHeader header = GetCamera(r, file);
  MapContents contents;
  contents.next_keyframe_id = r.Get<std::uint64_t>("next keyframe id");
  contents.next_point_id = r.Get<std::uint64_t>("next point id");
  // Each record takes at least 8 bytes: counts beyond the payload are corrupt.
  const std::uint64_t max_records = payload / 8;
  const std::uint64_t keyframes = r.Count(max_records, "keyframe");
  contents.keyframes.reserve(keyframes);
  for (std::uint64_t i = 0; i < keyframes; ++i) contents.keyframes.push_back(GetKeyFrame(r, header, keyframes, file));
  const std::uint64_t points = r.Count(max_records, "map point");
  contents.points.reserve(points);
  for (std::uint64_t i = 0; i < points; ++i) contents.points.push_back(GetPoint(r, keyframes));
  const std::uint64_t culled = r.Count(max_records, "culled keyframe");
  for (std::uint64_t i = 0; i < culled; ++i) {
    CulledKeyFrame c;
    c.id = r.Get<std::uint64_t>("culled keyframe");
    c.parent = r.Get<std::uint64_t>("culled keyframe");
    c.cam_from_parent = r.GetPose("culled keyframe pose");
    contents.culled.push_back(c);
  }
  if (version >= 2) {
    const std::uint64_t anchors = r.Count(max_records, "anchor");
    for (std::uint64_t i = 0; i < anchors; ++i) contents.anchors.push_back(r.Get<std::uint64_t>("anchor"));
  }
  if (r.offset() != kHeaderBytes + payload) {
    throw InputError(file, 0, "{} unread bytes at offset {} before the checksum", kHeaderBytes + payload - r.offset(),
                     r.offset());
  }
  try {
    map->Import(std::move(contents));
  } catch (const InputError&) {
    throw;
  } catch (const Error& e) {
    throw InputError(file, 0, "{}", e.what());
  }
  return header;
}

void SaveMap(const Map& map, const MapFileHeader& header, const std::filesystem::path& file) {
  const std::string bytes = SerializeMap(map.Export(), header);
  io::WriteFileAtomically(file, [&](std::ostream& out) { out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
}

MapFileHeader LoadMap(const std::filesystem::path& file, Map* map) {
  const std::string bytes = io::ReadFileBytes(file, kMaxMapFileBytes, "a map file");
  return ParseMap(bytes, file, map);
}

}  // namespace dlslam
