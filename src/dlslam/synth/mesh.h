#pragma once
// Triangle meshes of the synthetic scene. Texture coordinates are metres on
// the surface (u across, v along), so a material's texel density is its own
// pixels-per-metre and nothing stretches with the object's size.

#include <Eigen/Core>

#include <array>
#include <vector>

namespace dlslam::synth {

struct Mesh {
  std::vector<Eigen::Vector3f> positions;  // [m], object frame
  std::vector<Eigen::Vector2f> uvs;        // [m] on the surface, one per position
  // Counter-clockwise seen from the side the surface faces (its outside).
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> triangle_materials;  // index into Scene::materials, one per triangle

  int AddVertex(const Eigen::Vector3f& p, const Eigen::Vector2f& uv);
  void AddTriangle(int a, int b, int c, int material);
  // Appends `other` unchanged (same frame).
  void Append(const Mesh& other);
  // Corners of the axis-aligned bounding box of the positions.
  Eigen::Vector3f BoundsMin() const;
  Eigen::Vector3f BoundsMax() const;
};

// A rectangle `corner + s * edge_u + t * edge_v`, s, t in [0, 1], facing
// edge_u x edge_v, with u along edge_u and v running against edge_v (so a
// quad whose edge_v points up shows its texture upright), split into tiles of at most `tile` metres so that no
// triangle becomes huge on screen (float precision, near-plane clipping).
// uv_offset shifts the texture coordinates (distinct patches of one texture).
void AddQuad(Mesh& mesh, const Eigen::Vector3f& corner, const Eigen::Vector3f& edge_u,
             const Eigen::Vector3f& edge_v, int material,
             const Eigen::Vector2f& uv_offset = Eigen::Vector2f::Zero(), float tile = 1.0f);

// An axis-aligned box [lo, hi] facing outwards (inwards when `inward`, for a
// room). `materials`: -x, +x, -y, +y, -z, +z faces.
void AddBox(Mesh& mesh, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi,
            const std::array<int, 6>& materials, const Eigen::Vector2f& uv_offset = {0, 0},
            bool inward = false);

// A capsule along -z from the origin: elliptic cross-section with radii
// (radius_x, radius_y), straight part of length `length` between two
// half-ellipsoid caps of depth `cap`. u runs around (metres of the mean
// circumference C, from -x, so the seam is at the back and u = C/2 faces +x),
// v down along the axis from the top pole.
void AddCapsule(Mesh& mesh, float radius_x, float radius_y, float length, float cap, int material,
                int segments = 12, int cap_rings = 3);

}  // namespace dlslam::synth
