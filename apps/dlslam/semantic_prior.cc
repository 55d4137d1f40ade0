#include "semantic_prior.h"

#include "dlslam/io/image_io.h"
#include "dlslam/synth/actors.h"
#include "dlslam/synth/renderer.h"
#include "dlslam/util/check.h"
#include "dlslam/util/timing.h"

namespace dlslam::app {

namespace {

namespace fs = std::filesystem;

class GroundTruthPriorSource : public SemanticPriorSource {
 public:
  SemanticPrior Prior(std::size_t /*index*/, const io::RgbdFrame& frame) override {
    Stopwatch watch;
    SemanticPrior prior;
    // A frame without a mask gets no prior (and no statistics).
    if (!frame.mask.empty()) {
      prior.mask = ClassMaskFromLabels(frame.mask, synth::kClassPerson);
      prior.movable = ClassMaskFromLabels(frame.mask, synth::kClassMovable);
    }
    prior.compute_ms = watch.ElapsedMs();
    return prior;
  }
  std::string Describe() const override {
    return "the sequence's ground-truth masks (class person; movable: other movable objects)";
  }
};

class FolderPriorSource : public SemanticPriorSource {
 public:
  // `sequence` outlives the source.
  FolderPriorSource(fs::path dir, const io::RgbdSequence& sequence) : dir_(std::move(dir)), sequence_(sequence) {}

  SemanticPrior Prior(std::size_t index, const io::RgbdFrame& /*frame*/) override {
    DLSLAM_CHECK_LT(index, sequence_.size());
    Stopwatch watch;
    const io::ListedImage& rgb = sequence_.frames()[index].rgb;
    const io::ImageSource source{dir_ / (rgb.path.stem().string() + ".png"), rgb.list_file, rgb.line};
    SemanticPrior prior;
    prior.mask = io::ReadMaskImage(source, sequence_.camera().width, sequence_.camera().height);
    prior.compute_ms = watch.ElapsedMs();
    return prior;
  }
  std::string Describe() const override { return "masks in " + dir_.string(); }

 private:
  fs::path dir_;
  const io::RgbdSequence& sequence_;
};

}  // namespace

std::unique_ptr<SemanticPriorSource> MakeSemanticPriorSource(const std::string& spec,
                                                             const io::RgbdSequence& sequence) {
  if (spec == "gt") {
    if (!sequence.has_masks()) {
      throw InputError(sequence.folder() / "mask.txt", 0,
                       "--semantic-masks gt needs the sequence's ground-truth masks (mask.txt and mask/, "
                       "as dlslam synth writes them); this sequence has {}",
                       sequence.mask_list().empty() ? "none" : "none near its frame times");
    }
    return std::make_unique<GroundTruthPriorSource>();
  }
  const fs::path dir(spec);
  if (!fs::is_directory(dir)) {
    throw InputError(dir, 0, "--semantic-masks: not a folder (give 'gt' or a folder of PNG masks named like the "
                             "colour images)");
  }
  return std::make_unique<FolderPriorSource>(dir, sequence);
}

cv::Mat MovingTruthFromLabels(const cv::Mat& labels) {
  DLSLAM_CHECK_EQ(labels.type(), CV_8UC1, "label images are 8-bit single-channel");
  cv::Mat moving;
  cv::bitwise_and(labels, cv::Scalar(synth::kMaskMovingBit), moving);
  return moving != 0;  // 255 where the moving bit is set
}

cv::Mat ClassMaskFromLabels(const cv::Mat& labels, int class_id) {
  DLSLAM_CHECK_EQ(labels.type(), CV_8UC1, "label images are 8-bit single-channel");
  cv::Mat classes;
  cv::bitwise_and(labels, cv::Scalar(0x7F), classes);  // drop the moving bit (synth::MaskClass)
  return classes == class_id;
}

}  // namespace dlslam::app
