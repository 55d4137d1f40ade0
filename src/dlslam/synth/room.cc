#include "dlslam/synth/room.h"

#include <array>

#include "dlslam/synth/random.h"
#include "dlslam/synth/scene.h"

namespace dlslam::synth {

namespace {

using V3 = Eigen::Vector3f;
using Rng = std::mt19937;

V3 F(const Eigen::Vector3d& v) { return v.cast<float>(); }
Eigen::AlignedBox3d Aabb(const V3& lo, const V3& hi) { return {lo.cast<double>(), hi.cast<double>()}; }

// Face order of AddBox: -x, +x, -y, +y, -z, +z.
enum Face { kMinusX, kPlusX, kMinusY, kPlusY, kMinusZ, kPlusZ };

void Box(Scene& s, const V3& lo, const V3& hi, int material, int front_material = -1, Face front = kMinusY) {
  std::array<int, 6> m;
  m.fill(material);
  if (front_material >= 0) m[front] = front_material;
  AddBox(s.static_mesh, lo, hi, m);
}

void Desk(Scene& s, const V3& lo, const V3& hi, int top, int legs) {
  Box(s, V3(lo.x(), lo.y(), hi.z() - 0.04f), hi, top);
  const float w = 0.05f;
  for (float x : {lo.x(), hi.x() - w}) {
    for (float y : {lo.y(), hi.y() - w}) Box(s, V3(x, y, 0), V3(x + w, y + w, hi.z() - 0.04f), legs);
  }
  s.obstacles.push_back(Aabb(lo, hi));
}

// A chair whose seat centre is (x, y), backrest on the side of `back_dir` (+-1 along y or x).
void Chair(Scene& s, float x, float y, bool back_along_y, float back_dir, int seat, int legs) {
  const float h = static_cast<float>(room::kSeatHeight), half = 0.22f, w = 0.04f;
  Box(s, V3(x - half, y - half, h - 0.05f), V3(x + half, y + half, h), seat);
  for (float dx : {-half, half - w}) {
    for (float dy : {-half, half - w}) Box(s, V3(x + dx, y + dy, 0), V3(x + dx + w, y + dy + w, h - 0.05f), legs);
  }
  const V3 c(x, y, 0);
  const V3 along = back_along_y ? V3(0, back_dir, 0) : V3(back_dir, 0, 0);
  const V3 across = back_along_y ? V3(1, 0, 0) : V3(0, 1, 0);
  const V3 a = c + along * half + across * half + V3(0, 0, h);
  const V3 b = c + along * (half + 0.04f) - across * half + V3(0, 0, h + 0.48f);
  Box(s, a.cwiseMin(b), a.cwiseMax(b), seat);
  s.obstacles.push_back(Aabb(V3(x - half, y - half, 0), V3(x + half, y + half, h + 0.48f)));
}

// A shelf unit against the far wall with rows of books.
void Shelf(Scene& s, float x0, float x1, int wood, int books_front, int books_side, Rng& rng) {
  const float y0 = 3.05f, y1 = static_cast<float>(room::kMax.y()), top = 1.9f, t = 0.02f;
  Box(s, V3(x0, y0, 0), V3(x0 + t, y1, top), wood);
  Box(s, V3(x1 - t, y0, 0), V3(x1, y1, top), wood);
  Box(s, V3(x0, y1 - t, 0), V3(x1, y1, top), wood);
  for (int k = 0; k < 5; ++k) {
    const float z = 0.02f + k * 0.465f;
    Box(s, V3(x0 + t, y0, z - t), V3(x1 - t, y1 - t, z), wood);
    if (k == 4) break;
    for (float x = x0 + t + static_cast<float>(Uniform(rng, 0, 0.1)); x < x1 - 0.12f;) {
      const float w = std::min(static_cast<float>(Uniform(rng, 0.08, 0.35)), x1 - t - x);
      const float h = static_cast<float>(Uniform(rng, 0.18, 0.4));
      const float depth = static_cast<float>(Uniform(rng, 0.18, 0.3));
      Box(s, V3(x, y0 + 0.32f - depth, z), V3(x + w, y0 + 0.32f, z + h), books_side, books_front);
      x += w + static_cast<float>(Uniform(rng, 0.0, 0.12));
    }
  }
  s.obstacles.push_back(Aabb(V3(x0, y0, 0), V3(x1, y1, top)));
}

// A random stack of cardboard boxes on the floor inside [lo, hi] (x, y).
void BoxStack(Scene& s, float x0, float y0, float x1, float y1, const std::array<int, 2>& cardboard, Rng& rng) {
  float z = 0;
  for (int level = 0; level < 3 && z < 1.2f; ++level) {
    const float h = static_cast<float>(Uniform(rng, 0.25, 0.45));
    const float inset = 0.05f * level;
    const float w = (x1 - x0 - 2 * inset), d = (y1 - y0 - 2 * inset);
    const int n = UniformInt(rng, 1, 2);
    for (int i = 0; i < n; ++i) {
      const float bx = x0 + inset + w * i / n, by = y0 + inset + static_cast<float>(Uniform(rng, 0, 0.1));
      Box(s, V3(bx + 0.01f, by, z), V3(bx + w / n - 0.01f, by + d - 0.1f, z + h),
          cardboard[static_cast<std::size_t>(UniformInt(rng, 0, 1))]);
    }
    z += h;
  }
  s.obstacles.push_back(Aabb(V3(x0, y0, 0), V3(x1, y1, z)));
}

}  // namespace

void BuildRoom(Scene& s, const RoomOptions& options, Rng& rng) {
  const V3 lo = F(room::kMin), hi = F(room::kMax);
  const V3 size = hi - lo;
  const V3 up(0, 0, size.z());
  // Walls face into the room; u runs left to right as seen from inside.
  const int far_wall = s.AddMaterial(s.AddTexture(TextureStyle::kWall, 1024, 512, 170, rng), rng);
  const int back_wall = s.AddMaterial(s.AddTexture(TextureStyle::kWall, 1024, 512, 170, rng), rng);
  const int left_wall = s.AddMaterial(s.AddTexture(TextureStyle::kWall, 1024, 512, 170, rng), rng);
  const int right_wall = s.AddMaterial(s.AddTexture(TextureStyle::kWall, 1024, 512, 170, rng), rng);
  AddQuad(s.static_mesh, V3(lo.x(), hi.y(), 0), V3(size.x(), 0, 0), up, far_wall);
  AddQuad(s.static_mesh, V3(hi.x(), lo.y(), 0), V3(-size.x(), 0, 0), up, back_wall);
  AddQuad(s.static_mesh, V3(lo.x(), lo.y(), 0), V3(0, size.y(), 0), up, left_wall);
  AddQuad(s.static_mesh, V3(hi.x(), hi.y(), 0), V3(0, -size.y(), 0), up, right_wall);
  const int floor = s.AddMaterial(s.AddTexture(TextureStyle::kFloor, 512, 512, 100, rng), rng);
  AddQuad(s.static_mesh, V3(lo.x(), lo.y(), 0), V3(size.x(), 0, 0), V3(0, size.y(), 0), floor);
  if (options.ceiling) {
    const int ceiling = s.AddMaterial(s.AddTexture(TextureStyle::kCeiling, 512, 512, 85, rng), rng);
    AddQuad(s.static_mesh, V3(lo.x(), lo.y(), hi.z()), V3(0, size.y(), 0), V3(size.x(), 0, 0), ceiling);
  }
  s.room = Eigen::AlignedBox3d(room::kMin, room::kMax);

  const int wood_tex = s.AddTexture(TextureStyle::kWood, 512, 512, 256, rng);
  const int wood_tex2 = s.AddTexture(TextureStyle::kWood, 512, 512, 256, rng);
  const int device_tex = s.AddTexture(TextureStyle::kDevice, 256, 256, 400, rng);
  const int card_tex = s.AddTexture(TextureStyle::kCardboard, 512, 512, 300, rng);
  const int books_tex = s.AddTexture(TextureStyle::kBooks, 512, 256, 400, rng);
  const int desk_top = s.AddMaterial(wood_tex, rng), shelf_wood = s.AddMaterial(wood_tex2, rng);
  const int metal = s.AddMaterial(device_tex, rng, 0.8f);
  const std::array<int, 2> cardboard = {s.AddMaterial(card_tex, rng), s.AddMaterial(card_tex, rng, 0.85f)};
  const int books = s.AddMaterial(books_tex, rng), books2 = s.AddMaterial(books_tex, rng);
  auto screen = [&] { return s.AddMaterial(device_tex, rng); };

  // The main desk and what stands on it (clear of the sliding box's path, x in [0, 0.55]).
  const V3 shift(0, static_cast<float>(options.desk_shift_y), 0);
  auto desk_box = [&](const V3& a, const V3& b, int material, int front_material = -1, Face front = kMinusY) {
    Box(s, a + shift, b + shift, material, front_material, front);
  };
  const V3 desk_lo = F(room::kDeskMin) + shift, desk_hi = F(room::kDeskMax) + shift;
  Desk(s, desk_lo, desk_hi, desk_top, metal);
  const float top = desk_hi.z();
  desk_box(V3(-0.72f, 1.9f, top), V3(-0.62f, 1.98f, 0.9f), metal);
  desk_box(V3(-0.95f, 1.86f, 0.9f), V3(-0.4f, 1.93f, 1.24f), metal, screen());  // monitor
  desk_box(V3(-0.85f, 1.45f, top), V3(-0.45f, 1.62f, top + 0.025f), metal, screen(), kPlusZ);  // keyboard
  float z = top;
  for (int i = UniformInt(rng, 2, 4); i > 0; --i) {  // a pile of books
    const float h = static_cast<float>(Uniform(rng, 0.03, 0.07));
    const float dx = static_cast<float>(Uniform(rng, 0, 0.05));
    desk_box(V3(0.58f + dx, 1.38f + dx, z), V3(0.88f + dx, 1.6f + dx, z + h), books, s.AddMaterial(card_tex, rng),
             kPlusZ);
    z += h;
  }
  desk_box(V3(-0.35f, 1.78f, top), V3(-0.08f, 2.05f, top + 0.2f), cardboard[0]);
  Mesh mug;
  AddCapsule(mug, 0.045f, 0.045f, 0.08f, 0.01f, screen(), 12, 1);
  for (auto& p : mug.positions) p += V3(0.3f, 1.95f, top + 0.09f) + shift;
  s.static_mesh.Append(mug);

  // Shelves in the far corners, a cabinet and frames on the left, a side desk and boxes on the right.
  Shelf(s, -2.95f, -2.05f, shelf_wood, books, shelf_wood, rng);
  Shelf(s, 2.05f, 2.95f, shelf_wood, books2, shelf_wood, rng);
  Box(s, V3(lo.x(), 0.4f, 0), V3(-2.5f, 1.6f, 1.0f), desk_top);
  s.obstacles.push_back(Aabb(V3(lo.x(), 0.4f, 0), V3(-2.5f, 1.6f, 1.0f)));
  for (int k = 0; k < 3; ++k) {
    const float dz = 0.05f + 0.32f * k;
    Box(s, V3(-2.5f, 0.45f, dz), V3(-2.49f, 1.55f, dz + 0.28f), shelf_wood);
    Box(s, V3(-2.49f, 0.9f, dz + 0.2f), V3(-2.47f, 1.1f, dz + 0.23f), metal);
  }
  BoxStack(s, lo.x() + 0.05f, 1.9f, -2.35f, 2.9f, cardboard, rng);
  Desk(s, V3(2.3f, -0.2f, 0), V3(hi.x(), 1.3f, 0.75f), desk_top, metal);
  Box(s, V3(2.7f, 0.25f, 0.8f), V3(2.76f, 0.85f, 1.15f), metal, screen(), kMinusX);
  BoxStack(s, 2.3f, 1.6f, hi.x() - 0.05f, 2.8f, cardboard, rng);
  for (const float y : {-1.6f, 2.0f}) {  // picture frames on the side walls
    const float w = static_cast<float>(Uniform(rng, 0.5, 0.9));
    Box(s, V3(lo.x(), y, 1.3f), V3(lo.x() + 0.03f, y + w, 1.3f + 0.7f * w), shelf_wood, far_wall, kPlusX);
    Box(s, V3(hi.x() - 0.03f, y - 0.3f, 1.25f), V3(hi.x(), y - 0.3f + w, 1.25f + 0.6f * w), shelf_wood, back_wall, kMinusX);
  }
  for (const float x : {-1.3f, 0.9f}) {  // frames on the far wall above the walkers
    Box(s, V3(x, hi.y() - 0.03f, 1.7f), V3(x + 0.6f, hi.y(), 2.2f), shelf_wood, left_wall, kMinusY);
  }
  // Behind the start: a low book shelf and a door.
  Box(s, V3(-1.5f, lo.y(), 0), V3(1.2f, -2.15f, 0.9f), shelf_wood, books, kPlusY);
  s.obstacles.push_back(Aabb(V3(-1.5f, lo.y(), 0), V3(1.2f, -2.15f, 0.9f)));
  Box(s, V3(1.6f, lo.y(), 0), V3(2.5f, lo.y() + 0.04f, 2.05f), desk_top, shelf_wood, kPlusY);

  if (options.chairs_at_desk) {
    for (const auto& seat : {room::kSeatLeft, room::kSeatRight}) {
      Chair(s, static_cast<float>(seat.x()), static_cast<float>(seat.y()), true, 1.0f, metal, metal);
    }
  } else {
    Chair(s, 2.0f, 0.6f, false, -1.0f, metal, metal);
    Chair(s, -2.2f, -1.2f, true, -1.0f, metal, metal);
  }
}

}  // namespace dlslam::synth
