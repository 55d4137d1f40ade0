#include "dlslam/config/config_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam::config {
namespace {

using ::testing::HasSubstr;

class ConfigFileTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::MakeTempDir("config_file"); }
  std::filesystem::path Write(const std::string& text, const std::string& name = "c.yaml") const {
    const std::filesystem::path path = dir_ / name;
    std::ofstream(path) << text;
    return path;
  }
  std::string Error(const std::string& text) const {
    RunOptions options;
    try {
      LoadConfig(Write(text), &options);
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "accepted:\n" << text;
    return "";
  }
  std::filesystem::path dir_;
};

TEST_F(ConfigFileTest, TheDumpIsAValidFileThatChangesNothing) {
  const RunOptions defaults;
  const std::string dump = DumpConfig(defaults);
  RunOptions loaded;
  LoadConfig(Write(dump), &loaded);
  EXPECT_EQ(ConfigJson(loaded), ConfigJson(defaults));
  EXPECT_EQ(DumpConfig(loaded), dump);
  // Every option has a comment; some have units.
  EXPECT_THAT(dump, HasSubstr("min_local_map_inliers: 30  # [inliers] for a frame to count as tracked"));
  EXPECT_THAT(dump, HasSubstr("mode: orb  # "));
  EXPECT_THAT(dump, HasSubstr("dynamic_classes: [1]"));
  EXPECT_THAT(dump, HasSubstr("model_path: \"\""));
  // Many options, all reachable.
  EXPECT_GT(std::count(dump.begin(), dump.end(), '\n'), 200);
}

TEST_F(ConfigFileTest, SetsNestedOptionsAndKeepsTheOthers) {
  RunOptions options;
  options.system.sequential = true;  // set before: the file does not name it
  LoadConfig(Write("dynamic:\n  mode: full\n  geometry:\n    search: exhaustive\n    ant:\n      seed: 7\n"
                   "tracker:\n  min_local_map_inliers: 25\n  max_jump_speed: 5.5\n"
                   "semantic:\n  segmenter:\n    dynamic_classes: [1, 3]\n    num_classes: 4\n    model_path: my.onnx\n"
                   "mapping:\n  bundle:\n    solver: ceres\n  queue_capacity: 4\n"
                   "dense:\n  voxel_size: 0.01\n  truncation: 0.04\n"),
             &options);
  EXPECT_EQ(options.system.dynamic.mode, DynamicMode::kFull);
  EXPECT_EQ(options.system.dynamic.geometry.search, dynamic::SearchKind::kExhaustive);
  EXPECT_EQ(options.system.dynamic.geometry.ant.seed, 7u);
  EXPECT_EQ(options.system.tracker.min_local_map_inliers, 25);
  EXPECT_EQ(options.system.tracker.max_jump_speed, 5.5);
  EXPECT_EQ(options.system.semantic.segmenter.dynamic_classes, (std::vector<int>{1, 3}));
  EXPECT_EQ(options.system.semantic.segmenter.model_path, "my.onnx");
  EXPECT_EQ(options.system.mapping.bundle.solver, BundleSolver::kCeres);
  EXPECT_EQ(options.system.mapping.queue_capacity, 4u);
  EXPECT_EQ(options.dense.voxel_size, 0.01);
  EXPECT_TRUE(options.system.sequential);
  EXPECT_EQ(options.system.orb.n_features, 1000);
}

TEST_F(ConfigFileTest, OrbSlam3SettingsKeysAreLeftToTheCameraReader) {
  const std::filesystem::path file =
      Write("%YAML:1.0\nCamera.type: \"PinHole\"\nCamera.fx: 535.4\nDepthMapFactor: 5000.0\ntracker:\n  close_depth: 2.5\n");
  RunOptions options;
  LoadConfig(file, &options);
  EXPECT_EQ(options.system.tracker.close_depth, 2.5);
  EXPECT_TRUE(HasCameraKeys(file));
  EXPECT_FALSE(HasCameraKeys(Write("tracker:\n  close_depth: 2.5\n", "d.yaml")));
  RunOptions orb;
  LoadConfig(Write("ORBextractor.nFeatures: 1500\nORBextractor.scaleFactor: 1.3\nORBextractor.iniThFAST: 25\n", "o.yaml"), &orb);
  EXPECT_EQ(orb.system.orb.n_features, 1500);
  EXPECT_EQ(orb.system.orb.scale_factor, 1.3);
  EXPECT_EQ(orb.system.orb.fast_threshold_initial, 25);
  EXPECT_THAT(Error("ORBextractor.nFeatures: many\n"), HasSubstr("c.yaml:1: ORBextractor.nFeatures: expected a whole number"));
}

