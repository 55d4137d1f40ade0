#pragma once
// Keypoint orientation by the intensity centroid (Rosin; ORB): the direction
// from the patch centre to the centroid of the intensities of a circular
// patch of radius 15 px.

#include <opencv2/core.hpp>

#include <array>

#include "dlslam/features/orb_options.h"

namespace dlslam::features {

// Half-width of the circular patch in each row |v| = 0..15 from the centre:
// the pixels with u^2 + v^2 <= 15 * 16, a disc that is symmetric under
// 90-degree rotations and transposition (no orientation bias).
const std::array<int, kPatchRadius + 1>& CirclePatchHalfWidths();

// Angle [deg, in [0, 360)] of atan2(m01, m10), the first moments of the
// circular patch around pixel (x, y) of an 8-bit grey image, measured from
// the x axis towards the y axis (clockwise on screen, y down). The patch must
// lie inside the image (x, y at least 15 px from the edges).
float IntensityCentroidAngle(const cv::Mat& image, int x, int y);

}  // namespace dlslam::features
