#pragma once
// The synthetic world: a textured room with furniture (static, world frame),
// the actors that move through it, and where the camera starts.
// World frame: x right, y into the room, z up, floor at z = 0, metres.

#include <Eigen/Geometry>

#include <cstdint>
#include <random>
#include <vector>

#include "dlslam/geometry/se3.h"
#include "dlslam/synth/actors.h"
#include "dlslam/synth/mesh.h"
#include "dlslam/synth/preset.h"
#include "dlslam/synth/texture.h"
#include "dlslam/synth/texture_styles.h"

namespace dlslam::synth {

struct SceneOptions {
  bool ceiling = true;  // close the room at the top (else nothing is drawn there)
  void Check() const {}
};

struct Scene {
  std::vector<Texture> textures;
  std::vector<Material> materials;
  Mesh static_mesh;  // room and furniture, world frame
  std::vector<Actor> actors;
  Eigen::AlignedBox3d room;                    // inside of the walls [m]
  std::vector<Eigen::AlignedBox3d> obstacles;  // furniture the camera must stay out of
  SE3d viewpoint;                              // world_from_cam where the camera path starts
  Eigen::Vector3d light_direction{0.3, -0.5, 1.0};  // towards the light (normalised on use)

  int AddTexture(TextureStyle style, int width, int height, double texels_per_metre, std::mt19937& rng);
  // A material on `texture` with a random offset (objects sharing a texture
  // show different patches of it) and an optional tint.
  int AddMaterial(int texture, std::mt19937& rng, float tint = 1.0f);
};

// world_from_cam where a preset's camera path starts: (0, 0, 1.45 m) looking
// along +y, pitched down 12 degrees; the loop preset starts on its circle,
// room::kLoopRadius beyond room::kLoopCentre along +y, looking the same way.
SE3d PresetViewpoint(Preset preset);

// Builds the scene of `preset`; deterministic in `seed`.
Scene BuildScene(Preset preset, std::uint32_t seed, const SceneOptions& options = {});

// True when `p` is inside the room and outside every obstacle, with `margin` [m] to spare.
bool InFreeSpace(const Scene& scene, const Eigen::Vector3d& p, double margin);

}  // namespace dlslam::synth
