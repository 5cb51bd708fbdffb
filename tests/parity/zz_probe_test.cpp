#include "parity/parity_util.h"
namespace sl::imaging::testing {
std::vector<float> weightsP(int n, unsigned seed) {
  std::vector<float> w(size_t(n) * 4);
  uint32_t s = seed * 747796405u + 2891336453u;
  for (float& v : w) { s = s * 1664525u + 1013904223u; v = float(s >> 8) / float(1u << 24) * 0.5f - 0.15f; }
  return w;
}
TEST(Probe, Conv) {
  for (Backend b : {Backend::kReference, Backend::kOsmesa}) {
    Outcome o = runOn(b, [](Outcome& o) {
      putImage(kParityW, kParityH, patternImage(kParityW, kParityH, 31));
      const auto f = weightsP(15, 3 * 16 + 5 + GL_RGBA);
      glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 5, GL_RGBA, GL_FLOAT, f.data());
      glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_REDUCE);
      glEnable(GL_CONVOLUTION_2D);
      appendFloats(o, readRgbaF(0, 0, 8, 12));
      glDisable(GL_DITHER);
      glWindowPos2i(8, 0);
      glCopyPixels(0, 0, 8, 12, GL_COLOR);
      appendBytes(o, readWindow());
    });
    const int stride = b == Backend::kReference ? 8 : 6;
    for (int k = 0; k < 4; ++k) printf("%s: c%d float %.9f %.6f byte %d\n", backendName(b), k, o.floats[(2*stride+1)*4+k], o.floats[(2*stride+1)*4+k]*255, o.bytes[164+k]);
  }
}
}