TEST_F(ConfigFileTest, MistakesAreErrorsWithTheirLine) {
  EXPECT_THAT(Error("tracker:\n  min_local_map_inlier: 25\n"),
              HasSubstr("c.yaml:2: unknown key 'tracker.min_local_map_inlier'; did you mean "
                        "'tracker.min_local_map_inliers'?"));
  EXPECT_THAT(Error("trackr:\n  close_depth: 2\n"), HasSubstr("c.yaml:1: unknown key 'trackr'; did you mean 'tracker'?"));
  EXPECT_THAT(Error("xyz_unrelated: 1\n"), HasSubstr("dlslam config dump lists them all"));
  EXPECT_THAT(Error("tracker:\n  min_local_map_inliers: 2.5\n"),
              HasSubstr("c.yaml:2: tracker.min_local_map_inliers: expected a whole number"));
  EXPECT_THAT(Error("tracker:\n  min_local_map_inliers: 4294967326\n"), HasSubstr("expected a whole number"));
  EXPECT_THAT(Error("tracker:\n  close_depth: nan\n"), HasSubstr("expected a finite number"));
  EXPECT_THAT(Error("sequential: yes please\n"), HasSubstr("c.yaml:1: sequential: expected true or false"));
  EXPECT_THAT(Error("dynamic:\n  mode: fast\n"), HasSubstr("c.yaml:2: dynamic.mode: 'fast' is not one of orb, semantic"));
  EXPECT_THAT(Error("tracker: 3\n"), HasSubstr("c.yaml:1: tracker: expected a section"));
  EXPECT_THAT(Error("tracker:\n  close_depth: 2\n  close_depth: 3\n"), HasSubstr("c.yaml:3: key 'tracker.close_depth' given twice (first on line 2)"));
  EXPECT_THAT(Error("tracker: [1, 2\n"), HasSubstr("malformed YAML"));
  EXPECT_THAT(Error("- a\n- b\n"), HasSubstr("the top level must be"));
  EXPECT_THAT(Error(std::string(100000, '[')), HasSubstr("nested deeper than"));
  // Out of range: the module's own check, on the key's line.
  const std::string range = Error("orb:\n  n_features: 1000\n  scale_factor: 0.5\n");
  EXPECT_THAT(range, HasSubstr("c.yaml:3: orb.scale_factor: out of range"));
  EXPECT_THAT(Error("tracker:\n  max_coasting_frames: -1\n"), HasSubstr("c.yaml:2: tracker.max_coasting_frames: out of range"));
  // The new-map keys.
  EXPECT_THAT(Error("tracker:\n  new_map_after_lost_frames: -1\n"),
              HasSubstr("c.yaml:2: tracker.new_map_after_lost_frames: out of range"));
  EXPECT_THAT(Error("merge_every_frames: 0\n"), HasSubstr("c.yaml:1: merge_every_frames: out of range"));
  EXPECT_THAT(Error("max_mapping_lag_frames: -1\n"), HasSubstr("c.yaml:1: max_mapping_lag_frames: out of range"));
  EXPECT_THAT(Error("max_mapping_wait_ms: 70000\n"), HasSubstr("c.yaml:1: max_mapping_wait_ms: out of range"));
  EXPECT_THAT(Error("merge_agreement_deg: -3\n"), HasSubstr("c.yaml:1: merge_agreement_deg: out of range"));
  EXPECT_THAT(Error("mapping:\n  max_bundle_yields_in_a_row: -1\n"),
              HasSubstr("c.yaml:2: mapping.max_bundle_yields_in_a_row: out of range"));
  // The prediction gate, the extractor's exclusion radius, the mask completion.
  EXPECT_THAT(Error("tracker:\n  gate_departure_m: -0.01\n"),
              HasSubstr("c.yaml:2: tracker.gate_departure_m: out of range"));
  EXPECT_THAT(Error("tracker:\n  gate_radius_px: 0\n"), HasSubstr("c.yaml:2: tracker.gate_radius_px: out of range"));
  EXPECT_THAT(Error("static_orb:\n  exclusion_radius: 16\n"),
              HasSubstr("c.yaml:2: static_orb.exclusion_radius: out of range"));
  EXPECT_THAT(Error("dynamic:\n  completion:\n    pixel_step: 3\n"),
              HasSubstr("c.yaml:3: dynamic.completion.pixel_step: out of range"));
  // Geometry overruled, keyframes held for their masks.
  EXPECT_THAT(Error("dynamic:\n  max_geometry_share_of_prior_static: 0\n"),
              HasSubstr("c.yaml:2: dynamic.max_geometry_share_of_prior_static: out of range"));
  EXPECT_THAT(Error("semantic:\n  keyframe_mask_max_wait_frames: -1\n"),
              HasSubstr("c.yaml:2: semantic.keyframe_mask_max_wait_frames: out of range"));
  EXPECT_THAT(Error("semantic:\n  carried_segment_every: 0\n"),
              HasSubstr("c.yaml:2: semantic.carried_segment_every: out of range"));
  EXPECT_THAT(Error("semantic:\n  segmenter:\n    threads: -1\n"),
              HasSubstr("c.yaml:3: semantic.segmenter.threads: out of range"));
  // The dense free-space check.
  EXPECT_THAT(Error("dynamic:\n  geometry:\n    free_space:\n      cell_px: 0\n"),
              HasSubstr("c.yaml:4: dynamic.geometry.free_space.cell_px: out of range"));
  EXPECT_THAT(Error("dynamic:\n  geometry:\n    free_space:\n      max_violated_share: 1.5\n"),
              HasSubstr("c.yaml:4: dynamic.geometry.free_space.max_violated_share: out of range"));
  // The parallax occlusion check and the movable rule.
  EXPECT_THAT(Error("dynamic:\n  geometry:\n    multiview:\n      parallax_clearance_px: 50\n"),
              HasSubstr("c.yaml:4: dynamic.geometry.multiview.parallax_clearance_px: out of range"));
  EXPECT_THAT(Error("dynamic:\n  fusion:\n    movable_dynamic_share: 2\n"),
              HasSubstr("c.yaml:3: dynamic.fusion.movable_dynamic_share: out of range"));
}

TEST_F(ConfigFileTest, TheReportJsonIsNested) {
  const nlohmann::ordered_json j = ConfigJson(RunOptions());
  EXPECT_EQ(j.at("tracker").at("min_local_map_inliers"), 30);
  EXPECT_EQ(j.at("dynamic").at("mode"), "orb");
  EXPECT_EQ(j.at("dynamic").at("geometry").at("multiview").at("max_reference_views"), 5);
  EXPECT_EQ(j.at("dense").at("voxel_size"), 0.02);
}

}  // namespace
}  // namespace dlslam::config
