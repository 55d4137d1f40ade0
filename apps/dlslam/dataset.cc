// `dlslam dataset list` and `dlslam dataset fetch NAME... --to DIR`.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli_checks.h"
#include "commands.h"
#include "dlslam/datasets/catalogue.h"
#include "dlslam/datasets/fetch.h"
#include "dlslam/util/check.h"

namespace dlslam::app {
namespace {

struct FetchArgs {
  std::vector<std::string> names;
  std::string dir;
  datasets::FetchOptions options;
  bool quiet = false;
};

void PrintList(bool json) {
  if (json) {
    std::printf("%s\n", datasets::CatalogueJson().c_str());
    return;
  }
  std::printf("%-34s %-52s %-18s %s\n", "SHORT NAME", "NAME", "CATEGORY", "SIZE");
  for (const datasets::SequenceInfo& info : datasets::Catalogue()) {
    const std::string size =
        info.size_bytes > 0 ? fmt::format("{:.1f} MiB", static_cast<double>(info.size_bytes) / (1 << 20)) : "?";
    std::printf("%-34s %-52s %-18s %s\n", datasets::ShortName(info).c_str(), info.name.c_str(),
                (std::string(datasets::CollectionName(info.collection)) + "/" + info.category).c_str(),
                size.c_str());
  }
  std::printf("%zu sequences (SIZE ?: not recorded; checked against the server when fetched).\n"
              "Fetch one with: dlslam dataset fetch fr3/walking_xyz --to DIR\n",
              datasets::Catalogue().size());
}

void RunFetch(FetchArgs& args) {
  if (args.quiet) {
    args.options.download.show_progress = false;
    spdlog::set_level(spdlog::level::warn);
  }
  if (args.names.size() > 1 && (!args.options.sha256.empty() || !args.options.md5.empty())) {
    throw Error("--sha256 / --md5 check one archive: give a single sequence name with them");
  }
  args.options.dir = args.dir;
  // Resolve every name first: a typo in the third name should not wait for two downloads.
  std::vector<const datasets::SequenceInfo*> sequences;
  for (const std::string& name : args.names) sequences.push_back(&datasets::FindSequence(name));
  for (const datasets::SequenceInfo* info : sequences) {
    const datasets::FetchResult r = datasets::FetchSequence(*info, args.options);
    if (r.already_present) {
      spdlog::info("{}: already present in {}", info->name, r.sequence_dir.string());
    } else {
      spdlog::info("{}: ready in {} ({} files, {:.1f} MiB)", info->name, r.sequence_dir.string(),
                   r.extracted.files, static_cast<double>(r.extracted.bytes) / (1 << 20));
    }
  }
}

}  // namespace

void AddDatasetCommand(CLI::App& app) {
  CLI::App* dataset = app.add_subcommand("dataset", "Public RGB-D sequences: list and fetch (TUM RGB-D, Bonn)");
  dataset->require_subcommand(1);

  CLI::App* list = dataset->add_subcommand("list", "Print the catalogue of known sequences");
  auto json = std::make_shared<bool>(false);
  list->add_flag("--json", *json, "Print JSON instead of a table");
  list->callback([json] { PrintList(*json); });

  CLI::App* fetch = dataset->add_subcommand(
      "fetch", "Download, verify and unpack sequences into DIR/<name> (resumable; see docs/datasets-fetch.md)");
  auto args = std::make_shared<FetchArgs>();
  fetch->add_option("names", args->names, "Sequence names: fr3/walking_xyz, bonn/crowd, rgbd_bonn_crowd, ...")
      ->required();
  fetch->add_option("--to", args->dir, "Folder that receives DIR/<name> (created when missing)")->required();
  fetch->add_option("--base-url", args->options.base_url,
                    "Server prefix replacing the default (a mirror with the same layout)");
  fetch->add_option("--sha256", args->options.sha256, "Expected SHA-256 of the archive (hex)");
  fetch->add_option("--md5", args->options.md5, "Expected MD5 of the archive (hex)");
  fetch->add_flag("--keep-archive", args->options.keep_archive, "Keep the archive after unpacking");
  fetch->add_flag("-q,--quiet", args->quiet, "No progress bar, warnings and errors only");
  fetch->add_option("--retries", args->options.download.max_retries,
                    "Retries after a transient network error, with back-off")
      ->capture_default_str()->check(WholeNumber(0, 100));
  fetch->add_option("--connect-timeout", args->options.download.connect_timeout_s,
                    "Seconds allowed to open a connection")
      ->capture_default_str()->check(RealNumber(0.1, 3600));
  fetch->callback([args] { RunFetch(*args); });
}

}  // namespace dlslam::app
