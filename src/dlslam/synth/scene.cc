#include "dlslam/synth/scene.h"

#include <array>
#include <cmath>
#include <numbers>

#include "dlslam/synth/random.h"
#include "dlslam/synth/room.h"
#include "dlslam/synth/walker_routes.h"

namespace dlslam::synth {

namespace {

constexpr std::uint32_t kSceneStream = 1;

// A person's clothes and skin: textures sized so that one texture width wraps
// exactly once around the torso, legs and head.
PersonLook RandomLook(Scene& s, std::mt19937& rng) {
  PersonLook look;
  look.height = static_cast<float>(Uniform(rng, 1.62, 1.9));
  look.girth = static_cast<float>(Uniform(rng, 0.9, 1.15));
  look.long_sleeves = Uniform01(rng) < 0.6;
  const double pi2 = 2 * std::numbers::pi;
  const double torso_c = pi2 * 0.145 * look.girth * look.height / 1.75;
  const double leg_c = pi2 * 0.075 * look.girth * look.height / 1.75;
  const double head_c = pi2 * 0.0875 * look.height / 1.75;
  auto material = [&](TextureStyle style, int size, double circumference) {
    const int texture = s.AddTexture(style, size, size, size / circumference, rng);
    Material m;
    m.texture = texture;
    m.texels_per_metre = s.textures[static_cast<std::size_t>(texture)].texels_per_metre;
    s.materials.push_back(m);
    return static_cast<int>(s.materials.size()) - 1;
  };
  look.shirt = material(TextureStyle::kClothing, 512, torso_c);
  look.trousers = material(TextureStyle::kTrousers, 256, leg_c);
  look.head = material(TextureStyle::kHead, 256, head_c);
  look.skin = material(TextureStyle::kSkin, 128, 0.3);
  look.shoes = material(TextureStyle::kDevice, 128, 0.4);
  return look;
}

void AddWalkers(Scene& s, std::mt19937& rng) {
  // Routes first: their draws do not depend on how many the looks take.
  std::array<WalkerParams, 2> walkers = MakeWalkerPair(rng);
  walkers[1].box_material = s.AddMaterial(s.AddTexture(TextureStyle::kCardboard, 256, 256, 300, rng), rng);
  for (const WalkerParams& p : walkers) s.actors.push_back(MakeWalker(RandomLook(s, rng), p));
}

void AddSitters(Scene& s, std::mt19937& rng) {
  for (const auto& seat : {room::kSeatLeft, room::kSeatRight}) {
    SitterParams p;
    p.seat = seat;
    p.heading = -std::numbers::pi / 2;  // facing the camera (-y)
    p.seat_height = room::kSeatHeight;
    p.phase = Uniform(rng, 0.0, 2 * std::numbers::pi);
    for (double t = Uniform(rng, 1.0, 5.0); t < 900.0; t += Uniform(rng, 4.0, 10.0)) p.gesture_times.push_back(t);
    s.actors.push_back(MakeSitter(RandomLook(s, rng), p));
  }
  SlidingBoxParams box;
  box.offset_s = Uniform(rng, 0.0, 8.0);
  box.material = s.AddMaterial(s.AddTexture(TextureStyle::kCardboard, 256, 256, 400, rng), rng);
  s.actors.push_back(MakeSlidingBox(box));
}

}  // namespace

int Scene::AddTexture(TextureStyle style, int width, int height, double texels_per_metre, std::mt19937& rng) {
  textures.push_back(Texture::FromImage(MakeTextureImage(style, width, height, texels_per_metre, rng)));
  textures.back().texels_per_metre = static_cast<float>(texels_per_metre);
  return static_cast<int>(textures.size()) - 1;
}

int Scene::AddMaterial(int texture, std::mt19937& rng, float tint) {
  Material m;
  m.texture = texture;
  const Texture& t = textures[static_cast<std::size_t>(texture)];
  m.texels_per_metre = t.texels_per_metre;
  m.offset_x = static_cast<float>(Uniform(rng, 0, t.levels[0].cols));
  m.offset_y = static_cast<float>(Uniform(rng, 0, t.levels[0].rows));
  for (float& c : m.tint) c = tint;
  materials.push_back(m);
  return static_cast<int>(materials.size()) - 1;
}

SE3d PresetViewpoint(Preset preset) {
  const double p = room::kViewpointPitchDown;
  Eigen::Matrix3d R;  // columns: camera x (right), y (down), z (forward) in the world
  R.col(0) = Eigen::Vector3d::UnitX();
  R.col(2) = Eigen::Vector3d(0, std::cos(p), -std::sin(p));
  R.col(1) = R.col(2).cross(R.col(0));
  Eigen::Vector3d position = room::kViewpoint;
  if (preset == Preset::kLoop) position.head<2>() = room::kLoopCentre + Eigen::Vector2d(0, room::kLoopRadius);
  return SE3d(SO3d(R), position);
}

Scene BuildScene(Preset preset, std::uint32_t seed, const SceneOptions& options) {
  options.Check();
  Scene s;
  std::mt19937 rng = MakeRng(seed, kSceneStream);
  RoomOptions room_options;
  room_options.ceiling = options.ceiling;
  const bool walking = preset != Preset::kStatic && preset != Preset::kSittingStatic && preset != Preset::kKidnap &&
                       preset != Preset::kLoop;
  room_options.chairs_at_desk = !walking;
  room_options.desk_shift_y = walking ? room::kWalkingDeskShift : 0.0;
  BuildRoom(s, room_options, rng);
  s.viewpoint = PresetViewpoint(preset);
  switch (preset) {
    case Preset::kStatic:
    case Preset::kKidnap:
    case Preset::kLoop: break;
    case Preset::kSittingStatic: AddSitters(s, rng); break;
    case Preset::kWalkingXyz:
    case Preset::kWalkingRpy:
    case Preset::kWalkingHalfsphere:
    case Preset::kWalkingStatic: AddWalkers(s, rng); break;
  }
  return s;
}

bool InFreeSpace(const Scene& scene, const Eigen::Vector3d& p, double margin) {
  const Eigen::Vector3d m = Eigen::Vector3d::Constant(margin);
  if (!Eigen::AlignedBox3d(scene.room.min() + m, scene.room.max() - m).contains(p)) return false;
  for (const auto& box : scene.obstacles) {
    if (Eigen::AlignedBox3d(box.min() - m, box.max() + m).contains(p)) return false;
  }
  return true;
}

}  // namespace dlslam::synth
