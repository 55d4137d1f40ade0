#include "dlslam/dynamic/point_search.h"

namespace dlslam::dynamic {
namespace {

class ExhaustiveSearch final : public PointSearch {
 public:
  SearchResult Search(const std::vector<ProjectedPoint>& points, cv::Size /*image*/,
                      const std::function<PointLabel(std::size_t)>& test) override {
    SearchResult result;
    result.labels.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) result.labels[i] = test(i);
    result.tested = static_cast<int>(points.size());
    return result;
  }
};

}  // namespace

std::unique_ptr<PointSearch> MakeExhaustiveSearch() {
  return std::make_unique<ExhaustiveSearch>();
}

}  // namespace dlslam::dynamic
