#pragma once
// Rotation consistency of a set of matches (as ORB-SLAM): the keypoint
// orientation changes between the two views of true matches agree, so
// matches outside the dominant bins of a histogram of those changes are
// dropped.

#include <vector>

namespace dlslam {

// Bin of the orientation change from angle_a to angle_b [deg], 0..bins-1.
int RotationBin(float angle_a, float angle_b);

// Per match (given its bin): true if it falls into one of the three fullest
// bins that hold at least 10 % of the fullest one's count.
std::vector<bool> InDominantRotationBins(const std::vector<int>& bins);

}  // namespace dlslam
