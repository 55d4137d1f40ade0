#include "dlslam/synth/texture_styles.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "dlslam/synth/random.h"

namespace dlslam::synth {

namespace {

using Rng = std::mt19937;

cv::Scalar RandomColour(Rng& rng, int lo = 0, int hi = 255) {
  return cv::Scalar(UniformInt(rng, lo, hi), UniformInt(rng, lo, hi), UniformInt(rng, lo, hi));
}

cv::Scalar Jitter(Rng& rng, const cv::Scalar& c, int amount) {
  cv::Scalar out;
  for (int i = 0; i < 3; ++i) out[i] = std::clamp(c[i] + UniformInt(rng, -amount, amount), 0.0, 255.0);
  return out;
}

// Smooth low-frequency variation (paint, stains): coarse random values
// upsampled with cubic interpolation.
void AddBlotches(cv::Mat& img, Rng& rng, double amplitude, int cell, bool grey = true) {
  cv::Mat coarse(std::max(2, img.rows / cell), std::max(2, img.cols / cell), grey ? CV_32FC1 : CV_32FC3);
  cv::RNG cv_rng(rng());
  cv_rng.fill(coarse, cv::RNG::NORMAL, 0.0, amplitude);
  cv::Mat fine;
  cv::resize(coarse, fine, img.size(), 0, 0, cv::INTER_CUBIC);
  if (grey) cv::cvtColor(fine, fine, cv::COLOR_GRAY2BGR);
  cv::Mat f;
  img.convertTo(f, CV_32FC3);
  f += fine;
  f.convertTo(img, CV_8UC3);
}

// Per-texel grain (fabric, carpet, plaster): uniform noise of standard
// deviation sigma (the shape does not matter here, and uniform is fast).
void AddGrain(cv::Mat& img, Rng& rng, double sigma) {
  cv::Mat noise(img.size(), CV_16SC3);
  cv::RNG cv_rng(rng());
  const double half_width = sigma * std::sqrt(3.0);
  cv_rng.fill(noise, cv::RNG::UNIFORM, -half_width, half_width + 1);
  cv::Mat s;
  img.convertTo(s, CV_16SC3);
  s += noise;
  s.convertTo(img, CV_8UC3);
}

std::string RandomWord(Rng& rng) {
  static const char kChars[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  std::string w;
  const int n = UniformInt(rng, 2, 9);
  for (int i = 0; i < n; ++i) w += kChars[UniformInt(rng, 0, 35)];
  return w;
}

void DrawText(cv::Mat& img, Rng& rng, cv::Point org, double height_px, const cv::Scalar& colour) {
  const int font = UniformInt(rng, 0, 3);  // Hershey SIMPLEX, PLAIN, DUPLEX, COMPLEX
  const double scale = std::max(0.3, height_px / 22.0);
  cv::putText(img, RandomWord(rng), org, font, scale, colour, std::max(1, static_cast<int>(scale * 1.5)),
              cv::LINE_AA);
}

// One shape of random kind, size about `size` texels.
void DrawShape(cv::Mat& img, Rng& rng, cv::Point2d c, double size, const cv::Scalar& colour) {
  const int kind = UniformInt(rng, 0, 6);
  const cv::Point centre(static_cast<int>(c.x), static_cast<int>(c.y));
  const int s = std::max(1, static_cast<int>(size));
  if (kind == 0) {
    cv::circle(img, centre, s / 2, colour, cv::FILLED, cv::LINE_AA);
  } else if (kind == 1) {
    cv::ellipse(img, centre, cv::Size(s / 2, std::max(1, s / UniformInt(rng, 2, 5))), Uniform(rng, 0, 180),
                0, 360, colour, cv::FILLED, cv::LINE_AA);
  } else if (kind == 2) {
    const int w = UniformInt(rng, s / 3 + 1, s), h = UniformInt(rng, s / 3 + 1, s);
    cv::rectangle(img, cv::Rect(centre.x - w / 2, centre.y - h / 2, w, h), colour, cv::FILLED);
  } else if (kind == 3 || kind == 4) {
    std::vector<cv::Point> poly;
    const int n = kind == 3 ? 3 : UniformInt(rng, 4, 7);
    for (int i = 0; i < n; ++i) {
      const double a = 6.2832 * (i + Uniform(rng, 0, 0.7)) / n;
      const double r = Uniform(rng, 0.25, 0.6) * s;
      poly.emplace_back(centre.x + static_cast<int>(r * std::cos(a)), centre.y + static_cast<int>(r * std::sin(a)));
    }
    cv::fillPoly(img, std::vector<std::vector<cv::Point>>{poly}, colour, cv::LINE_AA);
  } else if (kind == 5) {
    const cv::Point d(UniformInt(rng, -s, s), UniformInt(rng, -s, s));
    cv::line(img, centre - d, centre + d, colour, std::max(1, s / 8), cv::LINE_AA);
  } else {
    DrawText(img, rng, centre, 0.5 * s, colour);
  }
}

// A poster or picture: its own background, shapes of many sizes, a title.
void DrawPoster(cv::Mat& img, Rng& rng, const cv::Rect& wanted) {
  const cv::Rect r = wanted & cv::Rect(0, 0, img.cols, img.rows);
  if (r.width < 4 || r.height < 4) return;
  cv::Mat roi = img(r);
  roi.setTo(RandomColour(rng, 30, 255));
  const int shapes = UniformInt(rng, 8, 30);
  const double big = std::min(r.width, r.height) * 0.6;
  for (int i = 0; i < shapes; ++i) {
    DrawShape(roi, rng, {Uniform(rng, 0, r.width), Uniform(rng, 0, r.height)},
              LogUniform(rng, std::max(3.0, big / 15), big), RandomColour(rng));
  }
  for (int line = UniformInt(rng, 1, 4); line > 0; --line) {
    DrawText(roi, rng, {UniformInt(rng, 0, r.width / 3), UniformInt(rng, r.height / 6, r.height)},
             LogUniform(rng, 6, std::max(7.0, r.height / 6.0)), RandomColour(rng, 0, 90));
  }
  cv::rectangle(img, r, RandomColour(rng, 0, 80), std::max(2, r.width / 40));
}

void Scatter(cv::Mat& img, Rng& rng, int count, double min_size, double max_size, int lo, int hi) {
  for (int i = 0; i < count; ++i) {
    DrawShape(img, rng, {Uniform(rng, 0, img.cols), Uniform(rng, 0, img.rows)},
              LogUniform(rng, min_size, max_size), RandomColour(rng, lo, hi));
  }
}

void Wall(cv::Mat& img, Rng& rng, double ppm) {
  static const cv::Scalar kPaints[] = {{225, 230, 232}, {200, 215, 225}, {190, 220, 205},
                                       {170, 200, 228}, {215, 205, 200}, {185, 185, 190}};
  img.setTo(Jitter(rng, kPaints[UniformInt(rng, 0, 5)], 12));
  AddBlotches(img, rng, 7, 24);
  const double area = img.cols * img.rows / (ppm * ppm);
  for (int i = 0; i < static_cast<int>(1.0 * area); ++i) {  // posters and frames, 0.25-1.1 m
    const int w = static_cast<int>(LogUniform(rng, 0.25, 1.1) * ppm);
    const int h = static_cast<int>(w * Uniform(rng, 0.6, 1.5));
    DrawPoster(img, rng, cv::Rect(UniformInt(rng, 0, img.cols - w), UniformInt(rng, 0, img.rows - h), w, h));
  }
  for (int i = 0; i < static_cast<int>(2.5 * area); ++i) {  // sticky notes, switches, small signs
    const int s = static_cast<int>(LogUniform(rng, 0.05, 0.15) * ppm);
    const cv::Rect r(UniformInt(rng, 0, img.cols - s), UniformInt(rng, 0, img.rows - s), s, s);
    cv::rectangle(img, r, RandomColour(rng, 60, 255), cv::FILLED);
    DrawText(img, rng, {r.x, r.y + s / 2}, s / 3.0, RandomColour(rng, 0, 60));
  }
  Scatter(img, rng, static_cast<int>(10 * area), 3, 0.1 * ppm, 0, 255);  // marks and scribbles
  AddGrain(img, rng, 3);
}

void Floor(cv::Mat& img, Rng& rng, double ppm) {
  img.setTo(RandomColour(rng, 50, 140));
  AddBlotches(img, rng, 14, 16, false);
  const double area = img.cols * img.rows / (ppm * ppm);
  Scatter(img, rng, static_cast<int>(25 * area), 2, 0.25 * ppm, 20, 230);  // stains, marks, debris
  for (int i = 0; i < static_cast<int>(area / 3); ++i) {  // taped lines
    const cv::Point a(UniformInt(rng, 0, img.cols), UniformInt(rng, 0, img.rows));
    const cv::Point d(UniformInt(rng, -img.cols / 3, img.cols / 3), UniformInt(rng, -img.rows / 3, img.rows / 3));
    cv::line(img, a, a + d, cv::Scalar(30, 200, 230), static_cast<int>(0.05 * ppm));
  }
  AddGrain(img, rng, 14);
}

void Ceiling(cv::Mat& img, Rng& rng, double ppm) {
  img.setTo(cv::Scalar(228, 230, 230));
  AddBlotches(img, rng, 6, 32);
  const int panel = static_cast<int>(0.6 * ppm);
  for (int x = UniformInt(rng, 0, panel); x < img.cols; x += panel) cv::line(img, {x, 0}, {x, img.rows}, {150, 150, 150}, 2);
  for (int y = UniformInt(rng, 0, panel); y < img.rows; y += panel + UniformInt(rng, -9, 9)) {
    cv::line(img, {0, y}, {img.cols, y}, {150, 150, 150}, 2);
  }
  Scatter(img, rng, img.cols * img.rows / (panel * panel) * 3, 3, 0.3 * ppm, 60, 240);  // vents, stains
  AddGrain(img, rng, 4);
}

void Wood(cv::Mat& img, Rng& rng, double ppm) {
  cv::Mat streaks(img.rows, std::max(2, img.cols / 64), CV_32FC1);
  cv::RNG cv_rng(rng());
  cv_rng.fill(streaks, cv::RNG::NORMAL, 0.0, 18.0);
  cv::resize(streaks, streaks, img.size(), 0, 0, cv::INTER_CUBIC);
  cv::Mat base(img.size(), CV_32FC3, Jitter(rng, cv::Scalar(60, 100, 150), 35));
  cv::cvtColor(streaks, streaks, cv::COLOR_GRAY2BGR);
  base += streaks;
  base.convertTo(img, CV_8UC3);
  const double area = img.cols * img.rows / (ppm * ppm);
  Scatter(img, rng, static_cast<int>(30 * area) + 4, 4, 0.2 * ppm, 0, 255);  // stickers, labels, marks
  AddGrain(img, rng, 5);
}

void Cardboard(cv::Mat& img, Rng& rng, double ppm) {
  img.setTo(Jitter(rng, cv::Scalar(90, 140, 185), 20));
  AddBlotches(img, rng, 8, 16);
  const int tape = static_cast<int>(0.05 * ppm);
  cv::rectangle(img, cv::Rect(0, UniformInt(rng, 0, img.rows - tape), img.cols, tape), {140, 185, 215}, cv::FILLED);
  const int labels = UniformInt(rng, 6, 14);
  for (int i = 0; i < labels; ++i) {
    const int w = static_cast<int>(LogUniform(rng, 0.06, 0.3) * ppm), h = static_cast<int>(w * Uniform(rng, 0.4, 1.0));
    const cv::Rect r(UniformInt(rng, 0, img.cols - w), UniformInt(rng, 0, img.rows - h), w, h);
    DrawPoster(img, rng, r);
  }
  Scatter(img, rng, 40, 4, 0.12 * ppm, 0, 120);  // printed marks
  AddGrain(img, rng, 6);
}

void Books(cv::Mat& img, Rng& rng, double ppm) {
  img.setTo(cv::Scalar(20, 20, 25));
  for (int x = 0; x < img.cols;) {
    const int w = static_cast<int>(LogUniform(rng, 0.015, 0.08) * ppm) + 1;
    const int top = UniformInt(rng, 0, img.rows / 4);
    const cv::Scalar c = RandomColour(rng, 20, 240);
    cv::rectangle(img, cv::Rect(x, top, w - 1, img.rows - top), c, cv::FILLED);
    for (int b = 0; b < UniformInt(rng, 0, 3); ++b) {  // bands and title labels on the spine
      const int y = UniformInt(rng, top, img.rows - 8), h = UniformInt(rng, 3, std::max(4, img.rows / 8));
      cv::rectangle(img, cv::Rect(x, y, w - 1, h), RandomColour(rng), cv::FILLED);
    }
    DrawText(img, rng, {x, UniformInt(rng, top + 10, img.rows)}, std::max(6, w / 2), RandomColour(rng));
    x += w;
  }
  AddGrain(img, rng, 4);
}

// A garment's colours: a dark, a light and a vivid one, so that its patterns
// keep their contrast in grey, which is all ORB sees.
using Palette = std::array<cv::Scalar, 3>;
Palette GarmentPalette(Rng& rng) {
  cv::Scalar vivid = RandomColour(rng, 0, 255);
  vivid[UniformInt(rng, 0, 2)] = UniformInt(rng, 200, 255);
  return {RandomColour(rng, 0, 70), RandomColour(rng, 175, 255), vivid};
}

cv::Scalar Pick(const Palette& palette, Rng& rng) {
  return Jitter(rng, palette[static_cast<std::size_t>(UniformInt(rng, 0, 2))], 25);
}

// Bands of irregular width across the whole image (rows, or columns when
// `vertical`), blended over what is there: stripes, and crossed, plaid.
void Bands(cv::Mat& img, Rng& rng, double ppm, bool vertical, double opacity, const Palette& palette) {
  const int extent = vertical ? img.cols : img.rows;
  for (int p = UniformInt(rng, 0, 8); p < extent; p += static_cast<int>(LogUniform(rng, 0.008, 0.06) * ppm) + 2) {
    const int w = std::min(extent - p, static_cast<int>(LogUniform(rng, 0.004, 0.04) * ppm) + 1);
    cv::Mat roi = vertical ? img.colRange(p, p + w) : img.rowRange(p, p + w);
    cv::addWeighted(roi, 1.0 - opacity, cv::Mat(roi.size(), roi.type(), Pick(palette, rng)), opacity, 0.0, roi);
  }
}

void ScatterPalette(cv::Mat& img, Rng& rng, int count, double min_size, double max_size, const Palette& palette) {
  for (int i = 0; i < count; ++i) {
    DrawShape(img, rng, {Uniform(rng, 0, img.cols), Uniform(rng, 0, img.rows)}, LogUniform(rng, min_size, max_size),
              Pick(palette, rng));
  }
}

// Real clothing is busy at many scales (prints, checks, seams, logos): ORB
// finds corners on people as densely as on the room, as in TUM's sequences.
void Clothing(cv::Mat& img, Rng& rng, double ppm) {
  const Palette palette = GarmentPalette(rng);
  img.setTo(Pick(palette, rng));
  const double area = img.cols * img.rows / (ppm * ppm);
  switch (UniformInt(rng, 0, 3)) {
    case 0: Bands(img, rng, ppm, false, 1.0, palette); break;  // stripes
    case 1:  // plaid: crossing translucent bands
      Bands(img, rng, ppm, false, 0.6, palette);
      Bands(img, rng, ppm, true, 0.6, palette);
      break;
    case 2: AddBlotches(img, rng, 70, 10, false); break;  // camouflage-like
    default: ScatterPalette(img, rng, static_cast<int>(300 * area), 0.01 * ppm, 0.06 * ppm, palette); break;
  }
  ScatterPalette(img, rng, static_cast<int>(120 * area), 0.006 * ppm, 0.12 * ppm, palette);  // prints, buttons
  Scatter(img, rng, static_cast<int>(40 * area), 0.006 * ppm, 0.05 * ppm, 0, 255);  // stains, badges
  for (int i = UniformInt(rng, 2, 5); i > 0; --i) {  // printed graphics
    const int w = static_cast<int>(LogUniform(rng, 0.08, 0.25) * ppm), h = static_cast<int>(w * Uniform(rng, 0.5, 1.3));
    DrawPoster(img, rng, cv::Rect(UniformInt(rng, 0, img.cols - w), UniformInt(rng, 0, img.rows - h), w, h));
  }
  for (int i = UniformInt(rng, 2, 6); i > 0; --i) {  // lettering
    DrawText(img, rng, {UniformInt(rng, 0, img.cols * 3 / 4), UniformInt(rng, 10, img.rows)},
             LogUniform(rng, 0.015, 0.06) * ppm, Pick(palette, rng));
  }
  AddGrain(img, rng, 7);
}

void Trousers(cv::Mat& img, Rng& rng, double ppm) {
  static const cv::Scalar kCloth[] = {{120, 70, 40}, {30, 30, 30}, {110, 160, 180}, {70, 70, 75}, {60, 90, 60}};
  img.setTo(Jitter(rng, kCloth[UniformInt(rng, 0, 4)], 15));
  AddBlotches(img, rng, 20, 10);
  if (Uniform01(rng) < 0.4) Bands(img, rng, ppm, UniformInt(rng, 0, 1) == 1, 0.5, GarmentPalette(rng));  // pinstripes
  for (int i = 0; i < 8; ++i) {  // seams, pockets, patches
    const int x = UniformInt(rng, 0, img.cols);
    cv::line(img, {x, 0}, {x + UniformInt(rng, -20, 20), img.rows}, RandomColour(rng, 100, 220), 2, cv::LINE_AA);
    const int s = static_cast<int>(LogUniform(rng, 0.05, 0.15) * ppm);
    const cv::Rect r(UniformInt(rng, 0, img.cols - s), UniformInt(rng, 0, img.rows - s), s, s);
    if (Uniform01(rng) < 0.4) cv::rectangle(img, r, RandomColour(rng, 0, 255), cv::FILLED);
    cv::rectangle(img, r, RandomColour(rng, 0, 255), 2, cv::LINE_AA);
  }
  Scatter(img, rng, static_cast<int>(60 * img.cols * img.rows / (ppm * ppm)), 0.006 * ppm, 0.06 * ppm, 0, 255);
  AddGrain(img, rng, 12);
}

cv::Scalar SkinTone(Rng& rng) {
  static const cv::Scalar kSkin[] = {{150, 180, 225}, {120, 160, 210}, {90, 130, 180}, {60, 90, 140}, {45, 60, 95}};
  return Jitter(rng, kSkin[UniformInt(rng, 0, 4)], 10);
}

void Head(cv::Mat& img, Rng& rng, double ppm) {
  const cv::Scalar skin = SkinTone(rng);
  img.setTo(skin);
  AddBlotches(img, rng, 6, 8);
  const cv::Scalar hair = RandomColour(rng, 10, 110);
  auto px = [&](double metres) { return static_cast<int>(metres * ppm); };
  const int cx = img.cols / 2;  // the face: u = C/2 faces forward on a capsule
  cv::rectangle(img, cv::Rect(0, 0, img.cols, px(0.075)), hair, cv::FILLED);
  cv::rectangle(img, cv::Rect(0, 0, cx - px(0.08), px(0.22)), hair, cv::FILLED);  // hair at the back
  cv::rectangle(img, cv::Rect(cx + px(0.08), 0, img.cols - cx - px(0.08), px(0.22)), hair, cv::FILLED);
  for (int side : {-1, 1}) {
    const cv::Point eye(cx + side * px(0.033), px(0.115));
    cv::ellipse(img, eye, cv::Size(px(0.014), px(0.007)), 0, 0, 360, {235, 235, 235}, cv::FILLED, cv::LINE_AA);
    cv::circle(img, eye, px(0.005), RandomColour(rng, 10, 120), cv::FILLED, cv::LINE_AA);
    cv::line(img, eye + cv::Point(-px(0.017), -px(0.016)), eye + cv::Point(px(0.017), -px(0.018)), hair, 3, cv::LINE_AA);
  }
  cv::ellipse(img, {cx, px(0.185)}, cv::Size(px(0.022), px(0.007)), 0, 0, 360, skin * 0.6 + cv::Scalar(20, 20, 60),
              cv::FILLED, cv::LINE_AA);
  cv::line(img, {cx, px(0.13)}, {cx + px(0.006), px(0.16)}, skin * 0.75, 2, cv::LINE_AA);
  AddGrain(img, rng, 3);
}

void Skin(cv::Mat& img, Rng& rng, double ppm) {
  img.setTo(SkinTone(rng));
  AddBlotches(img, rng, 8, 8);
  Scatter(img, rng, 10, 2, 0.01 * ppm, 30, 120);  // freckles, a watch band
  AddGrain(img, rng, 3);
}

void Device(cv::Mat& img, Rng& rng, double ppm) {
  img.setTo(RandomColour(rng, 25, 80));
  AddBlotches(img, rng, 5, 16);
  const int w = img.cols * 3 / 4, h = img.rows * 3 / 5;
  DrawPoster(img, rng, cv::Rect(img.cols / 8, img.rows / 8, w, h));  // screen content or a panel
  Scatter(img, rng, 15, 3, 0.05 * ppm, 60, 255);  // stickers, LEDs, labels
  AddGrain(img, rng, 3);
}

}  // namespace

cv::Mat MakeTextureImage(TextureStyle style, int width, int height, double texels_per_metre, Rng& rng) {
  cv::Mat img(height, width, CV_8UC3);
  const double ppm = texels_per_metre;
  switch (style) {
    case TextureStyle::kWall: Wall(img, rng, ppm); break;
    case TextureStyle::kFloor: Floor(img, rng, ppm); break;
    case TextureStyle::kCeiling: Ceiling(img, rng, ppm); break;
    case TextureStyle::kWood: Wood(img, rng, ppm); break;
    case TextureStyle::kCardboard: Cardboard(img, rng, ppm); break;
    case TextureStyle::kBooks: Books(img, rng, ppm); break;
    case TextureStyle::kClothing: Clothing(img, rng, ppm); break;
    case TextureStyle::kTrousers: Trousers(img, rng, ppm); break;
    case TextureStyle::kHead: Head(img, rng, ppm); break;
    case TextureStyle::kSkin: Skin(img, rng, ppm); break;
    case TextureStyle::kDevice: Device(img, rng, ppm); break;
  }
  return img;
}

}  // namespace dlslam::synth
