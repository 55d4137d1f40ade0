#pragma once
// The synthetic sequences we render, named after the TUM RGB-D fr3 dynamic
// sequences whose camera motion and scene content they imitate.

#include <string>
#include <string_view>
#include <vector>

namespace dlslam::synth {

enum class Preset {
  kStatic,             // no people; slow xyz-like camera motion
  kWalkingXyz,         // two people walk; camera translates along x, y, z (~+-0.5 m)
  kWalkingRpy,         // two people walk; camera rotates in roll, pitch, yaw (~+-20-30 deg)
  kWalkingHalfsphere,  // two people walk; camera moves on a half sphere (1 m diameter)
  kWalkingStatic,      // two people walk; camera nearly still (sub-cm jitter)
  kSittingStatic,      // two people sit and gesture, a box slides; camera nearly still
  kKidnap,             // no people; the camera pans, is covered (black frames), and reappears where it was
  kLoop,               // no people; the camera circles the room twice looking outward (loop closing)
};

// Throws dlslam::Error listing the known names.
Preset ParsePreset(std::string_view name);
std::string PresetName(Preset preset);
std::vector<std::string> PresetNames();

}  // namespace dlslam::synth
