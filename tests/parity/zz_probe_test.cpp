#include "parity/parity_util.h"
namespace sl::imaging::testing {
TEST(Probe, Accum) {
  for (Backend b : {Backend::kReference, Backend::kOsmesa}) {
    Outcome o = runOn(b, [](Outcome& o) {
      auto src = patternImage(kParityW, kParityH, 161);
      putImage(kParityW, kParityH, src);
      printf("src %d %d %d %d | (5,3) %d\n", src[0], src[1], src[2], src[3], src[(3*16+5)*4]);
      glAccum(GL_LOAD, 0.2f);
      appendBytes(o, readWindow());
      glAccum(GL_RETURN, 1.0f);
      appendBytes(o, readWindow());
      glEnable(GL_SCISSOR_TEST); glScissor(3, 2, 7, 5); glAccum(GL_LOAD, 0.6f); glDisable(GL_SCISSOR_TEST);
      appendBytes(o, readWindow());
      glAccum(GL_RETURN, 1.0f);
      appendBytes(o, readWindow());
    }, false);
    const int n = 16*12*4;
    for (int k = 0; k < 4; ++k) printf("%s step %d: px0 %d %d %d %d  (5,3) %d\n", backendName(b), k, o.bytes[k*n], o.bytes[k*n+1], o.bytes[k*n+2], o.bytes[k*n+3], o.bytes[k*n+(3*16+5)*4]);
  }
}
TEST(Probe, CopyTex) {
  for (int mode = 0; mode < 3; ++mode)
  for (Backend b : {Backend::kReference, Backend::kOsmesa}) {
    Outcome o = runOn(b, [mode](Outcome& o) {
      auto src = patternImage(kParityW, kParityH, 151);
      putImage(kParityW, kParityH, src);
      GLuint tex = 0; glGenTextures(1, &tex); glBindTexture(GL_TEXTURE_2D, tex);
      std::vector<uint8_t> zero(16 * 16 * 4, 0);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 16, 16, 0, GL_RGBA, GL_UNSIGNED_BYTE, zero.data());
      if (mode == 0) glPixelTransferf(GL_RED_SCALE, 0.8f);
      if (mode == 1) { std::vector<float> t(64*4); for (int k=0;k<256;++k) t[k]=float(k/4)/63.0f*0.5f; glColorTable(GL_COLOR_TABLE, GL_RGBA, 64, GL_RGBA, GL_FLOAT, t.data()); glEnable(GL_COLOR_TABLE);}
      if (mode == 2) { const float m[16] = {0.5f,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1}; glMatrixMode(GL_COLOR); glLoadMatrixf(m); glMatrixMode(GL_MODELVIEW);}
      glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, 8, 8);
      resetImaging();
      std::vector<uint8_t> back(16*16*4);
      glPixelStorei(GL_PACK_ALIGNMENT, 1);
      glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, back.data());
      printf("mode %d src %d %d %d %d -> %d %d %d %d\n", mode, src[0], src[1], src[2], src[3], back[0], back[1], back[2], back[3]);
      printf("          src %d %d %d %d -> %d %d %d %d\n", src[4], src[5], src[6], src[7], back[4], back[5], back[6], back[7]);
    });
  }
}
}
