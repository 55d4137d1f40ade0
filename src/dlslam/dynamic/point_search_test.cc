#include "dlslam/dynamic/point_search.h"

#include <gtest/gtest.h>

#include <random>

#include "dlslam/dynamic/ant_colony_search.h"
#include "dlslam/util/check.h"

namespace dlslam::dynamic {
namespace {

const cv::Size kImage(640, 480);

// ~1000 keypoint-like points: a uniform static background plus dense
// discs of dynamic points (movers are compact groups, as the paper assumes).
struct Layout {
  std::vector<ProjectedPoint> points;
  std::vector<int> group;  // -1 static, else the disc's index
  std::vector<cv::Point2f> centres;
  float radius = 40.0f;

  Layout(const std::vector<cv::Point2f>& disc_centres, std::uint32_t seed) : centres(disc_centres) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 639.0f), v(0.0f, 479.0f), unit(-1.0f, 1.0f);
    while (points.size() < 900) Add(u(rng), v(rng));
    for (const cv::Point2f& c : centres) {
      for (int added = 0; added < 40;) {
        const float dx = unit(rng) * radius, dy = unit(rng) * radius;
        if (dx * dx + dy * dy > radius * radius) continue;
        Add(c.x + dx, c.y + dy);
        ++added;
      }
    }
  }
  void Add(float x, float y) {
    ProjectedPoint p;
    p.pixel = {x, y};
    p.point = static_cast<int>(points.size());
    points.push_back(p);
    group.push_back(-1);
    for (std::size_t g = 0; g < centres.size(); ++g) {
      if (std::hypot(x - centres[g].x, y - centres[g].y) <= radius) group.back() = static_cast<int>(g);
    }
  }
  PointLabel Truth(std::size_t i) const {
    return group[i] >= 0 ? PointLabel::kDynamic : PointLabel::kStatic;
  }
  int DynamicCount() const {
    return static_cast<int>(std::count_if(group.begin(), group.end(), [](int g) { return g >= 0; }));
  }
};

SearchResult RunSearch(PointSearch& search, const Layout& layout, int* calls = nullptr) {
  int counted = 0;
  SearchResult result = search.Search(layout.points, kImage, [&](std::size_t i) {
    ++counted;
    return layout.Truth(i);
  });
  if (calls != nullptr) *calls = counted;
  return result;
}

TEST(ExhaustiveSearch, TestsEveryPoint) {
  const Layout layout({{100, 100}}, 1);
  auto search = MakeExhaustiveSearch();
  int calls = 0;
  const SearchResult result = RunSearch(*search, layout, &calls);
  EXPECT_EQ(result.tested, static_cast<int>(layout.points.size()));
  EXPECT_EQ(calls, result.tested);
  for (std::size_t i = 0; i < layout.points.size(); ++i) EXPECT_EQ(result.labels[i], layout.Truth(i));
}

TEST(AntColonySearch, FindsEveryDynamicGroupWithFarFewerTests) {
  for (const std::uint32_t seed : {1u, 2u, 3u}) {
    const Layout layout({{120, 100}, {500, 150}, {300, 380}}, seed);
    auto search = MakeAntColonySearch({});
    int calls = 0;
    const SearchResult result = RunSearch(*search, layout, &calls);
    EXPECT_EQ(calls, result.tested);
    std::vector<int> found(layout.centres.size(), 0);
    int found_total = 0;
    for (std::size_t i = 0; i < layout.points.size(); ++i) {
      if (result.labels[i] != PointLabel::kUntested) {
        EXPECT_EQ(result.labels[i], layout.Truth(i));
      }
      if (result.labels[i] == PointLabel::kDynamic) {
        ++found[static_cast<std::size_t>(layout.group[i])];
        ++found_total;
      }
    }
    for (std::size_t g = 0; g < found.size(); ++g) EXPECT_GT(found[g], 0) << "group " << g;
    // Expansion in dh-bands floods each disc (points ~11 px apart, dh 16).
    EXPECT_GE(found_total, 0.9 * layout.DynamicCount()) << "seed " << seed;
    // Static groups are skipped: far fewer tests than points.
    EXPECT_LT(result.tested, 0.5 * static_cast<double>(layout.points.size())) << "seed " << seed;
  }
}

TEST(AntColonySearch, AllStaticTestsAFraction) {
  const Layout layout({}, 4);
  auto search = MakeAntColonySearch({});
  const SearchResult result = RunSearch(*search, layout);
  EXPECT_LT(result.tested, 0.35 * static_cast<double>(layout.points.size()));
  EXPECT_GT(result.tested, 0);
}

