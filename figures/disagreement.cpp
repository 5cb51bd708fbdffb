// figures/disagreement.cpp — the overlay of figures/disagreement.h.
#include "figures/disagreement.h"

#include "core/base/errors.h"

namespace sl::figures {

namespace {
// Rec. 709 luma weights: the grey of the background.
constexpr float kLumaR = 0.2126f, kLumaG = 0.7152f, kLumaB = 0.0722f;

bool sameSize(const Image& a, const Image& b) { return a.width == b.width && a.height == b.height; }
}  // namespace

Disagreement disagreementOverlay(const Image& exactColour, const Image& exactMask,
                                 const Image& first, const Image& second, const Image& scored) {
  if (!sameSize(exactColour, exactMask) || !sameSize(exactMask, first) ||
      (!second.empty() && !sameSize(exactMask, second)) ||
      (!scored.empty() && !sameSize(exactMask, scored)))
    throw InputError("disagreement overlay: the images differ in size");
  const Image rgb = toRgb(exactColour);
  Disagreement d;
  d.overlay = Image(rgb.width, rgb.height, 3);
  for (int y = 0; y < rgb.height; ++y)
    for (int x = 0; x < rgb.width; ++x) {
      const bool counted = scored.empty() || scored.at(x, y) > 0.5f;
      d.pixels += counted;
      const bool lit = exactMask.at(x, y) >= kLitThreshold;
      const bool firstWrong = counted && (first.at(x, y) >= kLitThreshold) != lit;
      const bool secondWrong =
          counted && !second.empty() && (second.at(x, y) >= kLitThreshold) != lit;
      d.firstWrong += firstWrong;
      d.secondWrong += secondWrong;
      d.bothWrong += firstWrong && secondWrong;
      const float* colour = firstWrong && secondWrong ? kBothWrong
                            : firstWrong              ? kFirstOnlyWrong
                            : secondWrong             ? kSecondOnlyWrong
                                                      : nullptr;
      if (colour != nullptr) {
        for (int c = 0; c < 3; ++c) d.overlay.at(x, y, c) = colour[c];
        continue;
      }
      const float grey =
          kOverlayBackgroundShare *
          (kLumaR * rgb.at(x, y, 0) + kLumaG * rgb.at(x, y, 1) + kLumaB * rgb.at(x, y, 2));
      for (int c = 0; c < 3; ++c) d.overlay.at(x, y, c) = grey;
    }
  return d;
}

}  // namespace sl::figures
