// `dlslam run` with the dynamic modes, run as a user runs it: the report's
// "dynamic" object, the semantic prior sources, and bad values refused with a
// clear message and a non-zero exit.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>

#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "dlslam/io/sequence.h"
#include "dlslam/io/sequence_writer.h"
#include "dlslam/synth/actors.h"
#include "dlslam/synth/sequence.h"
#include "tests/support/cli_run.h"
#include "tests/support/test_data.h"

namespace dlslam {
namespace {

namespace fs = std::filesystem;
using ::testing::AllOf;
using ::testing::HasSubstr;
using dlslam::testing::CliRun;
using dlslam::testing::Quoted;

// Runs the CLI through the shell, stdout and stderr together.
CliRun Cli(const std::string& args) {
  return dlslam::testing::RunShell(Quoted(DLSLAM_CLI_PATH) + " " + args + " 2>&1");
}

class RunCliTest : public ::testing::Test {
 protected:
  // 40 frames of walking_xyz with ground-truth masks, written once.
  static void SetUpTestSuite() {
    root_ = new fs::path(testing::MakeTempDir("run_cli"));
    synth::SynthOptions options;
    options.preset = synth::Preset::kWalkingXyz;
    options.frames = 40;
    options.seed = 3;
    const synth::SynthSequence sequence(options);
    io::SequenceWriterOptions write;
    io::SequenceWriter writer(*root_ / "walk", options.camera, write);
    for (int i = 0; i < sequence.size(); ++i) {
      const synth::RenderedFrame f = sequence.Render(i);
      writer.Add(sequence.camera_path()[i].timestamp, f.colour, f.depth, f.mask, f.world_from_cam);
    }
    writer.Finish();
  }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete root_;
  }
  void SetUp() override { out_ = testing::MakeTempDir("run_cli_out"); }
  void TearDown() override { fs::remove_all(out_); }

  static fs::path Walk() { return *root_ / "walk"; }
  std::string RunArgs(const fs::path& sequence, const std::string& extra) const {
    return "run --sequence " + Quoted(sequence) + " --out " + Quoted(out_ / "t.txt") + " --sequential " + extra;
  }
  nlohmann::json Report(const std::string& name) const {
    nlohmann::json j;
    std::ifstream(out_ / name) >> j;
    return j;
  }

