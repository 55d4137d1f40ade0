#pragma once
// The two walkers of the walking presets, after TUM fr3/walking_*: they walk
// the floor between the camera and the desk (room::kWalkZoneMin/Max, 1.2 to
// 2.05 m ahead of the start), mostly inside the start view: across it, towards
// and away from the camera, now and then out of view at the sides, stopping
// and turning on the spot. Both follow one loop at one pace, about half a loop
// apart, offset so that their bodies never touch; seen from the camera they
// cross, one on the near side walking one way, the other on the far side
// walking back.

#include <array>
#include <random>

#include "dlslam/synth/actors.h"

namespace dlslam::synth {

struct WalkerPairOptions {
  double body_radius = 0.3;         // a walker's footprint (shoulders and arms) [m]
  double box_radius = 0.27;         // the carried box's footprint [m]
  double clearance = 0.02;          // between two footprints, at any time [m]
  double min_in_view_fraction = 0.6;  // of each route's time inside the start view's cone
  double exit_probability = 0.2;    // a waypoint is out of view at the side
  double stand_probability = 0.25;  // a waypoint (other than the first) is a stop
  void Check() const;
};

// Route, pace and schedules of two walkers (the second carries a box);
// deterministic in `rng`'s state. Looks and materials are the caller's.
std::array<WalkerParams, 2> MakeWalkerPair(std::mt19937& rng, const WalkerPairOptions& options = {});

// Smallest gap [m] between the two walkers' footprints over one period (of the first's route).
double SmallestGap(const std::array<WalkerParams, 2>& walkers, const WalkerPairOptions& options);

}  // namespace dlslam::synth
