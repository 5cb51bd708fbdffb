// figures/disagreement.h — where approximate shadow tests differ from an exact one (Chan 2004,
// Fig. 3-7: which pixels the shadow map and the hybrid method get wrong against shadow volumes).
#pragma once

#include "core/base/image.h"

namespace sl::figures {

// Colours of the overlay (RGB): pixels only the first technique decides wrongly, pixels both
// decide wrongly, pixels only the second decides wrongly. None is red, the close-up frames'
// colour.
constexpr float kFirstOnlyWrong[3] = {1.0f, 0.0f, 1.0f};   // magenta
constexpr float kBothWrong[3] = {1.0f, 0.9f, 0.0f};        // yellow
constexpr float kSecondOnlyWrong[3] = {0.0f, 0.8f, 1.0f};  // cyan
// The exact image under the colours, as grey at this share of its luminance, so that the
// coloured pixels stand out and the scene stays readable.
constexpr float kOverlayBackgroundShare = 0.5f;
// A pixel is in shadow when its visibility is below this (the masks' half-way point).
constexpr float kLitThreshold = 0.5f;

// The panel counters (Frame::counters names) an overlay panel reports: the prefix followed by
// the compared technique's name ("wrong_pixels modern.hw"), and the pixels both get wrong.
constexpr const char* kWrongPixelsCounter = "wrong_pixels ";
constexpr const char* kBothWrongCounter = "wrong_pixels of both";

struct Disagreement {
  Image overlay;              // RGB, the size of the exact image
  long long firstWrong = 0;   // pixels the first technique decides otherwise than the exact one
  long long secondWrong = 0;  // the same for the second
  long long bothWrong = 0;    // pixels both decide otherwise
  long long pixels = 0;       // pixels compared (the scored ones, or the whole image)
};

// Compares each technique's visibility mask with the exact one, pixel by pixel, lit or in
// shadow (kLitThreshold), and draws the exact colour image in grey with the pixels each gets
// wrong coloured. `second` may be empty (then only the first is compared). `scored`, when not
// empty, limits the comparison to the scored pixels of the one error definition
// (registry/shadow_error.h, docs/error.md: receivers facing the light inside its frustum), so
// that a terminator, unlit whatever the mask says, is not counted or coloured as an error.
// Throws InputError when the sizes differ.
Disagreement disagreementOverlay(const Image& exactColour, const Image& exactMask,
                                 const Image& first, const Image& second,
                                 const Image& scored = Image());

}  // namespace sl::figures
