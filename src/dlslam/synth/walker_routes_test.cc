#include "dlslam/synth/walker_routes.h"

#include <gtest/gtest.h>

#include <numbers>

#include "dlslam/synth/random.h"
#include "dlslam/synth/room.h"
#include "dlslam/util/check.h"

namespace dlslam::synth {
namespace {

std::array<WalkerParams, 2> Pair(std::uint32_t seed) {
  std::mt19937 rng = MakeRng(seed, 99);
  return MakeWalkerPair(rng);
}

// Every vertex of `actor` in the world at time t.
std::vector<Eigen::Vector3d> Vertices(const Actor& actor, double t) {
  const std::vector<SE3d> poses = actor.pose_at(t);
  std::vector<Eigen::Vector3d> out;
  for (std::size_t k = 0; k < actor.parts.size(); ++k) {
    for (const Eigen::Vector3f& p : actor.parts[k].mesh.positions) out.push_back(poses[k] * p.cast<double>());
  }
  return out;
}

TEST(WalkerPair, RoutesKeepToTheFloorBeforeTheDesk) {
  for (std::uint32_t seed = 1; seed <= 30; ++seed) {
    const auto walkers = Pair(seed);
    EXPECT_FALSE(walkers[0].carry_box);
    EXPECT_TRUE(walkers[1].carry_box);
    const WalkRoute a(walkers[0].route, walkers[0].walk), b(walkers[1].route, walkers[1].walk);
    EXPECT_DOUBLE_EQ(a.period_s(), b.period_s()) << "seed " << seed;
    for (const WalkRoute* route : {&a, &b}) {
      EXPECT_LT(route->standing_fraction(), 0.6) << "seed " << seed << ": they mostly walk";
      for (double t = 0; t < route->period_s(); t += 0.05) {
        const Eigen::Vector2d p = route->At(t).position;
        ASSERT_TRUE((p.array() >= room::kWalkZoneMin.array() - 1e-9).all() &&
                    (p.array() <= room::kWalkZoneMax.array() + 1e-9).all())
            << "seed " << seed << " t " << t << ": " << p.transpose();
      }
    }
  }
}

// The two walkers' surfaces (the box included) never come closer than a few
// centimetres over a whole period of their loop.
TEST(WalkerPair, BodiesNeverTouch) {
  for (std::uint32_t seed = 1; seed <= 4; ++seed) {
    const auto walkers = Pair(seed);
    PersonLook tall;  // the largest person drawn
    tall.height = 1.9f;
    tall.girth = 1.15f;
    const Actor a = MakeWalker(tall, walkers[0]), b = MakeWalker(tall, walkers[1]);
    const double period = WalkRoute(walkers[0].route, walkers[0].walk).period_s();
    double closest = 1e9;
    for (double t = 0; t < period; t += 0.1) {
      const auto va = Vertices(a, t), vb = Vertices(b, t);
      if ((va.front() - vb.front()).head<2>().norm() > 1.2) continue;  // torsos far apart: nothing can touch
      for (const auto& p : va) {
        for (const auto& q : vb) closest = std::min(closest, (p - q).norm());
      }
    }
    EXPECT_GT(closest, 0.03) << "seed " << seed;
  }
}

TEST(WalkerPair, DeterministicInTheEngine) {
  const auto a = Pair(5), b = Pair(5), c = Pair(6);
  ASSERT_EQ(a[0].route.size(), b[0].route.size());
  for (std::size_t i = 0; i < a[0].route.size(); ++i) EXPECT_EQ(a[0].route[i].position, b[0].route[i].position);
  EXPECT_EQ(a[1].schedule_offset_s, b[1].schedule_offset_s);
  EXPECT_NE(a[0].route[0].position, c[0].route[0].position);
}

TEST(WalkerPair, OptionsCheck) {
  WalkerPairOptions o;
  EXPECT_NO_THROW(o.Check());
  o.body_radius = 0;
  EXPECT_THROW(o.Check(), Error);
  o = {};
  o.min_in_view_fraction = 1.0;
  EXPECT_THROW(o.Check(), Error);
  o = {};
  o.exit_probability = 0.9;
  EXPECT_THROW(o.Check(), Error);
}

}  // namespace
}  // namespace dlslam::synth
