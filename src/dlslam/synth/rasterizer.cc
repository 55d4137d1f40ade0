#include "dlslam/synth/rasterizer.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace dlslam::synth {

namespace {

struct ClipVertex {
  Eigen::Vector3f p;  // camera frame [m]
  Eigen::Vector2f uv;
};

// Clips a convex polygon to z >= near (Sutherland-Hodgman, one plane).
int ClipNear(const ClipVertex* in, int n, float near_m, ClipVertex* out) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const ClipVertex& a = in[i];
    const ClipVertex& b = in[(i + 1) % n];
    const bool a_in = a.p.z() >= near_m;
    const bool b_in = b.p.z() >= near_m;
    if (a_in) out[m++] = a;
    if (a_in != b_in) {
      const float s = (near_m - a.p.z()) / (b.p.z() - a.p.z());
      out[m++] = {a.p + s * (b.p - a.p), a.uv + s * (b.uv - a.uv)};
    }
  }
  return m;
}

struct ScreenVertex {
  double x, y;     // pixel coordinates
  double iz;       // 1 / z
  double uz, vz;   // u / z, v / z (affine in screen space)
};

void DrawTriangle(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c, int record,
                  GBuffer& buf) {
  const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
  if (std::abs(area) < 1e-9) return;
  // Screen-space gradients of the affine attributes.
  auto gradient = [&](double va, double vb, double vc, double& ddx, double& ddy) {
    ddx = ((vb - va) * (c.y - a.y) - (vc - va) * (b.y - a.y)) / area;
    ddy = ((vc - va) * (b.x - a.x) - (vb - va) * (c.x - a.x)) / area;
  };
  double iz_dx, iz_dy, uz_dx, uz_dy, vz_dx, vz_dy;
  gradient(a.iz, b.iz, c.iz, iz_dx, iz_dy);
  gradient(a.uz, b.uz, c.uz, uz_dx, uz_dy);
  gradient(a.vz, b.vz, c.vz, vz_dx, vz_dy);
  const double ymin = std::min({a.y, b.y, c.y});
  const double ymax = std::max({a.y, b.y, c.y});
  const int y0 = std::max(0, static_cast<int>(std::ceil(ymin)));
  const int y1 = std::min(buf.height - 1, static_cast<int>(std::floor(ymax)));
  const ScreenVertex* v[3] = {&a, &b, &c};
  for (int y = y0; y <= y1; ++y) {
    // The span of this row: where the row crosses the triangle's edges.
    double xl = INFINITY, xr = -INFINITY;
    for (int e = 0; e < 3; ++e) {
      const ScreenVertex& p = *v[e];
      const ScreenVertex& q = *v[(e + 1) % 3];
      if ((y < p.y && y < q.y) || (y > p.y && y > q.y) || p.y == q.y) continue;
      const double x = p.x + (y - p.y) * (q.x - p.x) / (q.y - p.y);
      xl = std::min(xl, x);
      xr = std::max(xr, x);
    }
    if (xl > xr) continue;
    const int x0 = std::max(0, static_cast<int>(std::ceil(xl)));
    const int x1 = std::min(buf.width - 1, static_cast<int>(std::floor(xr)));
    if (x0 > x1) continue;
    const double dy = y - a.y;
    double iz = a.iz + iz_dx * (x0 - a.x) + iz_dy * dy;
    double uz = a.uz + uz_dx * (x0 - a.x) + uz_dy * dy;
    double vz = a.vz + vz_dx * (x0 - a.x) + vz_dy * dy;
    const int row = y * buf.width;
    for (int x = x0; x <= x1; ++x) {
      const int i = row + x;
      if (iz > buf.inv_depth[i]) {
        buf.inv_depth[i] = static_cast<float>(iz);
        buf.u[i] = static_cast<float>(uz / iz);
        buf.v[i] = static_cast<float>(vz / iz);
        buf.triangle[i] = record;
      }
      iz += iz_dx;
      uz += uz_dx;
      vz += vz_dx;
    }
  }
}

}  // namespace

void GBuffer::Reset(int w, int h) {
  width = w;
  height = h;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  inv_depth.assign(n, 0.0f);
  u.assign(n, 0.0f);
  v.assign(n, 0.0f);
  triangle.assign(n, -1);
  records.clear();
}

void RasterizeMesh(const Mesh& mesh, const Eigen::Matrix3f& R, const Eigen::Vector3f& t,
                   const CameraIntrinsics& camera, int label, const RasterLight& light, float near_m,
                   GBuffer& buffer) {
  std::vector<Eigen::Vector3f> cam(mesh.positions.size());
  for (std::size_t i = 0; i < cam.size(); ++i) cam[i] = R * mesh.positions[i] + t;
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    const auto& tri = mesh.triangles[k];
    const Eigen::Vector3f& p0 = cam[tri[0]];
    const Eigen::Vector3f& p1 = cam[tri[1]];
    const Eigen::Vector3f& p2 = cam[tri[2]];
    if (p0.z() < near_m && p1.z() < near_m && p2.z() < near_m) continue;
    const Eigen::Vector3f normal = (p1 - p0).cross(p2 - p0);
    if (normal.dot(p0) >= 0.0f) continue;  // back face (camera at the origin)
    const Eigen::Vector3f n = normal.normalized();
    TriangleRecord rec;
    rec.material = mesh.triangle_materials[k];
    rec.label = label;
    rec.shade = light.ambient + light.diffuse * std::max(0.0f, n.dot(light.direction_cam));
    const Eigen::Vector3f centroid = (p0 + p1 + p2) / 3.0f;
    rec.slant = std::max(0.2f, std::abs(n.dot(centroid.normalized())));
    const int record = static_cast<int>(buffer.records.size());
    buffer.records.push_back(rec);

    ClipVertex in[3] = {{p0, mesh.uvs[tri[0]]}, {p1, mesh.uvs[tri[1]]}, {p2, mesh.uvs[tri[2]]}};
    ClipVertex clipped[4];
    const int n_clipped = ClipNear(in, 3, near_m, clipped);
    ScreenVertex s[4];
    for (int i = 0; i < n_clipped; ++i) {
      const double iz = 1.0 / clipped[i].p.z();
      s[i] = {camera.fx * clipped[i].p.x() * iz + camera.cx, camera.fy * clipped[i].p.y() * iz + camera.cy,
              iz, clipped[i].uv.x() * iz, clipped[i].uv.y() * iz};
    }
    for (int i = 1; i + 1 < n_clipped; ++i) DrawTriangle(s[0], s[i], s[i + 1], record, buffer);
  }
}

}  // namespace dlslam::synth