TEST(AntColonySearch, PheromonePersistsAndLeadsTheNextSearch) {
  // Movers in the bottom-right: a fresh path starting top-left exhausts a
  // small test budget before reaching them; after one full search the
  // pheromone makes the path start there.
  const Layout layout({{560, 400}}, 5);
  AntColonyOptions budgeted;
  budgeted.max_tests = 30;
  budgeted.q0 = 1.0;  // no random jumps: the cold path is a plain sweep
  const auto count_dynamic = [](const SearchResult& r) {
    return std::count(r.labels.begin(), r.labels.end(), PointLabel::kDynamic);
  };
  AntColonySearch fresh(budgeted);
  const SearchResult cold = RunSearch(fresh, layout);
  EXPECT_EQ(cold.tested, 30);
  EXPECT_EQ(count_dynamic(cold), 0);

  AntColonySearch warmed({});  // no budget
  RunSearch(warmed, layout);
  const auto& tau = warmed.pheromone();
  const cv::Size grid = warmed.grid_size();
  ASSERT_EQ(tau.size(), static_cast<std::size_t>(grid.area()));
  const int cell = warmed.options().cell_size_px;
  const auto tau_at = [&](float x, float y) {
    return tau[static_cast<std::size_t>(static_cast<int>(y) / cell * grid.width + static_cast<int>(x) / cell)];
  };
  EXPECT_GT(tau_at(560, 400), warmed.options().tau_min);
  EXPECT_DOUBLE_EQ(tau_at(100, 100), warmed.options().tau_min);
  // The next path starts in a cell the movers deposited on.
  RunSearch(warmed, layout);
  ASSERT_FALSE(warmed.last_path().empty());
  const int start = warmed.last_path().front();
  EXPECT_NEAR((start % grid.width + 0.5) * cell, 560, 2 * cell);
  EXPECT_NEAR((start / grid.width + 0.5) * cell, 400, 2 * cell);

  // With the warm pheromone the same budget reaches the movers.
  warmed.set_max_tests(30);
  const SearchResult warm = RunSearch(warmed, layout);
  EXPECT_EQ(warm.tested, 30);
  EXPECT_GE(count_dynamic(warm), 20);
}

TEST(AntColonySearch, PheromoneEvaporatesWithoutMovers) {
  AntColonyOptions options;
  options.rho = 0.5;
  options.tau_max = 100;
  AntColonySearch search(options);
  RunSearch(search, Layout({{300, 200}}, 6));
  const Layout still({}, 6);
  const std::vector<double> before = search.pheromone();
  RunSearch(search, still);
  const std::vector<double>& after = search.pheromone();
  for (std::size_t c = 0; c < before.size(); ++c) {
    EXPECT_NEAR(after[c], std::max(options.tau_min, 0.5 * before[c]), 1e-12) << c;
  }
}

TEST(AntColonySearch, DeterministicForASeed) {
  const Layout layout({{200, 200}, {450, 300}}, 7);
  AntColonyOptions options;
  options.q0 = 0.5;  // many random choices
  AntColonySearch a(options), b(options);
  const SearchResult ra = RunSearch(a, layout), rb = RunSearch(b, layout);
  EXPECT_EQ(ra.labels, rb.labels);
  EXPECT_EQ(ra.tested, rb.tested);
  EXPECT_EQ(a.last_path(), b.last_path());
  options.seed = 99;
  AntColonySearch c(options);
  RunSearch(c, layout);
  EXPECT_NE(a.last_path(), c.last_path());
}

TEST(AntColonySearch, EmptyInput) {
  auto search = MakeAntColonySearch({});
  const SearchResult result = search->Search({}, kImage, [](std::size_t) {
    ADD_FAILURE();
    return PointLabel::kStatic;
  });
  EXPECT_EQ(result.tested, 0);
  EXPECT_TRUE(result.labels.empty());
  EXPECT_THROW(search->Search({}, cv::Size(0, 0), [](std::size_t) { return PointLabel::kStatic; }),
               Error);
}

TEST(AntColonyOptions, CheckRejectsBadValues) {
  EXPECT_NO_THROW(AntColonyOptions{}.Check());
  auto bad = [](auto mutate) {
    AntColonyOptions o;
    mutate(o);
    return o;
  };
  EXPECT_THROW(bad([](auto& o) { o.search_radius_px = 0; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.static_skip_radius_px = -1; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.band_width_px = -1; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.alpha = -1; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.beta = 11; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.q0 = 1.5; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.rho = 1.0; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.tau_min = 0; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.tau_max = 0.5; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.cell_size_px = 8; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.max_tests = -1; }).Check(), Error);
  EXPECT_THROW(AntColonySearch(bad([](auto& o) { o.rho = -0.1; })), Error);
}

}  // namespace
}  // namespace dlslam::dynamic