  static fs::path* root_;
  fs::path out_;
};

fs::path* RunCliTest::root_ = nullptr;

TEST_F(RunCliTest, BadModeSearchAndFusionNamesAreRefused) {
  for (const std::string bad : {"--mode dyna", "--geometry-search random", "--fusion intersection"}) {
    const CliRun run = Cli(RunArgs(Walk(), bad));
    EXPECT_NE(run.exit_code, 0) << bad;
    EXPECT_THAT(run.output, HasSubstr(bad.substr(bad.find(' ') + 1))) << bad;
    EXPECT_THAT(run.output, HasSubstr("not in")) << run.output;
  }
}

TEST_F(RunCliTest, EveryBadArgumentIsOneErrorLineAndExitStatusOne) {
  // Each was once accepted: -1 wrapped to 2^64 - 1, '' read as 0 or as the
  // current folder, inf gave a 0 ms budget.
  const std::vector<std::pair<std::string, std::string>> cases = {
      {RunArgs(Walk(), "--max-frames -1"), "--max-frames: expected a whole number in 0..1000000000, got '-1'"},
      {RunArgs(Walk(), "--max-frames ''"), "--max-frames: empty value"},
      {RunArgs(Walk(), "--max-frames=''"), "--max-frames: empty value"},
      {RunArgs(Walk(), "--max-frames 18446744073709551616"), "got '18446744073709551616'"},
      {RunArgs(Walk(), "--depth-factor 1e-300"), "--depth-factor: expected a number in [0.01, 100000]"},
      {RunArgs(Walk(), "--settings /dev/null"), "/dev/null: not a regular file"},
      {"bench --camera-hz inf", "--camera-hz: expected a number in [0.1, 1000], got 'inf'"},
      {"bench --config /nonexistent/c.yaml", "/nonexistent/c.yaml: file not found"},
      {"synth --out '' --frames 3", "--out: empty value"},
      {"vocab train --images . --out v.dlv --threads 100000", "--threads: expected a whole number in 0..256"},
      {RunArgs(Walk(), "--view=70000"), "--view: expected a whole number in 1..65535, got '70000'"},
      {RunArgs(Walk(), "--view-linger -1"), "--view-linger: expected a number in [0, 86400], got '-1'"},
      {RunArgs(Walk(), "--realtime=0"), "--realtime: expected a number in [0.01, 100], got '0'"},
      {"bench --realtime=abc", "--realtime: expected a number in [0.01, 100], got 'abc'"},
      {RunArgs(Walk(), "--removal-images-every 0"), "--removal-images-every: expected a whole number in 1..1000000, got '0'"},
      {RunArgs(Walk(), "--removal-images /dev/null"), "--removal-images /dev/null: exists and is not a folder"},
      {RunArgs(Walk(), "--config /nonexistent/c.yaml"), "/nonexistent/c.yaml: file not found"},
      {"config check /nonexistent/c.yaml", "/nonexistent/c.yaml: file not found"},
      {"nosuchcmd", "unknown command 'nosuchcmd'"},
      {"run --sequence " + std::string(300, 'a'), "File name too long"},
  };
  for (const auto& [args, expected] : cases) {
    const CliRun run = Cli(args);
    EXPECT_EQ(run.exit_code, 1) << args << "\n" << run.output;
    EXPECT_THAT(run.output, HasSubstr("[error] ")) << args;
    EXPECT_THAT(run.output, HasSubstr(expected)) << args;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << args << "\n" << run.output;
  }
}

TEST_F(RunCliTest, SemanticModesUseTheNetworkUnlessGivenMasks) {
  // Default prior: the shipped segmentation network in its worker thread.
  CliRun run = Cli(RunArgs(Walk(), "--mode semantic --max-frames 4 --report " + Quoted(out_ / "net.json")));
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("semantic prior: the segmentation network, every frame"));
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(out_ / "net.json"));
  EXPECT_EQ(report["timing_ms"]["semantic"]["count"].get<int>(), 4) << report["timing_ms"].dump();
  EXPECT_GT(report["dynamic"]["semantic_ms"]["median"].get<double>(), 0.0);
  // A broken model is named; the run does not start.
  std::ofstream(out_ / "broken.onnx") << "not an onnx model";
  run = Cli(RunArgs(Walk(), "--mode full --semantic-model " + Quoted(out_ / "broken.onnx")));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, AllOf(HasSubstr("[error]"), HasSubstr("broken.onnx")));
  run = Cli(RunArgs(Walk(), "--mode full --semantic-masks " + Quoted(out_ / "nope")));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, AllOf(HasSubstr("nope"), HasSubstr("--semantic-masks: not a folder")));
}

TEST_F(RunCliTest, GroundTruthPriorNeedsMasks) {
  // The same sequence without its mask list.
  const fs::path copy = out_ / "no_masks";
  fs::copy(Walk(), copy, fs::copy_options::recursive);
  fs::remove(copy / "mask.txt");
  const CliRun run = Cli(RunArgs(copy, "--mode semantic --semantic-masks gt"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, AllOf(HasSubstr("mask.txt"), HasSubstr("needs the sequence's ground-truth masks")));
}

TEST_F(RunCliTest, FolderPriorWithAMissingMaskNamesIt) {
  const fs::path masks = out_ / "masks";
  fs::create_directories(masks);
  const io::RgbdSequence sequence = io::RgbdSequence::Open(Walk());
  const fs::path first = sequence.frames()[0].rgb.path;
  cv::imwrite((masks / first.filename()).string(), cv::Mat(480, 640, CV_8UC1, cv::Scalar(0)));
  const CliRun run = Cli(RunArgs(Walk(), "--mode semantic --semantic-masks " + Quoted(masks)));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, AllOf(HasSubstr("rgb.txt:5: mask image"), HasSubstr("file not found")));
}

