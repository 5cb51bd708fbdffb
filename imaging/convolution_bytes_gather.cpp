// imaging/convolution_bytes_gather.cpp — form 1 of the 8-bit convolution (convolution_bytes.cpp):
// a byte gather through per-component tables, when every component has at most one non-zero tap.
#include <algorithm>
#include <cstring>

#include "imaging/convolution_bytes_internal.h"

namespace sl::imaging::detail::conv_bytes {

// ---------------------------------------------------------------- form 1: byte gather

// Builds the plan when every component has at most one non-zero tap and stages 5-7 are per
// component. table[c][v] is what the general path gives a group whose only contributing
// source value is v: the sum 0.0f + value * weight (accumulateTaps' operations; a component
// without a tap sums to 0.0f), then finishRow — the same code the sums go through.
bool planGather(Convolution& cv, GatherPlan& plan) {
  if (!cv.perComponent) return false;
  int tapOf[kGroup] = {-1, -1, -1, -1};
  for (size_t i = 0; i < cv.taps.size(); ++i)
    for (int c = 0; c < kGroup; ++c) {
      if (cv.taps[i].w[c] == 0.0f) continue;
      if (tapOf[c] >= 0) return false;
      tapOf[c] = int(i);
    }
  Image4 sums(kTableEntries, 1);
  for (int c = 0; c < kGroup; ++c) {
    const Tap* tap = tapOf[c] >= 0 ? &cv.taps[size_t(tapOf[c])] : nullptr;
    // No tap: a constant table; the centre keeps the (unused) source reads in range.
    plan.dx[c] = tap != nullptr ? tap->n - cv.cw : 0;
    plan.dy[c] = tap != nullptr ? tap->m - cv.ch : 0;
    for (int v = 0; v < kTableEntries; ++v) {
      const float x = v == kBorderEntry ? cv.border[c] : cv.values.px[size_t(v) * kGroup + c];
      float sum = 0.0f;
      if (tap != nullptr) sum += x * tap->w[c];
      sums.px[size_t(v) * kGroup + c] = sum;
    }
  }
  uint8_t bytes[kTableEntries * kGroup];
  finishRow(cv, nullptr, sums, bytes);
  for (int v = 0; v < kTableEntries; ++v)
    for (int c = 0; c < kGroup; ++c) {
      plan.table[c][v] = bytes[v * kGroup + c];
      if (v < kByteValues && bytes[v * kGroup + c] != v) plan.identity = false;
    }
  return true;
}

// Rows [y0, y1) of the gather.
void gatherRows(const Convolution& cv, const GatherPlan& plan, const Kernels& k, const uint8_t* src,
                uint8_t* out, int y0, int y1) {
  const int ws = cv.ws, hs = cv.hs, ow = cv.ow;
  // The interior columns, where every component's source column is inside the image.
  int xa = 0, xb = ow;
  for (int c = 0; c < kGroup; ++c) {
    xa = std::max(xa, -plan.dx[c]);
    xb = std::min(xb, ws - plan.dx[c]);
  }
  for (int y = y0; y < y1; ++y) {
    const uint8_t* rows[kGroup];
    bool borderRow = false;  // some component reads a CONSTANT border row
    for (int c = 0; c < kGroup; ++c) {
      int sy = y + plan.dy[c];
      if (sy < 0 || sy >= hs) {
        borderRow = borderRow || !cv.replicate;
        sy = std::clamp(sy, 0, hs - 1);
      }
      rows[c] = src + size_t(sy) * ws * kGroup;
    }
    uint8_t* const o = out + size_t(y) * ow * kGroup;
    // Any group, with the border rules: the edges, and whole rows that touch a border row.
    auto gatherGroup = [&](int x) {
      for (int c = 0; c < kGroup; ++c) {
        const int sy = y + plan.dy[c], sx = x + plan.dx[c];
        const bool inside = sx >= 0 && sx < ws && sy >= 0 && sy < hs;
        o[x * kGroup + c] =
            inside || cv.replicate
                ? plan.table[c][rows[c][size_t(std::clamp(sx, 0, ws - 1)) * kGroup + c]]
                : plan.table[c][kBorderEntry];
      }
    };
    if (borderRow || xa >= xb) {
      for (int x = 0; x < ow; ++x) gatherGroup(x);
      continue;
    }
    for (int x = 0; x < xa; ++x) gatherGroup(x);
    for (int x = xb; x < ow; ++x) gatherGroup(x);
    const uint8_t* s[kGroup];
    for (int c = 0; c < kGroup; ++c) s[c] = rows[c] + ptrdiff_t(plan.dx[c]) * kGroup + c;
    int x = xa;
    if (plan.identity && k.blend != nullptr) {
      const uint8_t* base[kGroup];
      for (int c = 0; c < kGroup; ++c) base[c] = s[c] - c;
      x = k.blend(base, o, x, xb);
    }
    for (; x < xb; ++x) {
      const size_t i = size_t(x) * kGroup;
      const uint32_t v = uint32_t(plan.table[0][s[0][i]]) | uint32_t(plan.table[1][s[1][i]]) << 8 |
                         uint32_t(plan.table[2][s[2][i]]) << 16 |
                         uint32_t(plan.table[3][s[3][i]]) << 24;
      std::memcpy(o + i, &v, 4);  // RGBA bytes, little-endian
    }
  }
}

}  // namespace sl::imaging::detail::conv_bytes
