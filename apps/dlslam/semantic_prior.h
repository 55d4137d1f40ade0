#pragma once
// Where `dlslam run --semantic-masks` gets each frame's semantic a-priori
// mask instead of the network (which runs in the library's semantic thread,
// SystemOptions::semantic): the sequence's ground truth or a folder of masks.
//   slam.TrackRgbd(..., {[&] { SemanticPrior p = source->Prior(i, frame);
//                              return dynamic::SemanticMasks{p.mask, p.movable}; }});

#include <filesystem>
#include <memory>
#include <string>

#include <opencv2/core.hpp>

#include "dlslam/io/sequence.h"

namespace dlslam::app {

struct SemanticPrior {
  cv::Mat mask;             // CV_8UC1, non-zero = a-priori dynamic; empty = none for this frame
  cv::Mat movable;          // CV_8UC1, non-zero = a movable class (chairs, boxes); empty = none
  double compute_ms = 0.0;  // time the source spent making it (inference, or reading)
};

class SemanticPriorSource {
 public:
  virtual ~SemanticPriorSource() = default;
  // The prior of frame `index`. Throws InputError when its input is missing
  // or bad.
  virtual SemanticPrior Prior(std::size_t index, const io::RgbdFrame& frame) = 0;
  // One line for the log, e.g. "ground-truth masks (class person)".
  virtual std::string Describe() const = 0;
};

// "gt": the sequence's own masks (mask.txt, `dlslam synth`), class-based:
// every person pixel, moving or not (what a perfect network would give), and
// the "other movable object" class as movable.
// Otherwise a folder of PNG masks named like the colour images
// (<rgb file stem>.png, 8-bit, non-zero = dynamic). Throws InputError when
// the sequence has no masks (gt) or the folder does not exist.
std::unique_ptr<SemanticPriorSource> MakeSemanticPriorSource(const std::string& spec,
                                                             const io::RgbdSequence& sequence);

// Ground truth of `dlslam synth` labels (class + 128 if moving): 255 where
// the moving bit is set (what should be removed), for statistics.
cv::Mat MovingTruthFromLabels(const cv::Mat& labels);
// 255 where the label's class is `class_id`, whatever the moving bit.
cv::Mat ClassMaskFromLabels(const cv::Mat& labels, int class_id);

}  // namespace dlslam::app