TEST_F(RunCliTest, ReportCountsRelocalizationsAndVocabularyErrorsAreClear) {
  const CliRun run = Cli(RunArgs(Walk(), "--max-frames 5 --report " + Quoted(out_ / "r.json")));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json j = Report("r.json");
  EXPECT_EQ(j.at("relocalizations").get<int>(), 0);  // never lost on this walk
  EXPECT_EQ(j.at("loops_closed").get<int>(), 0);
  EXPECT_EQ(Cli(RunArgs(Walk(), "--max-frames 5 --no-relocalization")).exit_code, 0);
  {
    std::ofstream bad(out_ / "bad.dlv");
    bad << "not a vocabulary";
  }
  const CliRun broken = Cli(RunArgs(Walk(), "--max-frames 5 --vocabulary " + Quoted(out_ / "bad.dlv")));
  EXPECT_NE(broken.exit_code, 0);
  EXPECT_THAT(broken.output, HasSubstr("bad.dlv")) << broken.output;
  const CliRun missing = Cli(RunArgs(Walk(), "--max-frames 5 --vocabulary " + Quoted(out_ / "none.dlv")));
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_THAT(missing.output, HasSubstr("none.dlv")) << missing.output;
}

TEST_F(RunCliTest, ReportHasTheDynamicObject) {
  const CliRun run = Cli(RunArgs(Walk(), "--mode full --semantic-masks gt --report " + Quoted(out_ / "r.json")));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json j = Report("r.json");
  for (const char* key : {"frames", "frames_tracked", "keyframes", "map_points", "timing_ms", "ate"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  const nlohmann::json& d = j.at("dynamic");
  EXPECT_EQ(d.at("mode"), "full");
  EXPECT_EQ(d.at("search"), "ant");
  EXPECT_EQ(d.at("fusion"), "union");
  EXPECT_GT(d.at("keypoints_tested").get<int>(), 0);
  EXPECT_GT(d.at("keypoints_removed").get<int>(), 0);
  EXPECT_GE(d.at("keypoints_tested").get<int>(), d.at("keypoints_dynamic").get<int>());
  for (const char* stage : {"geometry_ms", "semantic_ms", "semantic_wait_ms"}) {
    ASSERT_TRUE(d.at(stage).is_object()) << stage;
    EXPECT_GE(d.at(stage).at("p95").get<double>(), d.at(stage).at("median").get<double>()) << stage;
  }
  EXPECT_EQ(d.at("frames_with_truth"), 40);
  const double precision = d.at("precision");
  const double recall = d.at("recall");
  const double tp = d.at("true_positives"), fp = d.at("false_positives"), fn = d.at("false_negatives");
  EXPECT_DOUBLE_EQ(precision, tp / (tp + fp));
  EXPECT_DOUBLE_EQ(recall, tp / (tp + fn));
  EXPECT_TRUE(j.at("timing_ms").contains("geometry"));
}

TEST_F(RunCliTest, RealtimePlaysAtTheCamerasPaceAndReportsLatency) {
  // 40 frames at 30 Hz, played at twice the camera's speed: at least 0.65 s.
  const auto start = std::chrono::steady_clock::now();
  const CliRun run = Cli(RunArgs(Walk(), "--mode orb --realtime=2 --report " + Quoted(out_ / "r.json")));
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_GE(wall_s, 39.0 / 30.0 / 2.0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("latency from arrival to pose"));
  const nlohmann::json j = Report("r.json");
  EXPECT_EQ(j.at("realtime_rate"), 2.0);
  const nlohmann::json& latency = j.at("timing_ms").at("latency");
  EXPECT_GE(latency.at("median").get<double>(), 0.0);
  EXPECT_EQ(j.at("frames_tracked").get<int>() + j.at("frames_coasted").get<int>() +
                j.at("pose_sources").at("none").get<int>(),
            40);
}

TEST_F(RunCliTest, RealtimeDropsTheFramesItHadNoTimeFor) {
  // At 100x the camera's speed a frame arrives every 0.3 ms: most are
  // overwritten while one is tracked, and have no pose.
  const CliRun run = Cli(RunArgs(Walk(), "--mode orb --realtime=100 --report " + Quoted(out_ / "r.json")));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json j = Report("r.json");
  const int dropped = j.at("frames_dropped");
  EXPECT_GT(dropped, 10) << run.output;
  EXPECT_EQ(j.at("frames"), 40);
  EXPECT_EQ(j.at("frames_tracked").get<int>() + j.at("frames_coasted").get<int>() + j.at("frames_lost").get<int>() +
                j.at("frames_waiting").get<int>() + dropped,
            40);
  std::ifstream sources(out_ / "t.sources.txt");
  int none = 0;
  for (std::string line; std::getline(sources, line);) none += line.find(" none") != std::string::npos;
  EXPECT_GE(none, dropped);
}

TEST_F(RunCliTest, DenseMapIsAPlyWithoutThePeople) {
  const CliRun run = Cli(RunArgs(Walk(), "--mode full --semantic-masks gt --dense-map " + Quoted(out_ / "room.ply") +
                                             " --report " + Quoted(out_ / "r.json")));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json d = Report("r.json").at("dense_map");
  const std::size_t points = d.at("points");
  EXPECT_GT(points, 10000u);
  EXPECT_LT(d.at("people_share").get<double>(), 0.001);  // the synth masks are known
  std::ifstream ply(out_ / "room.ply", std::ios::binary);
  std::string line;
  std::getline(ply, line);
  EXPECT_EQ(line, "ply");
  const std::size_t header = [&] {
    std::string text = "ply\n";
    while (std::getline(ply, line) && line != "end_header") text += line + "\n";
    return text.size() + std::string("end_header\n").size();
  }();
  EXPECT_EQ(fs::file_size(out_ / "room.ply"), header + 15 * points);
  // A voxel size out of range is refused like every other flag.
  const CliRun bad = Cli(RunArgs(Walk(), "--dense-map " + Quoted(out_ / "x.ply") + " --dense-voxel 0"));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_THAT(bad.output, HasSubstr("--dense-voxel"));
  EXPECT_FALSE(fs::exists(out_ / "x.ply"));
}

TEST_F(RunCliTest, SaveLoadAndLocalizeInAMap) {
  const std::string map = Quoted(out_ / "walk.dlmap");
  const CliRun save = Cli(RunArgs(Walk(), "--save-map " + map));
  ASSERT_EQ(save.exit_code, 0) << save.output;
  EXPECT_THAT(save.output, HasSubstr("saved map"));
  const CliRun localize =
      Cli(RunArgs(Walk(), "--load-map " + map + " --localize --report " + Quoted(out_ / "r.json")));
  ASSERT_EQ(localize.exit_code, 0) << localize.output;
  const nlohmann::json j = Report("r.json");
  EXPECT_EQ(j.at("map_file").at("localization_only"), true);
  EXPECT_GE(j.at("map_file").at("load_ms").get<double>(), 0.0);
  EXPECT_EQ(j.at("frames_posed"), 40);
  // --localize needs a map; a corrupt map names its file and offset.
  const CliRun alone = Cli(RunArgs(Walk(), "--localize"));
  EXPECT_EQ(alone.exit_code, 1);
  EXPECT_THAT(alone.output, HasSubstr("--load-map"));
  {
    std::fstream f(out_ / "walk.dlmap", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(100);
    f.put('\x7f');
  }
  const CliRun corrupt = Cli(RunArgs(Walk(), "--load-map " + map));
  EXPECT_EQ(corrupt.exit_code, 1);
  EXPECT_THAT(corrupt.output, AllOf(HasSubstr("walk.dlmap"), HasSubstr("checksum mismatch"), HasSubstr("offset")));
}

TEST_F(RunCliTest, OneConfigFileForEveryOption) {
  // The dump alone on stdout, a valid file.
  const CliRun dump = dlslam::testing::RunShell(Quoted(DLSLAM_CLI_PATH) + " config dump 2>/dev/null");
  ASSERT_EQ(dump.exit_code, 0);
  EXPECT_THAT(dump.output, HasSubstr("min_local_map_inliers: 30  # [inliers]"));
  std::ofstream(out_ / "all.yaml") << dump.output;
  EXPECT_EQ(Cli("config check " + Quoted(out_ / "all.yaml")).exit_code, 0);
  // The file sets the options; flags given override it; the report records them.
  std::ofstream(out_ / "c.yaml") << "dynamic:\n  mode: full\n  fusion:\n    dilation_px: 7\ntracker:\n  max_jump_speed: 6\n";
  const CliRun run = Cli(RunArgs(Walk(), "--config " + Quoted(out_ / "c.yaml") + " --semantic-masks gt --report " +
                                             Quoted(out_ / "r.json")));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  nlohmann::json j = Report("r.json");
  EXPECT_EQ(j.at("options").at("dynamic").at("mode"), "full");
  EXPECT_EQ(j.at("options").at("dynamic").at("fusion").at("dilation_px"), 7.0);
  EXPECT_EQ(j.at("options").at("tracker").at("max_jump_speed"), 6.0);
  EXPECT_EQ(j.at("dynamic").at("mode"), "full");
  const CliRun flag = Cli(RunArgs(Walk(), "--config " + Quoted(out_ / "c.yaml") + " --mode orb --report " +
                                              Quoted(out_ / "r.json")));
  ASSERT_EQ(flag.exit_code, 0) << flag.output;
  j = Report("r.json");
  EXPECT_EQ(j.at("options").at("dynamic").at("mode"), "orb");
  EXPECT_EQ(j.at("options").at("dynamic").at("fusion").at("dilation_px"), 7.0);
  // A misspelled key: one error line with file:line, exit 1.
  std::ofstream(out_ / "bad.yaml") << "tracker:\n  max_jump_sped: 6\n";
  const CliRun bad = Cli(RunArgs(Walk(), "--config " + Quoted(out_ / "bad.yaml")));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_THAT(bad.output, HasSubstr("bad.yaml:2: unknown key 'tracker.max_jump_sped'; did you mean 'tracker.max_jump_speed'?"));
}

// The HTML report in a real browser: headless Chromium (Debian's chromium,
// installed by scripts/setup.sh) loads the file, runs its script, and the
// page says what it drew and which canvases hold pixels; a screenshot is
// kept in build/test-artifacts/ for people to look at.
TEST_F(RunCliTest, HtmlReportDrawsInABrowser) {
  const CliRun which = dlslam::testing::RunShell("command -v chromium 2>/dev/null");
  if (which.exit_code != 0) GTEST_SKIP() << "chromium is not installed (scripts/setup.sh installs it)";
  const fs::path page = out_ / "report.html";
  const CliRun run = Cli(RunArgs(Walk(), "--mode full --semantic-masks gt --html " + Quoted(page)));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string browser =
      "chromium --headless --no-sandbox --disable-gpu --disable-dev-shm-usage --no-first-run --user-data-dir=" +
      Quoted(out_ / "profile") + " ";
  const CliRun dom = dlslam::testing::RunShell(browser + "--dump-dom " + Quoted("file://" + page.string()) + " 2>/dev/null");
  ASSERT_EQ(dom.exit_code, 0);
  EXPECT_THAT(dom.output, HasSubstr("frames 40, posed 40; drawn: trajectory, error, map, timings; nonblank: trajectory, error, map"));
  const fs::path artifacts = fs::path(DLSLAM_CLI_PATH).parent_path().parent_path() / "test-artifacts";
  fs::create_directories(artifacts);
  const fs::path shot = artifacts / "html_report.png";
  fs::remove(shot);
  const CliRun screenshot = dlslam::testing::RunShell(browser + "--window-size=1400,1300 --screenshot=" + Quoted(shot) +
                                                      " " + Quoted("file://" + page.string()) + " 2>/dev/null");
  ASSERT_EQ(screenshot.exit_code, 0);
  const cv::Mat image = cv::imread(shot.string());
  ASSERT_FALSE(image.empty()) << shot;
  cv::Mat grey, ink;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  cv::threshold(grey, ink, 200, 255, cv::THRESH_BINARY_INV);
  EXPECT_GT(cv::countNonZero(ink), 2000);  // lines and map points even without fonts
}

// The live view in a real browser: a run serves its page on loopback while
// it goes (and for a few seconds after), headless Chromium loads it and
// lets the page poll; the page must have drawn the frame's trajectory, the
// error and the map from the running system.
TEST_F(RunCliTest, LiveViewServesThePageWhileRunning) {
  const CliRun which = dlslam::testing::RunShell("command -v chromium 2>/dev/null");
  if (which.exit_code != 0) GTEST_SKIP() << "chromium is not installed (scripts/setup.sh installs it)";
  const int port = dlslam::testing::FreeTcpPort();
  const fs::path log = out_ / "run.log";
  const std::string url = "http://127.0.0.1:" + std::to_string(port) + "/";
  const std::string browser =
      "chromium --headless --no-sandbox --disable-gpu --disable-dev-shm-usage --no-first-run --user-data-dir=" +
      Quoted(out_ / "profile") + " --virtual-time-budget=3000 ";
  const fs::path artifacts = fs::path(DLSLAM_CLI_PATH).parent_path().parent_path() / "test-artifacts";
  fs::create_directories(artifacts);
  const fs::path shot = artifacts / "live_view.png";
  fs::remove(shot);
  // The run in the background, lingering; the browser once the page is up;
  // then the run is stopped (its frames are done and its files written by then).
  const std::string script =
      Quoted(DLSLAM_CLI_PATH) + " " + RunArgs(Walk(), "--mode full --semantic-masks gt --view=" + std::to_string(port) + " --view-linger 60") +
      " 2>" + Quoted(log) + " & pid=$!; for i in $(seq 1 300); do grep -q 'serving for' " + Quoted(log) +
      " && break; sleep 0.1; done; " + browser + "--dump-dom " + url + " 2>/dev/null; " + browser +
      "--window-size=1400,1800 --screenshot=" + Quoted(shot) + " " + url + " >/dev/null 2>&1; kill $pid; wait $pid";
  const CliRun run = dlslam::testing::RunShell(script);
  EXPECT_THAT(run.output, HasSubstr("drawn: trajectory, error, map, timings; nonblank: trajectory, error, map"));
  EXPECT_THAT(run.output, HasSubstr("frames 40, posed 40"));  // every frame done, the page lingers
  EXPECT_TRUE(fs::exists(shot));
  EXPECT_TRUE(fs::exists(out_ / "t.txt"));  // written before the view lingers
  std::ifstream in(log);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_THAT(text, HasSubstr("live view on " + url));
}

TEST_F(RunCliTest, FolderPriorEqualsTheGroundTruthPrior) {
  // The person masks written as a folder source give the same removal.
  const fs::path masks = out_ / "masks";
  fs::create_directories(masks);
  const io::RgbdSequence sequence = io::RgbdSequence::Open(Walk());
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    const cv::Mat labels = sequence.LoadFrame(i).mask;
    cv::Mat person;
    cv::compare(labels & 0x7F, synth::kClassPerson, person, cv::CMP_EQ);
    cv::imwrite((masks / (sequence.frames()[i].rgb.path.stem().string() + ".png")).string(), person);
  }
  ASSERT_EQ(Cli(RunArgs(Walk(), "--mode semantic --semantic-masks gt --report " + Quoted(out_ / "gt.json"))).exit_code, 0);
  ASSERT_EQ(Cli(RunArgs(Walk(), "--mode semantic --semantic-masks " + Quoted(masks) + " --report " +
                                    Quoted(out_ / "dir.json")))
                .exit_code,
            0);
  const nlohmann::json gt = Report("gt.json").at("dynamic");
  const nlohmann::json dir = Report("dir.json").at("dynamic");
  // The prior's pixels are left out of the extraction: measured as pixels.
  EXPECT_GT(gt.at("image_share_removed").get<double>(), 0.01);
  EXPECT_EQ(gt.at("image_share_removed"), dir.at("image_share_removed"));
  EXPECT_EQ(gt.at("keypoints_removed"), dir.at("keypoints_removed"));
  EXPECT_EQ(gt.at("true_positives"), dir.at("true_positives"));
  EXPECT_EQ(gt.at("keypoints_tested"), 0);  // no geometry in mode semantic
}

// --removal-images: every k-th frame as the dynamic stage saw it, named like
// its colour image; the network prior's region is tinted red. A folder with
// files in it is refused (nothing overwritten). No live view unless asked.
TEST_F(RunCliTest, RemovalImagesShowThePriorsRegion) {
  const fs::path pictures = out_ / "removal";
  const CliRun run = Cli(RunArgs(Walk(), "--mode full --semantic-masks gt --removal-images " + Quoted(pictures) +
                                             " --removal-images-every 10 2>&1"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, Not(HasSubstr("live view")));
  const io::RgbdSequence sequence = io::RgbdSequence::Open(Walk());
  int with_people = 0;
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    const fs::path file = pictures / (sequence.frames()[i].rgb.path.stem().string() + ".jpg");
    ASSERT_EQ(fs::exists(file), i % 10 == 0) << file;
    if (i % 10 != 0) continue;
    const cv::Mat picture = cv::imread(file.string(), cv::IMREAD_COLOR);
    const io::RgbdFrame frame = sequence.LoadFrame(i);
    ASSERT_EQ(picture.size(), frame.color.size());
    cv::Mat person;
    cv::compare(frame.mask & 0x7F, synth::kClassPerson, person, cv::CMP_EQ);
    cv::erode(person, person, cv::Mat(), cv::Point(-1, -1), 3);  // clear of JPEG ringing at the outline
    if (cv::countNonZero(person) < 500) continue;
    ++with_people;
    std::vector<cv::Mat> drawn, original;
    cv::split(picture, drawn);
    cv::split(frame.color, original);
    // Red up, blue down inside the person: tinted towards (60, 60, 230) BGR.
    EXPECT_GT(cv::mean(drawn[2], person)[0], cv::mean(original[2], person)[0] + 15) << file;
    EXPECT_LT(cv::mean(drawn[0], person)[0], cv::mean(original[0], person)[0]) << file;
  }
  EXPECT_GT(with_people, 0);
  const CliRun again = Cli(RunArgs(Walk(), "--mode full --semantic-masks gt --removal-images " + Quoted(pictures) + " 2>&1"));
  EXPECT_NE(again.exit_code, 0);
  EXPECT_THAT(again.output, HasSubstr("not empty"));
  EXPECT_THAT(again.output, HasSubstr(pictures.string()));
}

// `dlslam bench`: every mode asked for, timed stage by stage, in bench.json.
TEST_F(RunCliTest, BenchTimesEachModeAndWritesJson) {
  const CliRun run = Cli("bench --sequence " + Quoted(Walk()) + " --modes orb,geometry --sequential --out " +
                         Quoted(out_ / "bench"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, AllOf(HasSubstr("frame_total"), HasSubstr("real-time factor"), HasSubstr("geometry")));
  nlohmann::json j;
  std::ifstream(out_ / "bench" / "bench.json") >> j;
  ASSERT_EQ(j.at("runs").size(), 2u);
  EXPECT_EQ(j.at("threads"), "sequential");
  for (const nlohmann::json& r : j.at("runs")) {
    EXPECT_EQ(r.at("frames"), 40);
    EXPECT_EQ(r.at("stages_ms").at("frame_total").at("count"), 40);
    EXPECT_GT(r.at("stages_ms").at("orb_extraction").at("median").get<double>(), 0.0);
    EXPECT_GT(r.at("realtime_factor").get<double>(), 0.0);
    EXPECT_TRUE(r.at("ate_rmse").is_number());
  }
  EXPECT_EQ(j.at("runs")[1].at("mode"), "geometry");
  EXPECT_GT(j.at("runs")[1].at("stages_ms").at("geometry").at("count").get<int>(), 0);
  EXPECT_TRUE(fs::exists(out_ / "bench" / "orb_report.json"));
}

// A config file sets bench's runs as it sets dlslam run's; the modes stay bench's.
TEST_F(RunCliTest, BenchRunsWithAConfigFile) {
  std::ofstream(out_ / "bench.yaml") << "dynamic:\n  mode: full\ntracker:\n  max_jump_speed: 6\nmapping:\n  thread_nice: 3\n";
  const CliRun run = Cli("bench --sequence " + Quoted(Walk()) + " --modes orb --max-frames 20 --config " +
                         Quoted(out_ / "bench.yaml") + " --out " + Quoted(out_ / "bench"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  nlohmann::json j;
  std::ifstream(out_ / "bench" / "orb_report.json") >> j;
  EXPECT_EQ(j.at("options").at("dynamic").at("mode"), "orb");
  EXPECT_EQ(j.at("options").at("tracker").at("max_jump_speed"), 6.0);
  EXPECT_EQ(j.at("options").at("mapping").at("thread_nice"), 3);
  // A bad value or a misspelled key: one error with file and line, exit 1.
  std::ofstream(out_ / "bad_bench.yaml") << "mapping:\n  thread_nice: 25\n";
  const CliRun bad = Cli("bench --sequence " + Quoted(Walk()) + " --modes orb --max-frames 5 --config " +
                         Quoted(out_ / "bad_bench.yaml") + " --out " + Quoted(out_ / "bench_bad"));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_THAT(bad.output, AllOf(HasSubstr("thread_nice"), HasSubstr("25"))) << bad.output;
  std::ofstream(out_ / "typo_bench.yaml") << "tracker:\n  max_jump_sped: 6\n";
  const CliRun typo = Cli("bench --sequence " + Quoted(Walk()) + " --modes orb --max-frames 5 --config " +
                          Quoted(out_ / "typo_bench.yaml") + " --out " + Quoted(out_ / "bench_typo"));
  EXPECT_EQ(typo.exit_code, 1);
  EXPECT_THAT(typo.output, HasSubstr("typo_bench.yaml:2: unknown key 'tracker.max_jump_sped'")) << typo.output;
}

TEST_F(RunCliTest, BenchRefusesUnknownModes) {
  const CliRun run = Cli("bench --sequence " + Quoted(Walk()) + " --modes orb,dyna --out " + Quoted(out_ / "b"));
  EXPECT_NE(run.exit_code, 0);
  EXPECT_THAT(run.output, HasSubstr("unknown mode 'dyna'")) << run.output;
  EXPECT_FALSE(fs::exists(out_ / "b" / "bench.json"));
}

}  // namespace
}  // namespace dlslam
