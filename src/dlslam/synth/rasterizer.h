#pragma once
// A small CPU rasteriser: triangles with a z-buffer into a G-buffer that
// keeps, per pixel, the inverse depth, the surface coordinates (u, v)
// (perspective-correct) and which triangle won. Shading, texturing and the
// ground-truth mask are then evaluated once per pixel from the same buffer
// (deferred), so overdraw costs only the depth test.

#include <Eigen/Core>

#include <vector>

#include "dlslam/data/camera.h"
#include "dlslam/synth/mesh.h"

namespace dlslam::synth {

// What the shading pass needs to know about a drawn triangle.
struct TriangleRecord {
  int material = 0;
  int label = 0;        // who owns it: 0 static, else a dynamic part (see Renderer)
  float shade = 1.0f;   // Lambert factor, flat per triangle
  float slant = 1.0f;   // |cos| between normal and viewing ray, >= 0.2 (texture mip choice)
};

struct GBuffer {
  int width = 0;
  int height = 0;
  std::vector<float> inv_depth;  // 1 / z [1/m]; 0 where nothing was drawn
  std::vector<float> u, v;       // surface coordinates [m]
  std::vector<int> triangle;     // index into `records`, -1 where nothing was drawn
  std::vector<TriangleRecord> records;

  void Reset(int w, int h);
};

struct RasterLight {
  Eigen::Vector3f direction_cam = Eigen::Vector3f(0, -1, 0);  // towards the light, camera frame, unit
  float ambient = 0.55f;                                       // [0, 1]
  float diffuse = 0.5f;                                        // [0, 1]
};

// Draws `mesh` posed by cam_from_object (rotation R, translation t) into
// `buffer`. Triangles facing away are culled (meshes are closed or seen from
// their front); parts in front of `near_m` are clipped. Pinhole projection
// without distortion, pixel centres at integer coordinates.
void RasterizeMesh(const Mesh& mesh, const Eigen::Matrix3f& R, const Eigen::Vector3f& t,
                   const CameraIntrinsics& camera, int label, const RasterLight& light, float near_m,
                   GBuffer& buffer);

}  // namespace dlslam::synth
