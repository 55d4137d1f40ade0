#include "dlslam/synth/mesh.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace dlslam::synth {

int Mesh::AddVertex(const Eigen::Vector3f& p, const Eigen::Vector2f& uv) {
  positions.push_back(p);
  uvs.push_back(uv);
  return static_cast<int>(positions.size()) - 1;
}

void Mesh::AddTriangle(int a, int b, int c, int material) {
  triangles.push_back({a, b, c});
  triangle_materials.push_back(material);
}

void Mesh::Append(const Mesh& other) {
  const int base = static_cast<int>(positions.size());
  positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  uvs.insert(uvs.end(), other.uvs.begin(), other.uvs.end());
  for (const auto& t : other.triangles) triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  triangle_materials.insert(triangle_materials.end(), other.triangle_materials.begin(),
                            other.triangle_materials.end());
}

Eigen::Vector3f Mesh::BoundsMin() const {
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(INFINITY);
  for (const auto& p : positions) lo = lo.cwiseMin(p);
  return lo;
}

Eigen::Vector3f Mesh::BoundsMax() const {
  Eigen::Vector3f hi = Eigen::Vector3f::Constant(-INFINITY);
  for (const auto& p : positions) hi = hi.cwiseMax(p);
  return hi;
}

void AddQuad(Mesh& mesh, const Eigen::Vector3f& corner, const Eigen::Vector3f& edge_u,
             const Eigen::Vector3f& edge_v, int material, const Eigen::Vector2f& uv_offset,
             float tile) {
  const float len_u = edge_u.norm();
  const float len_v = edge_v.norm();
  const int nu = std::max(1, static_cast<int>(std::ceil(len_u / tile)));
  const int nv = std::max(1, static_cast<int>(std::ceil(len_v / tile)));
  const int base = static_cast<int>(mesh.positions.size());
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i <= nu; ++i) {
      const float s = static_cast<float>(i) / nu;
      const float t = static_cast<float>(j) / nv;
      // v runs from the far end of edge_v back to the corner: walls built with
      // edge_v pointing up show their textures upright (image rows run down).
      mesh.AddVertex(corner + s * edge_u + t * edge_v,
                     uv_offset + Eigen::Vector2f(s * len_u, (1 - t) * len_v));
    }
  }
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const int a = base + j * (nu + 1) + i;
      const int b = a + 1;
      const int c = a + nu + 1;
      const int d = c + 1;
      mesh.AddTriangle(a, b, d, material);
      mesh.AddTriangle(a, d, c, material);
    }
  }
}

void AddBox(Mesh& mesh, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi,
            const std::array<int, 6>& materials, const Eigen::Vector2f& uv_offset, bool inward) {
  const Eigen::Vector3f d = hi - lo;
  const Eigen::Vector3f ex(d.x(), 0, 0), ey(0, d.y(), 0), ez(0, 0, d.z());
  // Each face as (corner, edge_u, edge_v) with edge_u x edge_v pointing out.
  struct Face {
    Eigen::Vector3f corner, eu, ev;
  };
  const Face faces[6] = {
      {lo + ey, -ey, ez},       // -x
      {lo + ex, ey, ez},        // +x
      {lo, ex, ez},             // -y
      {lo + ex + ey, -ex, ez},  // +y
      {lo + ey, ex, -ey},       // -z
      {lo + ez, ex, ey},        // +z
  };
  for (int f = 0; f < 6; ++f) {
    if (materials[f] < 0) continue;  // open side
    const Eigen::Vector2f offset = uv_offset + Eigen::Vector2f(0.37f * f, 0.61f * f);
    if (inward) {
      AddQuad(mesh, faces[f].corner + faces[f].eu, -faces[f].eu, faces[f].ev, materials[f], offset);
    } else {
      AddQuad(mesh, faces[f].corner, faces[f].eu, faces[f].ev, materials[f], offset);
    }
  }
}

void AddCapsule(Mesh& mesh, float radius_x, float radius_y, float length, float cap, int material,
                int segments, int cap_rings) {
  // Rings from the top cap's pole down to the bottom cap's pole: (z, scale of
  // the cross-section).
  std::vector<std::pair<float, float>> rings;
  const float half_pi = std::numbers::pi_v<float> / 2;
  for (int k = 0; k <= cap_rings; ++k) {
    const float a = half_pi * static_cast<float>(cap_rings - k) / cap_rings;  // pi/2 .. 0
    rings.emplace_back(cap * std::sin(a), std::cos(a));
  }
  for (int k = 0; k <= cap_rings; ++k) {
    const float a = half_pi * static_cast<float>(k) / cap_rings;  // 0 .. pi/2
    rings.emplace_back(-length - cap * std::sin(a), std::cos(a));
  }
  const float mean_radius = 0.5f * (radius_x + radius_y);
  const float circumference = 2 * std::numbers::pi_v<float> * mean_radius;
  const int base = static_cast<int>(mesh.positions.size());
  for (const auto& [z, scale] : rings) {
    for (int s = 0; s <= segments; ++s) {  // duplicated seam column for u wrap
      const float phi = 2 * std::numbers::pi_v<float> * static_cast<float>(s) / segments;
      // Starting at -x puts the texture seam at the back (u = C/2 faces +x).
      const Eigen::Vector3f p(-radius_x * scale * std::cos(phi), -radius_y * scale * std::sin(phi), z);
      mesh.AddVertex(p, Eigen::Vector2f(circumference * static_cast<float>(s) / segments, cap - z));
    }
  }
  const int row = segments + 1;
  for (int r = 0; r + 1 < static_cast<int>(rings.size()); ++r) {
    for (int s = 0; s < segments; ++s) {
      const int a = base + r * row + s;
      const int b = a + 1;
      const int c = a + row;
      const int d = c + 1;
      // Rings run downwards and phi counter-clockwise seen from +z, so
      // (a, c, b) and (b, c, d) face outwards. Pole triangles are degenerate.
      if (rings[r].second > 1e-6f) mesh.AddTriangle(a, c, b, material);
      if (rings[r + 1].second > 1e-6f) mesh.AddTriangle(b, c, d, material);
    }
  }
}

}  // namespace dlslam::synth
