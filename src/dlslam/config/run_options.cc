// The list of every option: key, unit, one-line comment. The defaults are
// the structs' own; the ranges are their Check()s.

#include "dlslam/config/run_options.h"

namespace dlslam::config {

namespace {

using V = OptionVisitor;

// One per options struct, below; declared first so that Section can call any.
void Visit(features::OrbOptions& o, V& v);
void Visit(PoseOptimizerOptions& o, V& v);
void Visit(place::BowMatchOptions& o, V& v);
void Visit(place::CandidateOptions& o, V& v);
void Visit(RelocalizerOptions& o, V& v);
void Visit(TrackerOptions& o, V& v);
void Visit(TriangulationMatchOptions& o, V& v);
void Visit(FuseMatchOptions& o, V& v);
void Visit(BundleAdjusterOptions& o, V& v);
void Visit(LocalMapperOptions& o, V& v);
void Visit(dynamic::GeometryOptions& o, V& v);
void Visit(DynamicOptions& o, V& v);
void Visit(SemanticThreadOptions& o, V& v);
void Visit(LoopClosingOptions& o, V& v);
void Visit(dense::TsdfOptions& o, V& v);

// A nested group: one options struct under `name`.
template <class Options>
void Section(V& v, std::string_view name, std::string_view comment, Options& options) {
  v.Begin(name, comment);
  Visit(options, v);
  v.End();
}

void Visit(features::OrbOptions& o, V& v) {
  v.Value("n_features", o.n_features, {"keypoints", "keypoints wanted over all pyramid levels"});
  v.Value("n_levels", o.n_levels, {"", "pyramid levels (level 0 = the image)"});
  v.Value("scale_factor", o.scale_factor, {"", "size ratio between consecutive pyramid levels (> 1)"});
  v.Value("fast_threshold_initial", o.fast_threshold_initial, {"grey levels", "FAST threshold tried first per grid cell"});
  v.Value("fast_threshold_min", o.fast_threshold_min, {"grey levels", "FAST threshold where the first found nothing"});
  v.Value("cell_size", o.cell_size, {"px", "side of the grid cells FAST thresholds are chosen for"});
  v.Value("edge_border", o.edge_border, {"px", "no keypoint closer than this to a level's edge"});
  v.Value("exclusion_radius", o.exclusion_radius,
          {"px at the level", "no keypoint this close to an excluded (dynamic) pixel: FAST's circle must be static"});
}

void Visit(PoseOptimizerOptions& o, V& v) {
  v.Value("rounds", o.rounds, {"", "optimise / reclassify outliers rounds"});
  v.Value("iterations_per_round", o.iterations_per_round, {"", "Levenberg-Marquardt iterations per round"});
  v.Value("chi2_mono", o.chi2_mono, {"px^2", "outlier threshold of a keypoint without depth (95 %, 2 dof)"});
  v.Value("chi2_stereo", o.chi2_stereo, {"px^2", "outlier threshold of a keypoint with depth (95 %, 3 dof)"});
  v.Value("robust_last_round", o.robust_last_round, {"", "keep the Huber kernel in the last round"});
  v.Value("min_step", o.min_step, {"", "stop when the update is smaller"});
}

void Visit(place::BowMatchOptions& o, V& v) {
  v.Value("max_distance", o.max_distance, {"bits", "largest Hamming distance of a match"});
  v.Value("ratio", o.ratio, {"", "best / second-best distance ratio"});
  v.Value("check_rotation", o.check_rotation, {"", "keep only matches of the dominant rotation"});
}

void Visit(place::CandidateOptions& o, V& v) {
  v.Value("min_common_words_ratio", o.min_common_words_ratio, {"", "of the best candidate's shared words"});
  v.Value("group_size", o.group_size, {"keyframes", "covisible group scored together"});
  v.Value("retain_ratio", o.retain_ratio, {"", "groups above this share of the best score are kept"});
}

void Visit(RelocalizerOptions& o, V& v) {
  v.Value("min_bow_matches", o.min_bow_matches, {"matches", "bag-of-words matches a candidate needs"});
  Section(v, "bow_match", "bag-of-words descriptor matching", o.bow_match);
  v.Value("ransac_reprojection_px", o.ransac_reprojection_px, {"px", "PnP RANSAC inlier threshold"});
  v.Value("ransac_iterations", o.ransac_iterations, {"", "PnP RANSAC iterations"});
  v.Value("min_first_inliers", o.min_first_inliers, {"inliers", "after RANSAC, before the guided search"});
  v.Value("guided_search_radius", o.guided_search_radius, {"px", "projection search around the RANSAC pose"});
  v.Value("local_keyframes", o.local_keyframes, {"keyframes", "searched around the candidate"});
  v.Value("min_inliers", o.min_inliers, {"inliers", "for a relocalization to be accepted"});
  v.Value("max_candidates", o.max_candidates, {"keyframes", "candidates tried per frame"});
  Section(v, "candidates", "keyframe candidates from the index", o.candidates);
  Section(v, "pose", "pose optimisation", o.pose);
}

void Visit(TrackerOptions& o, V& v) {
  v.Value("min_init_points", o.min_init_points, {"keypoints", "with depth, to start the map from one frame"});
  v.Value("min_init_points_spread", o.min_init_points_spread, {"keypoints", "... or this many, spread (0 = off)"});
  v.Value("min_init_cells", o.min_init_cells, {"cells", "... over this many cells of a 4 x 4 grid"});
  v.Value("motion_search_radius", o.motion_search_radius, {"px", "projection search around the motion guess"});
  v.Value("local_search_radius", o.local_search_radius, {"px", "projection search of the local map"});
  v.Value("min_motion_matches", o.min_motion_matches, {"matches", "after the motion-model search"});
  v.Value("min_reference_inliers", o.min_reference_inliers, {"inliers", "after the reference-keyframe fallback"});
  v.Value("min_local_map_inliers", o.min_local_map_inliers, {"inliers", "for a frame to count as tracked"});
  v.Value("max_local_keyframes", o.max_local_keyframes, {"keyframes", "in the local map"});
  v.Value("close_depth", o.close_depth, {"m", "keypoints closer than this have reliable depth"});
  v.Value("keyframe_tracked_ratio", o.keyframe_tracked_ratio, {"", "new keyframe below this share of the reference's points"});
  v.Value("max_frames_between_keyframes", o.max_frames_between_keyframes, {"frames", "new keyframe after this many"});
  v.Value("max_frames_between_keyframes_dynamic", o.max_frames_between_keyframes_dynamic, {"frames", "... in modes semantic, geometry and full"});
  v.Value("crowded_removed_share", o.crowded_removed_share,
          {"", "a frame with this share of the image removed makes no keyframe for its untracked close points (1 = off)"});
  v.Value("max_mapping_backlog", o.max_mapping_backlog, {"keyframes", "no new keyframe while this many wait for mapping"});
  v.Value("min_new_points", o.min_new_points, {"points", "a keyframe creates at least this many depth points"});
  v.Value("max_coasting_frames", o.max_coasting_frames, {"frames", "in a row on the motion model when tracking fails"});
  v.Value("coasting_velocity_frames", o.coasting_velocity_frames, {"frames", "coasting moves on the median motion of this many tracked frames"});
  v.Value("min_coasting_inliers", o.min_coasting_inliers, {"inliers", "to refine a coasting pose on its matches"});
  v.Value("max_coasting_correction_m", o.max_coasting_correction_m, {"m", "largest refinement of a coasting pose"});
  v.Value("max_coasting_correction_deg", o.max_coasting_correction_deg, {"deg", "largest refinement of a coasting pose"});
  v.Value("max_jump_speed", o.max_jump_speed, {"m/s", "a tracked pose departing faster from the prediction is refused"});
  v.Value("max_jump_rate", o.max_jump_rate, {"deg/s", "a tracked pose turning faster from the prediction is refused"});
  v.Value("gate_departure_m", o.gate_departure_m,
          {"m", "a tracked pose further from the prediction is solved again on the matches near it (0 = off)"});
  v.Value("gate_departure_deg", o.gate_departure_deg, {"deg", "... or turned further (0 = off)"});
  v.Value("gate_radius_px", o.gate_radius_px, {"px", "... the matches within this of their keypoints at the prediction"});
  v.Value("gate_refuses", o.gate_refuses, {"", "a pose departing that far after the gate coasts instead"});
  v.Value("gate_on_median_motion", o.gate_on_median_motion,
          {"", "the gate's prediction moves on the median of the recent motions"});
  v.Value("gated_keyframe_min_inliers", o.gated_keyframe_min_inliers,
          {"inliers", "a gated frame becomes a keyframe only with this many (0 = never; modes semantic and full only)"});
  v.Value("new_map_after_lost_frames", o.new_map_after_lost_frames,
          {"frames", "lost this long without relocalizing: start a new map at the last pose; 0 = never"});
  v.Value("insert_keyframes", o.insert_keyframes, {"", "false: never extend the map (see localization_only)"});
  Section(v, "pose", "pose optimisation", o.pose);
  Section(v, "relocalization", "relocalization of a lost camera", o.relocalization);
}

void Visit(TriangulationMatchOptions& o, V& v) {
  v.Value("max_distance", o.max_distance, {"bits", "largest Hamming distance of a match"});
  v.Value("epipolar_chi2", o.epipolar_chi2, {"px^2", "distance to the epipolar line (95 %, 1 dof)"});
  v.Value("min_epipole_distance", o.min_epipole_distance, {"px", "no match this close to the epipole"});
  v.Value("check_orientation", o.check_orientation, {"", "keep only matches of the dominant rotation"});
}

void Visit(FuseMatchOptions& o, V& v) {
  v.Value("radius", o.radius, {"px", "projection search radius (times the level's scale)"});
  v.Value("max_distance", o.max_distance, {"bits", "largest Hamming distance of a match"});
  v.Value("chi2_mono", o.chi2_mono, {"px^2", "reprojection threshold without depth"});
  v.Value("chi2_stereo", o.chi2_stereo, {"px^2", "reprojection threshold with depth"});
  v.Value("max_view_angle_deg", o.max_view_angle_deg, {"deg", "from the point's mean viewing direction"});
}

void Visit(BundleAdjusterOptions& o, V& v) {
  v.Enum("solver", o.solver, {"lm", "ceres"}, [](BundleSolver s) { return std::string(ToString(s)); },
         ParseBundleSolver, {"", "our sparse Levenberg-Marquardt or Ceres"});
  v.Value("first_pass_iterations", o.first_pass_iterations, {"", "with the robust kernel"});
  v.Value("second_pass_iterations", o.second_pass_iterations, {"", "after removing outliers"});
  v.Value("chi2_mono", o.chi2_mono, {"px^2", "outlier threshold without depth"});
  v.Value("chi2_stereo", o.chi2_stereo, {"px^2", "outlier threshold with depth"});
  v.Value("threads", o.threads, {"", "solver threads"});
  v.Value("function_tolerance", o.function_tolerance, {"", "relative cost decrease to stop at"});
}

void Visit(LocalMapperOptions& o, V& v) {
  v.Value("queue_capacity", o.queue_capacity, {"keyframes", "waiting for local mapping; tracking blocks when full"});
  v.Value("thread_nice", o.thread_nice, {"", "lower CPU priority than the tracker (nice increment, 0..19)"});
  v.Value("min_point_observations", o.min_point_observations, {"keyframes", "a recent point needs, or it is culled"});
  v.Value("min_found_ratio", o.min_found_ratio, {"", "found / visible a recent point needs"});
  v.Value("keyframe_redundancy", o.keyframe_redundancy, {"", "keyframes whose close points are this redundant are culled"});
  v.Value("close_depth", o.close_depth, {"m", "keypoints closer than this have reliable depth"});
  v.Value("triangulation", o.triangulation, {"", "new points by triangulation with neighbours"});
  v.Begin("triangulate", "triangulation of new points");
  v.Value("neighbours", o.triangulate.neighbours, {"keyframes", "covisible keyframes matched"});
  v.Value("min_baseline", o.triangulate.min_baseline, {"m", "between the two cameras"});
  v.Value("max_cos_parallax", o.triangulate.max_cos_parallax, {"", "rays closer to parallel are not triangulated"});
  v.Value("chi2_mono", o.triangulate.chi2_mono, {"px^2", "reprojection threshold without depth"});
  v.Value("chi2_stereo", o.triangulate.chi2_stereo, {"px^2", "reprojection threshold with depth"});
  v.Value("scale_consistency", o.triangulate.scale_consistency, {"", "distance ratio vs pyramid scale ratio allowed"});
  Section(v, "match", "epipolar matching", o.triangulate.match);
  v.End();
  v.Value("fusion", o.fusion, {"", "fuse duplicated points across neighbours"});
  v.Begin("fuse", "point fusion");
  v.Value("neighbours", o.fuse.neighbours, {"keyframes", "covisible keyframes"});
  v.Value("second_neighbours", o.fuse.second_neighbours, {"keyframes", "their neighbours too"});
  Section(v, "match", "projection matching", o.fuse.match);
  v.End();
  v.Value("bundle_adjustment", o.bundle_adjustment, {"", "local bundle adjustment per keyframe"});
  v.Value("max_bundle_yields_in_a_row", o.max_bundle_yields_in_a_row, {"", "threaded: local bundle adjustments stopped for a queued keyframe, at most this many in a row (0 = never)"});
  Section(v, "bundle", "local bundle adjustment", o.bundle);
}

void Visit(dynamic::GeometryOptions& o, V& v) {
  v.Begin("multiview", "the multi-view depth check (paper Sec. III-C)");
  v.Value("max_reference_views", o.multiview.max_reference_views, {"keyframes", "earlier views projected (paper: 5)"});
  v.Value("max_view_angle_deg", o.multiview.max_view_angle_deg, {"deg", "a point seen at a larger angle is not tested"});
  v.Value("depth_threshold_m", o.multiview.depth_threshold_m, {"m", "depth difference at 0 m that means moving"});
  v.Value("depth_threshold_per_m2", o.multiview.depth_threshold_per_m2, {"1/m", "... plus this times depth^2"});
  v.Value("depth_patch_radius_px", o.multiview.depth_patch_radius_px, {"px", "depth read as the patch's nearest"});
  v.Value("agreement_radius_px", o.multiview.agreement_radius_px, {"px", "static if any depth this near agrees"});
  v.Value("parallax_occlusion_check", o.multiview.parallax_occlusion_check, {"", "a point hidden behind a surface the reference view saw past is occluded, not moving"});
  v.Value("parallax_clearance_px", o.multiview.parallax_clearance_px, {"px", "... seen past by at least this much"});
  v.Value("min_depth_m", o.multiview.min_depth_m, {"m", "nearer depth is not tested"});
  v.Value("max_depth_m", o.multiview.max_depth_m, {"m", "farther depth is not tested"});
  v.End();
  v.Enum("search", o.search, {"exhaustive", "ant"}, [](dynamic::SearchKind k) { return dynamic::ToString(k); },
         dynamic::ParseSearchKind,
         {"", "which projected points are tested: all, or the ant colony's"});
  v.Begin("ant", "the ant colony search (paper Sec. III-D)");
  v.Value("search_radius_px", o.ant.search_radius_px, {"px", "neighbourhood an ant moves in"});
  v.Value("static_skip_radius_px", o.ant.static_skip_radius_px, {"px", "points near a static one are skipped"});
  v.Value("band_width_px", o.ant.band_width_px, {"px", "band around a dynamic point searched densely"});
  v.Value("alpha", o.ant.alpha, {"", "pheromone exponent"});
  v.Value("beta", o.ant.beta, {"", "heuristic exponent"});
  v.Value("q0", o.ant.q0, {"", "probability of the greedy choice"});
  v.Value("rho", o.ant.rho, {"", "pheromone evaporation"});
  v.Value("deposit", o.ant.deposit, {"", "pheromone deposited on a dynamic find"});
  v.Value("tau_min", o.ant.tau_min, {"", "pheromone bounds (MAX-MIN ant system)"});
  v.Value("tau_max", o.ant.tau_max, {"", "pheromone bounds (MAX-MIN ant system)"});
  v.Value("cell_size_px", o.ant.cell_size_px, {"px", "seed grid"});
  v.Value("expand_on_vanished", o.ant.expand_on_vanished, {"", "search around vanished points too"});
  v.Value("max_tests", o.ant.max_tests, {"points", "per frame; 0 = no limit"});
  v.Value("seed", o.ant.seed, {"", "random seed (runs repeat)"});
  v.End();
  v.Begin("region", "region growing from dynamic points over the depth");
  v.Value("max_step_m", o.region.max_step_m, {"m", "depth step between neighbours"});
  v.Value("max_step_relative", o.region.max_step_relative, {"", "... plus this share of the depth"});
  v.Value("max_depth_from_seed_m", o.region.max_depth_from_seed_m, {"m", "depth difference to the seed"});
  v.Value("max_distance_from_seed_m", o.region.max_distance_from_seed_m, {"m", "3-D distance to the seed"});
  v.Value("static_points_compete", o.region.static_points_compete, {"", "static points grow regions that stop the dynamic ones"});
  v.Value("static_head_start_px", o.region.static_head_start_px, {"px", "of the static regions"});
  v.Value("static_distance_from_seed_m", o.region.static_distance_from_seed_m, {"m", "reach of a static region"});
  v.Value("pixel_step", o.region.pixel_step, {"px", "growing grid"});
  v.Value("max_region_pixels", o.region.max_region_pixels, {"px", "per region"});
  v.Value("min_depth_m", o.region.min_depth_m, {"m", "nearer depth is not grown over"});
  v.Value("max_depth_m", o.region.max_depth_m, {"m", "farther depth is not grown over"});
  v.End();
  v.Value("grow_from_vanished", o.grow_from_vanished, {"", "grow regions from vanished points too"});
  v.Value("vanished_as_barriers", o.vanished_as_barriers, {"", "vanished points stop static regions"});
  v.Begin("free_space", "the dense check: depth standing where recent frames saw through");
  v.Value("enabled", o.free_space.enabled, {"", "run it (modes geometry and full)"});
  v.Value("cell_px", o.free_space.cell_px, {"px", "grid cell side"});
  v.Value("view_every_frames", o.free_space.view_every_frames, {"frames", "one tracked frame in this many is kept as a view"});
  v.Value("max_views", o.free_space.max_views, {"views", "kept, the oldest dropped"});
  v.Value("neighbourhood_cells", o.free_space.neighbourhood_cells, {"cells", "the nearest kept depth this near the projection counts"});
  v.Value("depth_threshold_m", o.free_space.depth_threshold_m, {"m", "seen through by more than this at 0 m"});
  v.Value("depth_threshold_per_m2", o.free_space.depth_threshold_per_m2, {"1/m", "... plus this times depth^2"});
  v.Value("min_region_cells", o.free_space.min_region_cells, {"cells", "smaller connected violations are noise"});
  v.Value("max_violated_share", o.free_space.max_violated_share, {"", "a view violated on more of the compared cells is misposed: ignored"});
  v.Value("min_depth_m", o.free_space.min_depth_m, {"m", "nearer depth is not used"});
  v.Value("max_depth_m", o.free_space.max_depth_m, {"m", "farther depth is not used"});
  v.End();
}

void Visit(DynamicOptions& o, V& v) {
  v.Enum("mode", o.mode, {"orb", "semantic", "geometry", "full"}, [](DynamicMode m) { return std::string(ToString(m)); },
         ParseDynamicMode, {"", "what removes moving keypoints: nothing, the network, geometry, both"});
  Section(v, "geometry", "multi-view geometry", o.geometry);
  v.Begin("fusion", "how the semantic prior and geometry combine");
  v.Enum("policy", o.fusion.policy, {"union", "geometry_confirms", "semantic", "geometry"},
         [](dynamic::FusionPolicy p) { return dynamic::ToString(p); }, dynamic::ParseFusionPolicy, {"", "mode full: prior or geometry, prior kept where geometry sees it still, ..."});
  v.Value("min_static_evidence", o.fusion.min_static_evidence, {"points", "geometry_confirms: static points to keep a segment"});
  v.Value("max_dynamic_evidence", o.fusion.max_dynamic_evidence, {"points", "geometry_confirms: at most this many dynamic"});
  v.Value("drop_moving_movables", o.fusion.drop_moving_movables, {"", "drop a movable-class segment whole when geometry sees it move"});
  v.Value("movable_dynamic_evidence", o.fusion.movable_dynamic_evidence, {"points", "dynamic points that make it move"});
  v.Value("movable_dynamic_share", o.fusion.movable_dynamic_share, {"", "... and their least share of its tested points"});
  v.Value("dilation_px", o.fusion.dilation_px, {"px", "of the removal mask"});
  v.End();
  v.Begin("completion", "the network's person mask completed with the depth");
  v.Value("enabled", o.completion.enabled, {"", "add the pixels beside a person at the person's depth"});
  v.Value("reach_m", o.completion.reach_m, {"m", "from the person's outline, at their depth"});
  v.Value("depth_margin_m", o.completion.depth_margin_m, {"m", "around the person's depth quartiles"});
  v.Value("min_segment_pixels", o.completion.min_segment_pixels, {"px", "smaller segments are not completed"});
  v.Value("min_depth_m", o.completion.min_depth_m, {"m", "valid depths"});
  v.Value("max_depth_m", o.completion.max_depth_m, {"m", "valid depths"});
  v.Value("pixel_step", o.completion.pixel_step, {"px", "working grid (1 or 2)"});
  v.End();
  v.Value("cull_vanished_points", o.cull_vanished_points, {"", "remove map points geometry sees gone"});
  v.Value("resolve_inverted_check", o.resolve_inverted_check, {"", "repeat an inverted-looking check with the movers' pose"});
  v.Value("inverted_check_min_share", o.inverted_check_min_share, {"", "of the image marked before trying"});
  v.Value("max_geometry_share_of_prior_static", o.max_geometry_share_of_prior_static,
          {"", "full: geometry taking more of what the prior left is overruled"});
  v.Value("geometry_mode_parallax_check", o.geometry_mode_parallax_check, {"", "mode geometry uses geometry.multiview.parallax_occlusion_check too (mode full always does)"});
}

void Visit(SemanticThreadOptions& o, V& v) {
  v.Value("network", o.network, {"", "segment frames with the network (false: the caller brings priors)"});
  v.Begin("segmenter", "the segmentation network");
  v.Value("backend", o.segmenter.backend, {"", "inference backend"});
  v.Value("model_path", o.segmenter.model_path, {"", "ONNX model; empty = the shipped one"});
  v.Value("input_width", o.segmenter.input_width, {"px", "network input; 0 = the size the model declares"});
  v.Value("input_height", o.segmenter.input_height, {"px", "network input; 0 = the size the model declares"});
  v.Value("num_classes", o.segmenter.num_classes, {"", "output channels"});
  v.Value("dynamic_classes", o.segmenter.dynamic_classes, {"", "classes that may move (people)"});
  v.Value("movable_classes", o.segmenter.movable_classes, {"", "classes that move when pushed (chairs)"});
  v.Value("dynamic_margin_px", o.segmenter.dynamic_margin_px, {"px", "dilation of the dynamic mask"});
  v.Value("threads", o.segmenter.threads, {"", "OpenCV threads, process-wide (1: the system's own threads fill the cores); 0 = OpenCV's default"});
  v.Value("min_image_side", o.segmenter.min_image_side, {"px", "smaller images are refused"});
  v.End();
  v.Begin("worker", "the semantic thread");
  v.Value("queue_capacity", o.worker.queue_capacity, {"frames", "waiting to be segmented"});
  v.Value("segment_every", o.worker.segment_every, {"frames", "segment every k-th frame"});
  v.Value("propagation_grow_px", o.worker.propagation_grow_px, {"px/frame", "growth of a propagated mask"});
  v.Value("thread_nice", o.worker.thread_nice, {"", "lower CPU priority than the tracker (nice increment, 0..19)"});
  v.End();
  v.Value("wait_for_masks", o.wait_for_masks, {"", "false: asynchronous masks (experimental)"});
  v.Value("carry_grow_px", o.carry_grow_px, {"px/frame", "asynchronous: growth of a carried mask per frame of age"});
  v.Value("max_carry_grow_px", o.max_carry_grow_px, {"px", "asynchronous: largest growth"});
  v.Value("wait_when_removed_share", o.wait_when_removed_share, {"", "asynchronous: wait after a frame that lost this share of the image"});
  v.Value("keyframes_wait_for_own_masks", o.keyframes_wait_for_own_masks,
          {"", "asynchronous: a keyframe enters the map only after its own masks"});
  v.Value("keyframe_mask_max_wait_frames", o.keyframe_mask_max_wait_frames,
          {"frames", "asynchronous: then the tracker waits for the keyframe's masks"});
  v.Value("carried_segment_every", o.carried_segment_every,
          {"frames", "asynchronous: offer a frame with carried masks to the network after this many"});
}

void Visit(LoopClosingOptions& o, V& v) {
  v.Begin("detection", "loop detection");
  LoopDetectorOptions& d = o.detection;
  v.Value("min_keyframes_between_loops", d.min_keyframes_between_loops, {"keyframes", "after the last loop"});
  v.Value("min_consistency", d.min_consistency, {"keyframes", "consecutive detections of the same place"});
  Section(v, "candidates", "keyframe candidates from the index", d.candidates);
  v.Value("min_bow_matches", d.min_bow_matches, {"matches", "bag-of-words matches a candidate needs"});
  Section(v, "bow_match", "bag-of-words descriptor matching", d.bow_match);
  v.Begin("ransac", "3D-3D rigid RANSAC");
  v.Value("max_iterations", d.ransac.max_iterations, {"", "iterations"});
  v.Value("confidence", d.ransac.confidence, {"", "stop when this sure"});
  v.Value("min_inliers", d.ransac.min_inliers, {"inliers", "for a candidate"});
  v.End();
  v.Value("ransac_error_m", d.ransac_error_m, {"m", "3-D inlier threshold at 0 m"});
  v.Value("ransac_error_per_m2", d.ransac_error_per_m2, {"1/m", "... plus this times depth^2"});
  v.Value("loop_group_keyframes", d.loop_group_keyframes, {"keyframes", "around the candidate searched"});
  v.Value("guided_search_radius", d.guided_search_radius, {"px", "projection search with the RANSAC pose"});
  v.Value("min_inliers", d.min_inliers, {"inliers", "for a loop to be accepted"});
  Section(v, "pose", "pose optimisation", d.pose);
  v.Value("seed", d.seed, {"", "RANSAC's random seed"});
  v.End();
  v.Begin("correction", "loop correction");
  v.Value("min_covisibility", o.correction.min_covisibility, {"points", "essential-graph covisibility edges"});
  v.Value("loop_group_keyframes", o.correction.loop_group_keyframes, {"keyframes", "fused on both sides"});
  Section(v, "fuse", "loop fusion matching", o.correction.fuse);
  v.Begin("pose_graph", "essential-graph optimisation (Ceres)");
  v.Value("max_iterations", o.correction.pose_graph.max_iterations, {"", "iterations"});
  v.Value("function_tolerance", o.correction.pose_graph.function_tolerance, {"", "Ceres tolerance"});
  v.Value("gradient_tolerance", o.correction.pose_graph.gradient_tolerance, {"", "Ceres tolerance"});
  v.Value("parameter_tolerance", o.correction.pose_graph.parameter_tolerance, {"", "Ceres tolerance"});
  v.Value("threads", o.correction.pose_graph.threads, {"", "Ceres threads"});
  v.End();
  v.End();
  v.Value("global_bundle_adjustment", o.global_bundle_adjustment, {"", "after each loop, in the background"});
  Section(v, "global_bundle", "global bundle adjustment", o.global_bundle);
  v.Value("queue_capacity", o.queue_capacity, {"keyframes", "waiting for loop detection"});
  v.Value("thread_nice", o.thread_nice, {"", "lower CPU priority than the tracker (nice increment, 0..19)"});
}

void Visit(dense::TsdfOptions& o, V& v) {
  v.Value("voxel_size", o.voxel_size, {"m", "edge of a voxel"});
  v.Value("truncation", o.truncation, {"m", "signed distance kept within this of the surface"});
  v.Value("max_depth", o.max_depth, {"m", "farther depth is not fused"});
  v.Value("allocation_stride", o.allocation_stride, {"px", "ray sampling that creates blocks"});
  v.Value("min_weight", o.min_weight, {"views", "a voxel needs to be surface"});
  v.Value("max_weight", o.max_weight, {"views", "weights stop growing here"});
  v.Value("exclusion_margin_px", o.exclusion_margin_px, {"px", "growth of the removed regions before fusing"});
}

}  // namespace

void RunOptions::Check() const {
  system.Check();
  dense.Check();
}

void VisitOptions(RunOptions& options, OptionVisitor& v) {
  SystemOptions& s = options.system;
  Section(v, "orb", "ORB extraction", s.orb);
  Section(v, "static_orb", "ORB re-extraction outside the removed regions", s.static_orb);
  v.Value("reextract_removed_share", s.reextract_removed_share, {"", "re-extract when this share of keypoints was removed"});
  v.Value("extract_outside_prior", s.extract_outside_prior, {"", "one ORB extraction, outside the network's removal"});
  v.Value("static_orb_removed_share", s.static_orb_removed_share, {"", "... with static_orb when it removes this share of the image"});
  Section(v, "tracker", "frame-to-map tracking", s.tracker);
  Section(v, "mapping", "local mapping", s.mapping);
  Section(v, "dynamic", "moving objects: modes, geometry, fusion", s.dynamic);
  Section(v, "semantic", "the semantic thread", s.semantic);
  v.Value("sequential", s.sequential, {"", "local mapping inline: reproducible bit for bit"});
  v.Value("max_mapping_lag_frames", s.max_mapping_lag_frames,
          {"frames", "threaded: a frame waits for local mapping to finish keyframes this much older (0 = never)"});
  v.Value("max_mapping_wait_ms", s.max_mapping_wait_ms, {"ms", "... at most this long"});
  v.Value("relocalization", s.relocalization, {"", "relocalize a lost camera"});
  v.Value("loop_closing", s.loop_closing, {"", "close loops"});
  v.Value("merge_every_frames", s.merge_every_frames, {"frames", "in a new map: try to merge it every k-th frame"});
  v.Value("merge_agreement_m", s.merge_agreement_m, {"m", "two tries in a row must place the new map this close"});
  v.Value("merge_agreement_deg", s.merge_agreement_deg, {"deg", "... and turned this close"});
  Section(v, "loop", "loop closing", s.loop);
  v.Value("vocabulary", s.vocabulary, {"", "bag-of-words vocabulary (.dlv); empty = the shipped one"});
  v.Value("keep_keyframe_images", s.keep_keyframe_images, {"", "keep keyframe images for the dense map"});
  v.Value("localization_only", s.localization_only, {"", "never add keyframes (a loaded map)"});
  Section(v, "dense", "the dense map", options.dense);
}

}  // namespace dlslam::config
