// Rendering speed: one 640x480 frame of a walking sequence (rasterise, shade,
// masks, sensor noise), without PNG writing.
#include <benchmark/benchmark.h>

#include "dlslam/synth/sequence.h"

namespace {

void BM_RenderFrame(benchmark::State& state) {
  dlslam::synth::SynthOptions options;
  options.preset = static_cast<dlslam::synth::Preset>(state.range(0));
  options.frames = 64;
  const dlslam::synth::SynthSequence sequence(options);
  int i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(sequence.Render(i));
    i = (i + 7) % sequence.size();
  }
}
BENCHMARK(BM_RenderFrame)
    ->Arg(static_cast<int>(dlslam::synth::Preset::kWalkingXyz))
    ->Arg(static_cast<int>(dlslam::synth::Preset::kSittingStatic))
    ->Unit(benchmark::kMillisecond);

void BM_BuildScene(benchmark::State& state) {
  for (auto _ : state) {
    benchmark::DoNotOptimize(dlslam::synth::BuildScene(dlslam::synth::Preset::kWalkingXyz, 1));
  }
}
BENCHMARK(BM_BuildScene)->Unit(benchmark::kMillisecond);

}  // namespace
