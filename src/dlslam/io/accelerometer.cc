#include "dlslam/io/accelerometer.h"

#include "dlslam/io/text_table.h"
#include "dlslam/util/check.h"

namespace dlslam::io {

std::vector<AccelerometerSample> ReadAccelerometer(const std::filesystem::path& path) {
  const TextTable table = ReadTextTable(path);
  std::vector<AccelerometerSample> samples;
  samples.reserve(table.rows.size());
  for (const TextRow& row : table.rows) {
    if (row.fields.size() != 4) {
      throw InputError(path, row.line, "expected 'timestamp ax ay az', got {} fields",
                       row.fields.size());
    }
    AccelerometerSample s;
    s.timestamp = ParseDouble(row.fields[0], path, row.line, "timestamp");
    for (int k = 0; k < 3; ++k) {
      s.acceleration[k] =
          ParseDouble(row.fields[static_cast<std::size_t>(k) + 1], path, row.line, "acceleration");
    }
    if (!samples.empty() && !(s.timestamp > samples.back().timestamp)) {
      throw InputError(path, row.line, "timestamp {:.6f} is not larger than the previous {:.6f}",
                       s.timestamp, samples.back().timestamp);
    }
    samples.push_back(s);
  }
  return samples;
}

}  // namespace dlslam::io
