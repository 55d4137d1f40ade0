#pragma once
// Every option a run of the system has, in one struct, and the one list of
// them (VisitOptions) that config files, `dlslam config dump` and reports
// are made from.

#include "dlslam/config/option_visitor.h"
#include "dlslam/dense/tsdf_volume.h"
#include "dlslam/system/slam_system.h"

namespace dlslam::config {

struct RunOptions {
  SystemOptions system;
  dense::TsdfOptions dense;  // the dense map (dlslam run --dense-map)

  // Throws dlslam::Error naming the bad value.
  void Check() const;
};

// Visits every option of `options`, grouped as the modules are (orb,
// tracker, mapping, dynamic, semantic, loop, dense, and the system's own).
void VisitOptions(RunOptions& options, OptionVisitor& visitor);

}  // namespace dlslam::config
