#pragma once
// The subcommands of the `dlslam` tool, one file each. Every Add*Command
// registers a CLI11 subcommand whose callback does the work; errors are
// thrown and turned into a message and a non-zero exit by main().

#include <CLI/CLI.hpp>

namespace dlslam::app {

void AddDemoCommand(CLI::App& app);     // demo.cc: the bundled default run
void AddEvalCommand(CLI::App& app);     // eval.cc: ATE / RPE as the TUM tools
void AddSynthCommand(CLI::App& app);    // synth.cc: synthetic dynamic RGB-D sequences
void AddDatasetCommand(CLI::App& app);  // dataset.cc: fetch TUM / Bonn sequences
void AddInfoCommand(CLI::App& app);     // info.cc: what a sequence folder holds
void AddRunCommand(CLI::App& app);      // run.cc: SLAM on a sequence
void AddConfigCommand(CLI::App& app);   // config_cmd.cc: config dump / check
void AddVocabCommand(CLI::App& app);    // vocab.cc: bag-of-words vocabularies (train, info)
void AddSegmentCommand(CLI::App& app);  // segment.cc: dynamic-object masks from the segmentation network
void AddBenchCommand(CLI::App& app);    // bench.cc: the whole system timed stage by stage, per mode
void AddCompositeCommand(CLI::App& app);  // composite.cc: real people walked through a real static sequence

}  // namespace dlslam::app
