#pragma once
// Procedural textures for the synthetic room and its people. Built for
// feature detectors: high-contrast shapes at many scales (log-uniform sizes),
// irregular layouts and printed text, so that FAST/ORB find many distinct,
// well-spread corners, and no regular checkerboards that would make matches
// ambiguous.

#include <opencv2/core.hpp>

#include <random>

namespace dlslam::synth {

enum class TextureStyle {
  kWall,       // painted plaster with posters, notes, frames and a whiteboard
  kFloor,      // carpet with speckles, marks and taped lines
  kCeiling,    // ceiling panels with vents
  kWood,       // wood grain with stickers and labels
  kCardboard,  // brown cardboard with printed labels and tape
  kBooks,      // shelf contents: spines of random widths and colours, with titles
  kClothing,   // shirts: base colour with prints, stripes of random width, logos
  kTrousers,   // denim-like weave with seams and pockets
  kHead,       // skin, hair on top and back, a face in the middle column (capsule front)
  kSkin,       // bare arms and hands
  kDevice,     // monitors, cabinets: dark plastic with stickers and a screen
};

// A width x height 8-bit BGR image (both powers of two) of the given style.
// `texels_per_metre` tells styles with real-sized features (the face) how
// big to draw them.
cv::Mat MakeTextureImage(TextureStyle style, int width, int height, double texels_per_metre,
                         std::mt19937& rng);

}  // namespace dlslam::synth
