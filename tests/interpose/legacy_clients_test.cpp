// tests/interpose/legacy_clients_test.cpp — the drop-in imaging library on programs nobody here
// wrote: the Red Book's convolution.c and histogram.c (../shared/legacy-clients), built
// unchanged by scripts/build_legacy_client.sh and run by `shadowlab run-legacy --backend glx`
// (Xvfb + freeglut + GLX llvmpipe + LD_PRELOAD); their frames and read-backs are compared
// with the same calls made in process on the emulation (Debian OSMesa) and on the reference
// Mesa 7.8.2 (native imaging). Also a C program on OSMesa (osmesa_client.c) and bad input.
// Skips, with the reason, only where ../shared or the X / GLUT packages are absent.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "apps/command_util.h"
#include "core/base/image.h"
#include "core/gl/context.h"
#include "core/gl/gl.h"
#include "imaging/imaging.h"

namespace sl {
namespace {
namespace fs = std::filesystem;
using namespace sl::gl;
using test::CommandResult;
using test::runBinary;
using test::testDir;

constexpr float kByteMax = 255.0f;

fs::path sourceDir() { return fs::path(SHADOWLAB_SOURCE_DIR); }
fs::path clientsDir() { return sourceDir() / ".." / "shared" / "legacy-clients" / "redbook"; }
fs::path libraryDir() { return fs::path(SHADOWLAB_BINARY).parent_path() / ".." / "lib"; }

bool onPath(const std::string& tool) {
  return std::system(("command -v " + tool + " >/dev/null 2>&1").c_str()) == 0;
}

// Why the X path cannot run here, or "" when it can.
std::string missingForGlx() {
  if (!fs::exists(clientsDir() / "convolution.c"))
    return "../shared/legacy-clients is not here (the Red Book clients are test inputs)";
  if (std::getenv("DISPLAY") == nullptr && !onPath("Xvfb"))
    return "Xvfb is not installed (scripts/setup.sh installs xvfb)";
  if (std::system("pkg-config --exists glut gl") != 0)
    return "freeglut3-dev is not installed (scripts/setup.sh installs it)";
  if (!fs::exists(libraryDir() / "libshadowlab-frames.so"))
    return "build/lib/libshadowlab-frames.so was not built (freeglut missing at configure time)";
  return "";
}

#define SL_REQUIRE_GLX() \
  if (const std::string why = missingForGlx(); !why.empty()) GTEST_SKIP() << "skipped: " << why

// Builds a client once per test process, into build/test-output/interpose/clients, with
// leeds.bin beside it (the programs read it from their working directory).
fs::path client(const std::string& name, const fs::path& sources = clientsDir()) {
  static std::mutex m;
  std::lock_guard<std::mutex> lock(m);
  const fs::path dir = fs::path(SHADOWLAB_TEST_OUTPUT_DIR) / "interpose" / "clients";
  fs::create_directories(dir);
  const fs::path program = dir / name;
  const std::string cmd = (sourceDir() / "scripts" / "build_legacy_client.sh").string() + " " +
                          (sources / (name + ".c")).string() + " " + dir.string() + " >/dev/null";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  // ctest runs the cases as parallel processes: the image is copied under a name of this
  // process and renamed, so a program never reads a half-copied file.
  const fs::path partial = dir / ("leeds.bin." + std::to_string(getpid()));
  fs::copy_file(clientsDir() / "leeds.bin", partial, fs::copy_options::overwrite_existing);
  fs::rename(partial, dir / "leeds.bin");
  return program;
}

// The image the clients draw: big-endian width and height, then RGB bytes (README).
struct Leeds {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
};
Leeds readLeeds() {
  std::ifstream in(clientsDir() / "leeds.bin", std::ios::binary);
  uint8_t header[8];
  in.read(reinterpret_cast<char*>(header), 8);
  Leeds l;
  l.width = (header[0] << 24) | (header[1] << 16) | (header[2] << 8) | header[3];
  l.height = (header[4] << 24) | (header[5] << 16) | (header[6] << 8) | header[7];
  l.rgb.resize(size_t(l.width) * l.height * 3);
  in.read(reinterpret_cast<char*>(l.rgb.data()), std::streamsize(l.rgb.size()));
  return l;
}

// `shadowlab run-legacy --backend B` from the client's folder.
CommandResult runLegacy(const fs::path& program, const std::string& keys, const fs::path& frames,
                        const fs::path& logs, const std::string& env = "",
                        const std::string& backend = "glx") {
  const std::string args = "run-legacy --backend " + backend + " --keys '" + keys + "' --frames " +
                           frames.string() + " -- ./" + program.filename().string();
  return runBinary("cd " + program.parent_path().string() + " && " + env + " " + SHADOWLAB_BINARY,
                   args, logs);
}

std::vector<uint8_t> pngBytes(const fs::path& p, int& w, int& h) {
  const Image img = readPng(p.string());
  w = img.width;
  h = img.height;
  std::vector<uint8_t> out(size_t(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        out[(size_t(y) * w + x) * 3 + c] = uint8_t(std::lround(img.at(x, y, c) * kByteMax));
  return out;
}

// The window as the convolution client leaves it, drawn in process on `backend`: the calls
// its README describes (a 3x3 GL_LUMINANCE filter on GL_CONVOLUTION_2D, glDrawPixels of the
// image at raster position (1, 1) in a pixel-exact orthographic projection), read back with
// the convolution disabled.
std::vector<uint8_t> convolvedInProcess(Backend backend, const Leeds& l, const float kernel[9]) {
  ContextSpec spec;
  spec.backend = backend;
  spec.width = l.width;
  spec.height = l.height;
  auto ctx = GlContext::create(spec);
  imaging::install(*ctx);
  glViewport(0, 0, l.width, l.height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, l.width, 0, l.height, -1, 1);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glClearColor(0, 0, 0, 0);
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_LUMINANCE, 3, 3, GL_LUMINANCE, GL_FLOAT, kernel);
  glEnable(GL_CONVOLUTION_2D);
  glClear(GL_COLOR_BUFFER_BIT);
  glRasterPos2i(1, 1);
  glDrawPixels(l.width, l.height, GL_RGB, GL_UNSIGNED_BYTE, l.rgb.data());
  glDisable(GL_CONVOLUTION_2D);
  glFinish();
  std::vector<uint8_t> out(size_t(l.width) * l.height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, l.width, l.height, GL_RGB, GL_UNSIGNED_BYTE, out.data());
  return out;
}

// The three kernels the program's keys select (README: horizontal, vertical, Laplacian
// edge filters), rows as glConvolutionFilter2D takes them.
constexpr float kHorizontal[9] = {0, -1, 0, 0, 1, 0, 0, 0, 0};
constexpr float kVertical[9] = {0, 0, 0, -1, 1, 0, 0, 0, 0};
constexpr float kLaplacianSide = -0.125f;
constexpr float kLaplacian[9] = {kLaplacianSide, kLaplacianSide, kLaplacianSide,
                                 kLaplacianSide, 1.0f,           kLaplacianSide,
                                 kLaplacianSide, kLaplacianSide, kLaplacianSide};

int differingPixels(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  int n = 0;
  for (size_t i = 0; i + 2 < a.size() && i + 2 < b.size(); i += 3)
    n += a[i] != b[i] || a[i + 1] != b[i + 1] || a[i + 2] != b[i + 2];
  return n;
}

TEST(LegacyClients, ConvolutionRefusesWithoutTheEmulation) {
  SL_REQUIRE_GLX();
  const fs::path program = client("convolution");
  const fs::path dir = testDir("interpose", true);
  // SHADOWLAB_IMAGING=off: the library passes everything through, as if it were absent.
  const CommandResult r = runLegacy(program, "", dir / "frames", dir, "SHADOWLAB_IMAGING=off");
  EXPECT_EQ(r.status, 1) << r.err;  // the program's own exit status
  EXPECT_NE(r.err.find("Sorry, this program requires GL_ARB_imaging."), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "frames")) << "no frames from a failed run";
}

TEST(LegacyClients, ConvolutionFramesEqualTheInProcessEmulation) {
  SL_REQUIRE_GLX();
  const fs::path program = client("convolution");
  const fs::path dir = testDir("interpose", true);
  const CommandResult r = runLegacy(program, "h v l", dir / "frames", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("Using the laplacian filter"), std::string::npos) << "stdout passes through";
  const Leeds l = readLeeds();
  const float* kernels[4] = {kHorizontal, kHorizontal, kVertical, kLaplacian};
  std::vector<uint8_t> previous;
  for (int f = 0; f < 4; ++f) {
    char name[16];
    std::snprintf(name, sizeof name, "%03d.png", f);
    int w = 0, h = 0;
    const std::vector<uint8_t> frame = pngBytes(dir / "frames" / name, w, h);
    ASSERT_EQ(w, l.width);
    ASSERT_EQ(h, l.height);
    const std::vector<uint8_t> expected = convolvedInProcess(Backend::kOsmesa, l, kernels[f]);
    EXPECT_EQ(differingPixels(frame, expected), 0) << "frame " << name;
    if (f == 2 || f == 3) {
      EXPECT_GT(differingPixels(frame, previous), 0) << name << " = previous";
    }
    previous = frame;
  }
  EXPECT_FALSE(fs::exists(dir / "frames" / "004.png"));
}

// The Laplacian's exact value at window pixel (x, y), in 1/(8 * 255) steps: with GL_REDUCE the
// output group (i, j) lands at (1 + i, 1 + j) and is centred on source pixel (1 + i, 1 + j),
// so window pixel (x, y) is 8 * centre - the 8 neighbours of source (x, y).
int laplacianEighths(const Leeds& l, int x, int y, int c) {
  auto at = [&](int sx, int sy) { return int(l.rgb[(size_t(sy) * l.width + sx) * 3 + c]); };
  int sum = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      if (dx != 0 || dy != 0) sum += at(x + dx, y + dy);
  return 8 * at(x, y) - sum;
}

bool referenceHere() { return !referenceGlPath().empty() && fs::exists(referenceGlPath()); }

#define SL_REQUIRE_REFERENCE() \
  if (!referenceHere())        \
  GTEST_SKIP() << "skipped: the reference GL (../shared/reference-gl) is not here"

// One program on the three back ends of run-legacy, each into logs/<backend>.
struct ThreeRuns {
  fs::path dir;
  std::string keys;
  std::vector<uint8_t> frame(const std::string& backend, int f, int& w, int& h) const {
    char name[16];
    std::snprintf(name, sizeof name, "%03d.png", f);
    return pngBytes(dir / backend / "frames" / name, w, h);
  }
};
// Mesa 22's window-system framebuffers (GLX) are sRGB-capable whenever the GL exposes
// GL_EXT_framebuffer_sRGB, so their colour buffers have an sRGB format; Mesa's software glAccum
// (src/mesa/main/accum.c) reads and writes the colour buffer through that format's unpack and
// pack, which decode and encode sRGB whatever GL_FRAMEBUFFER_SRGB says. OSMesa's buffer is
// linear. So on glx a GL_ACCUM average is taken of sRGB-decoded colours (51 and 0 over two
// passes: 35 on glx, sRGB(lin(51) / 2); 25 on osmesa): our reading of Mesa's source, borne
// out by the frames. Without the extension the GLX buffers are linear too, and the back ends
// agree; programs of GL 1.x never use it.
constexpr const char* kGlxLinearAccumulation = "MESA_EXTENSION_OVERRIDE=-GL_EXT_framebuffer_sRGB";

// `glxEnv`: environment for the glx run only.
ThreeRuns runThree(const fs::path& program, const std::string& keys, bool trace,
                   const std::string& glxEnv = "") {
  ThreeRuns runs{testDir("interpose", true), keys};
  for (const std::string backend : {"glx", "osmesa", "reference"}) {
    const fs::path logs = runs.dir / backend;
    fs::create_directories(logs);
    const std::string env =
        "SHADOWLAB_IMAGING_VERBOSE=1 " + (backend == "glx" ? glxEnv + " " : std::string()) +
        (trace ? "SHADOWLAB_IMAGING_TRACE=" + (logs / "trace.jsonl").string() : std::string());
    const CommandResult r = runLegacy(program, keys, logs / "frames", logs, env, backend);
    EXPECT_EQ(r.status, 0) << backend << ": " << r.err;
    // The library emulates where the GL lacks GL_ARB_imaging and stays out of the way of the
    // reference's native subset.
    const char* chosen = backend == "reference" ? "passed through" : "imaging emulated";
    EXPECT_NE(r.err.find(chosen), std::string::npos) << backend << ": " << r.err;
  }
  return runs;
}

// convolution.c with keys h, v, l on glx, osmesa (the project's headless GLUT, Debian's
// OSMesa, the drop-in library) and reference (the headless GLUT on Mesa 7.8.2's native
// imaging). glx and osmesa are bit-identical; so is the reference, but for the Laplacian's
// -1/8 weights, which put some results on an exact tie k + 1/2 that single-precision sums
// round either way (the reference README's "exact ties may go either way"): there, and only
// there, a byte may differ by one (each is checked against the exact value).
TEST(LegacyClients, ConvolutionFramesOnAllThreeBackends) {
  SL_REQUIRE_GLX();
  SL_REQUIRE_REFERENCE();
  const ThreeRuns runs = runThree(client("convolution"), "h v l", false);
  const Leeds l = readLeeds();
  constexpr int kFrames = 4, kLaplacianFrame = 3;
  constexpr int kTieEighths = 4;  // k + 4/8: an exact tie
  for (int f = 0; f < kFrames; ++f) {
    int w = 0, h = 0, w2 = 0, h2 = 0, w3 = 0, h3 = 0;
    const std::vector<uint8_t> glx = runs.frame("glx", f, w, h);
    const std::vector<uint8_t> osmesa = runs.frame("osmesa", f, w2, h2);
    const std::vector<uint8_t> reference = runs.frame("reference", f, w3, h3);
    ASSERT_EQ(w, l.width);
    ASSERT_EQ(h, l.height);
    ASSERT_EQ(glx.size(), osmesa.size());
    ASSERT_EQ(glx.size(), reference.size());
    EXPECT_EQ(differingPixels(glx, osmesa), 0) << "frame " << f << ": glx and osmesa";
    if (f != kLaplacianFrame) {
      EXPECT_EQ(differingPixels(glx, reference), 0) << "frame " << f << ": glx and reference";
      continue;
    }
    int ties = 0, unexplained = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) {
          const size_t i = (size_t(y) * w + x) * 3 + c;
          if (glx[i] == reference[i]) continue;
          const bool inside = x >= 1 && y >= 1 && x + 1 < l.width && y + 1 < l.height;
          const int v = inside ? laplacianEighths(l, x, y, c) : 0;
          const bool tie = inside && v > 0 && v % 8 == kTieEighths &&
                           std::abs(int(glx[i]) - int(reference[i])) == 1 &&
                           std::min(glx[i], reference[i]) == v / 8;
          tie ? ++ties : ++unexplained;
        }
    EXPECT_EQ(unexplained, 0) << "Laplacian bytes that differ off an exact tie";
    std::cout << "Laplacian frame: " << ties << " bytes differ by one from the reference, all on "
              << "exact ties\n";
  }
}

// histogram.c with key s on the three back ends: the histogram the program reads back (the
// library's trace) is the same everywhere; glx and osmesa draw bit-identical frames; the
// reference differs from them only on the pixels of the three line strips, which the two
// rasterisers draw differently (the line pixels: non-black pixels of either back end's frame
// after 's', where the sink discards the image and only the strips are drawn, from the same
// counts).
std::vector<std::vector<uint32_t>> histogramReads(const fs::path& trace) {
  std::ifstream in(trace);
  std::vector<std::vector<uint32_t>> reads;
  for (std::string line; std::getline(in, line);) {
    const auto j = nlohmann::json::parse(line);
    if (j["call"] == "glGetHistogram") reads.push_back(j["values"].get<std::vector<uint32_t>>());
  }
  return reads;
}

TEST(LegacyClients, HistogramOnAllThreeBackends) {
  SL_REQUIRE_GLX();
  SL_REQUIRE_REFERENCE();
  const ThreeRuns runs = runThree(client("histogram"), "s", true);
  const auto glx = histogramReads(runs.dir / "glx" / "trace.jsonl");
  ASSERT_EQ(glx.size(), 2u) << "one read-back per displayed frame";
  EXPECT_EQ(histogramReads(runs.dir / "osmesa" / "trace.jsonl"), glx);
  EXPECT_EQ(histogramReads(runs.dir / "reference" / "trace.jsonl"), glx);
  EXPECT_EQ(glx.front(), glx.back()) << "the sink flag does not change the counts";
  int w = 0, h = 0;
  const auto isLine = [&](const std::vector<uint8_t>& sinkFrame, size_t p) {
    return sinkFrame[p * 3] != 0 || sinkFrame[p * 3 + 1] != 0 || sinkFrame[p * 3 + 2] != 0;
  };
  const std::vector<uint8_t> osmesaSink = runs.frame("osmesa", 1, w, h);
  const std::vector<uint8_t> referenceSink = runs.frame("reference", 1, w, h);
  for (int f = 0; f < 2; ++f) {
    const std::vector<uint8_t> a = runs.frame("glx", f, w, h);
    const std::vector<uint8_t> b = runs.frame("osmesa", f, w, h);
    const std::vector<uint8_t> c = runs.frame("reference", f, w, h);
    EXPECT_EQ(differingPixels(a, b), 0) << "frame " << f << ": glx and osmesa";
    int onLines = 0, offLines = 0;
    for (size_t p = 0; p < size_t(w) * h; ++p) {
      if (b[p * 3] == c[p * 3] && b[p * 3 + 1] == c[p * 3 + 1] && b[p * 3 + 2] == c[p * 3 + 2])
        continue;
      isLine(osmesaSink, p) || isLine(referenceSink, p) ? ++onLines : ++offLines;
    }
    EXPECT_EQ(offLines, 0) << "frame " << f << ": pixels off the line strips differ";
    EXPECT_GT(onLines, 0) << "the two rasterisers draw the strips alike: no difference to explain";
    std::cout << "histogram frame " << f << ": " << onLines
              << " pixels differ from the reference, all on the line strips\n";
  }
}

// histogram.c reads its GL_RGB histogram back (glGetHistogram, GL_UNSIGNED_SHORT) in every
// display; the library's trace records it. It must equal the emulation's in process and the
// reference's, and 's' (sink) must not change what is counted.
std::vector<uint32_t> histogramInProcess(Backend backend, const Leeds& l) {
  ContextSpec spec;
  spec.backend = backend;
  spec.width = l.width;
  spec.height = l.height;
  auto ctx = GlContext::create(spec);
  imaging::install(*ctx);
  constexpr int kBins = 256;  // the program's HISTOGRAM_SIZE (README: 256 bins)
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glHistogram(GL_HISTOGRAM, kBins, GL_RGB, GL_FALSE);
  glEnable(GL_HISTOGRAM);
  glViewport(0, 0, l.width, l.height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, l.width, 0, l.height, -1, 1);
  glMatrixMode(GL_MODELVIEW);
  glRasterPos2i(1, 1);
  glDrawPixels(l.width, l.height, GL_RGB, GL_UNSIGNED_BYTE, l.rgb.data());
  std::vector<GLushort> values(kBins * 3);
  glGetHistogram(GL_HISTOGRAM, GL_TRUE, GL_RGB, GL_UNSIGNED_SHORT, values.data());
  return std::vector<uint32_t>(values.begin(), values.end());
}

TEST(LegacyClients, HistogramReadBackEqualsInProcess) {
  SL_REQUIRE_GLX();
  const fs::path program = client("histogram");
  const fs::path dir = testDir("interpose", true);
  const fs::path trace = dir / "trace.jsonl";
  const CommandResult r =
      runLegacy(program, "s", dir / "frames", dir, "SHADOWLAB_IMAGING_TRACE=" + trace.string());
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(trace);
  std::vector<std::vector<uint32_t>> reads;
  for (std::string line; std::getline(in, line);) {
    const auto j = nlohmann::json::parse(line);
    if (j["call"] == "glGetHistogram") reads.push_back(j["values"].get<std::vector<uint32_t>>());
  }
  ASSERT_GE(reads.size(), 2u) << "one read-back per displayed frame";
  const Leeds l = readLeeds();
  const std::vector<uint32_t> emulated = histogramInProcess(Backend::kOsmesa, l);
  EXPECT_EQ(reads.front(), emulated);
  EXPECT_EQ(reads.back(), emulated) << "the sink flag does not change the counts";
  if (referenceHere()) {
    EXPECT_EQ(reads.front(), histogramInProcess(Backend::kReference, l));
  }
}

// A program of our own in the style of the book's accumulation and imaging chapters
// (clients/accumulate.c): jittered passes averaged in the accumulation buffer, key 'a' (1 -> 8
// passes), key 'g' (the window copied onto itself through a grey colour matrix). It runs on
// the three back ends; the grey frame is grey; the 8-pass frame is not the 1-pass one. glx
// (its accumulation linear: kGlxLinearAccumulation) and osmesa draw every frame bit-identically
// (the same GL, and the headless GLUT's torus and sphere are freeglut's); the reference
// rasterises with its older rasteriser, so its frames are not compared.
TEST(LegacyClients, AccumulationProgramOnAllThreeBackends) {
  SL_REQUIRE_GLX();
  SL_REQUIRE_REFERENCE();
  const ThreeRuns runs =
      runThree(client("accumulate", sourceDir() / "tests" / "interpose" / "clients"), "a g", false,
               kGlxLinearAccumulation);
  for (const std::string backend : {"glx", "osmesa", "reference"}) {
    int w = 0, h = 0;
    const std::vector<uint8_t> one = runs.frame(backend, 0, w, h);
    const std::vector<uint8_t> eight = runs.frame(backend, 1, w, h);
    const std::vector<uint8_t> grey = runs.frame(backend, 2, w, h);
    constexpr int kWidth = 160, kHeight = 120;  // the program's window
    ASSERT_EQ(w, kWidth) << backend;
    ASSERT_EQ(h, kHeight) << backend;
    EXPECT_GT(differingPixels(one, eight), 0) << backend << ": 8 passes changed nothing";
    int notGrey = 0;
    for (size_t p = 0; p + 2 < grey.size(); p += 3)
      notGrey += grey[p] != grey[p + 1] || grey[p] != grey[p + 2];
    EXPECT_EQ(notGrey, 0) << backend << ": the colour matrix rows are equal, so R = G = B";
  }
  for (int f = 0; f < 3; ++f) {
    int w = 0, h = 0;
    EXPECT_EQ(differingPixels(runs.frame("glx", f, w, h), runs.frame("osmesa", f, w, h)), 0)
        << "frame " << f << ": glx and osmesa";
  }
}

// ---- the headless GLUT's shapes against freeglut's ----

// tests/interpose/glut_capture_preload.c built into dir.
fs::path captureShim(const fs::path& dir) {
  const fs::path lib = dir / "libglut_capture.so";
  const std::string build =
      "cc -O1 -shared -fPIC -o " + lib.string() + " " +
      (sourceDir() / "tests" / "interpose" / "glut_capture_preload.c").string() + " -ldl";
  EXPECT_EQ(std::system(build.c_str()), 0) << build;
  return lib;
}

// What one GLUT sent the GL for each shape of clients/glut_shapes.c (the shim's format).
struct Primitive {
  std::string kind;  // "prim", or "unread" (a draw the shim could not read)
  unsigned mode = 0;
  std::vector<std::vector<float>> vertices;  // x y z nx ny nz [s t]
};
struct CapturedShape {
  std::string call;
  std::vector<Primitive> primitives;
};
std::vector<CapturedShape> readCapture(const fs::path& capture, const fs::path& calls) {
  std::vector<CapturedShape> shapes;
  std::ifstream names(calls);
  for (std::string line; std::getline(names, line);)
    shapes.push_back({line.substr(line.find(' ') + 1), {}});
  std::ifstream in(capture);
  int current = -1;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string first;
    words >> first;
    if (first == "mark") {
      words >> current;
      continue;
    }
    if (current < 1 || current > int(shapes.size())) continue;  // a draw outside the shapes
    auto& prims = shapes[size_t(current - 1)].primitives;
    if (first == "prim" || first == "unread") {
      std::string mode;
      words >> mode;
      prims.push_back({first, unsigned(std::stoul(mode, nullptr, 16)), {}});
      continue;
    }
    std::vector<float> values{std::strtof(first.c_str(), nullptr)};
    for (std::string w; words >> w;) values.push_back(std::strtof(w.c_str(), nullptr));
    if (!prims.empty()) prims.back().vertices.push_back(values);
  }
  return shapes;
}

// Runs clients/glut_shapes with the capture shim ahead of the GL: on freeglut + GLX (Xvfb via
// xvfb-run unless DISPLAY is set), or on the headless GLUT + Debian's OSMesa, as run-legacy
// --backend glx|osmesa stacks them (without the imaging library, which this does not need).
std::vector<CapturedShape> captureShapes(const fs::path& program, const fs::path& shim,
                                         const std::string& backend, const fs::path& dir) {
  fs::create_directories(dir);
  const fs::path capture = dir / "capture.txt";
  std::string preload = shim.string();
  std::string launcher;
  if (backend == "glx") {
    if (std::getenv("DISPLAY") == nullptr) launcher = "xvfb-run -a -s '-screen 0 640x480x24' ";
  } else {
    preload += " " + (libraryDir() / "libshadowlab-glut.so").string() + " libOSMesa.so.8";
  }
  const CommandResult r = runBinary("cd " + program.parent_path().string() + " && " + launcher +
                                        "env LIBGL_ALWAYS_SOFTWARE=1 LD_PRELOAD='" + preload +
                                        "' SHADOWLAB_GLUT_CAPTURE=" + capture.string(),
                                    "./" + program.filename().string(), dir);
  EXPECT_EQ(r.status, 0) << backend << ": " << r.err;
  return readCapture(capture, dir / "stdout.txt");
}

// Two captures agree where they send the same primitives (mode and vertex count, in order)
// with the same vertices, normals and texture coordinates in the same order. Both compute in
// single precision by the same operations with the same libm, and are bit-identical here; the
// tolerance, 4 float ulps of each value's magnitude (at least of 1), leaves room only for a
// freeglut built to round differently (fused multiply-adds), while a tessellation that differs
// (a slice more or less, another order) moves values by orders of magnitude more.
constexpr float kCaptureUlps = 4.0f;
std::string compareShape(const CapturedShape& a, const CapturedShape& b, float& worst) {
  worst = 0.0f;
  if (a.primitives.empty()) return "freeglut drew nothing";
  if (a.primitives.size() != b.primitives.size())
    return std::to_string(a.primitives.size()) + " primitives against " +
           std::to_string(b.primitives.size());
  for (size_t p = 0; p < a.primitives.size(); ++p) {
    const Primitive &x = a.primitives[p], &y = b.primitives[p];
    const std::string where = "primitive " + std::to_string(p) + ": ";
    if (x.kind != "prim" || y.kind != "prim") return where + "a draw the shim could not read";
    if (x.mode != y.mode)
      return where + "mode " + std::to_string(x.mode) + " against " + std::to_string(y.mode);
    if (x.vertices.size() != y.vertices.size())
      return where + std::to_string(x.vertices.size()) + " vertices against " +
             std::to_string(y.vertices.size());
    for (size_t v = 0; v < x.vertices.size(); ++v) {
      if (x.vertices[v].size() != y.vertices[v].size())
        return where + "vertex " + std::to_string(v) + " has other attributes";
      for (size_t c = 0; c < x.vertices[v].size(); ++c) {
        const float d = std::fabs(x.vertices[v][c] - y.vertices[v][c]);
        worst = std::max(worst, d);
        const float allowed =
            kCaptureUlps * FLT_EPSILON * std::max(1.0f, std::fabs(x.vertices[v][c]));
        if (d > allowed)
          return where + "vertex " + std::to_string(v) + " value " + std::to_string(c) + ": " +
                 std::to_string(x.vertices[v][c]) + " against " + std::to_string(y.vertices[v][c]);
      }
    }
  }
  return "";
}

// Every glutSolid*/glutWire* shape of clients/glut_shapes.c: what libshadowlab-glut.so sends
// the GL equals what Debian's freeglut sends it, primitive for primitive, vertex for vertex.
TEST(GlutShapes, SameCallsAsFreeglut) {
  SL_REQUIRE_GLX();
  if (std::getenv("DISPLAY") == nullptr && (!onPath("xvfb-run") || !onPath("xauth")))
    GTEST_SKIP() << "skipped: xvfb-run or xauth is not installed (scripts/setup.sh installs xvfb "
                    "and xauth)";
  const fs::path dir = testDir("interpose", true);
  const fs::path program = client("glut_shapes", sourceDir() / "tests" / "interpose" / "clients");
  const fs::path shim = captureShim(dir);
  const std::vector<CapturedShape> freeglut = captureShapes(program, shim, "glx", dir / "glx");
  const std::vector<CapturedShape> ours = captureShapes(program, shim, "osmesa", dir / "osmesa");
  constexpr size_t kShapes = 23;  // the client's 22 shapes and its "end" marker
  ASSERT_EQ(freeglut.size(), kShapes);
  ASSERT_EQ(ours.size(), kShapes);
  for (size_t i = 0; i + 1 < kShapes; ++i) {
    ASSERT_EQ(freeglut[i].call, ours[i].call);
    float worst = 0.0f;
    const std::string why = compareShape(freeglut[i], ours[i], worst);
    size_t vertices = 0;
    for (const Primitive& p : freeglut[i].primitives) vertices += p.vertices.size();
    EXPECT_EQ(why, "") << freeglut[i].call;
    std::cout << freeglut[i].call << ": " << freeglut[i].primitives.size() << " draws, " << vertices
              << " vertices: "
              << (!why.empty()    ? why
                  : worst == 0.0f ? std::string("bit-identical")
                                  : "same within the tolerance (largest difference " +
                                        std::to_string(worst) + ")")
              << "\n";
  }
  EXPECT_TRUE(freeglut.back().primitives.empty() && ours.back().primitives.empty());
}

// The same client drawn (lit, flat-shaded: each triangle's colour is its provoking vertex's)
// by run-legacy on glx and on osmesa: the same GL (Mesa 22 llvmpipe) given the same calls
// draws the same pixels.
TEST(GlutShapes, SameFrameOnGlxAndOsmesa) {
  SL_REQUIRE_GLX();
  const fs::path dir = testDir("interpose", true);
  const fs::path program = client("glut_shapes", sourceDir() / "tests" / "interpose" / "clients");
  std::vector<std::vector<uint8_t>> frames;
  for (const std::string backend : {"glx", "osmesa"}) {
    const fs::path logs = dir / backend;
    fs::create_directories(logs);
    const CommandResult r = runLegacy(program, "", logs / "frames", logs, "", backend);
    ASSERT_EQ(r.status, 0) << backend << ": " << r.err;
    int w = 0, h = 0;
    frames.push_back(pngBytes(logs / "frames" / "000.png", w, h));
    constexpr int kWidth = 384, kHeight = 256;  // the client's 6 x 4 cells of 64 pixels
    ASSERT_EQ(w, kWidth);
    ASSERT_EQ(h, kHeight);
  }
  int lit = 0;
  for (size_t i = 0; i < frames[1].size(); ++i) lit += frames[1][i] != 0;
  EXPECT_GT(lit, 0) << "osmesa drew nothing";
  EXPECT_EQ(differingPixels(frames[0], frames[1]), 0) << "glx and osmesa";
}

// Builds tests/interpose/NAME.c against Debian's OSMesa into dir/NAME.
fs::path osmesaClient(const std::string& name, const fs::path& dir) {
  const fs::path exe = dir / name;
  const std::string build = "cc -O1 -o " + exe.string() + " " +
                            (sourceDir() / "tests" / "interpose" / (name + ".c")).string() +
                            " $(pkg-config --cflags --libs osmesa) -lpthread";
  EXPECT_EQ(std::system(build.c_str()), 0) << build;
  return exe;
}

// LD_PRELOAD for a client: the library, after the AddressSanitizer runtime in a sanitizer
// build (scripts/sanitize.sh), which must come first in the process.
std::string preloadImagingLibrary() {
  const std::string runtime = SHADOWLAB_SANITIZER_RUNTIME;
  return "LD_PRELOAD='" + (runtime.empty() ? "" : runtime + " ") +
         (libraryDir() / "libshadowlab-imaging.so").string() + "'";
}

int okLines(const std::string& out) {
  int ok = out.rfind("ok ", 0) == 0 ? 1 : 0;
  for (size_t p = out.find("\nok "); p != std::string::npos; p = out.find("\nok ", p + 1)) ++ok;
  return ok;
}

// A C program on OSMesa: extension strings, GetProcAddress, merged errors, enables and
// queries, the colour matrix on glDrawPixels, contexts on two threads (osmesa_client.c).
TEST(DropIn, OsmesaClientSeesTheImagingSubset) {
  if (std::system("pkg-config --exists osmesa") != 0) GTEST_SKIP() << "skipped: no OSMesa headers";
  const fs::path dir = testDir("interpose", true);
  const fs::path exe = osmesaClient("osmesa_client", dir);
  ASSERT_TRUE(fs::exists(exe));
  const CommandResult without = runBinary(exe.string(), "", dir);
  EXPECT_EQ(without.status, 1) << "Debian's OSMesa alone has no GL_ARB_imaging";
  EXPECT_NE(without.out.find("FAIL no GL_ARB_imaging"), std::string::npos) << without.out;
  const CommandResult with = runBinary(preloadImagingLibrary() + " " + exe.string(), "", dir);
  EXPECT_EQ(with.status, 0) << with.out << with.err;
  constexpr int kChecks = 7;  // the "ok" lines osmesa_client.c prints
  EXPECT_EQ(okLines(with.out), kChecks) << with.out;
}

// Wrong enums and sizes through the preloaded library (bad_input_client.c): each call raises
// the specification's error, read through glGetError, and the program ends normally (a crash
// or a sanitizer report is a status other than 0).
TEST(DropIn, BadInputGivesTheSpecsErrorsNeverACrash) {
  if (std::system("pkg-config --exists osmesa") != 0) GTEST_SKIP() << "skipped: no OSMesa headers";
  const fs::path dir = testDir("interpose", true);
  const fs::path exe = osmesaClient("bad_input_client", dir);
  ASSERT_TRUE(fs::exists(exe));
  // With the read-back trace on, so that its reads of the program's buffers are checked too.
  const CommandResult r = runBinary("SHADOWLAB_IMAGING_TRACE=" + (dir / "trace.jsonl").string() +
                                        " " + preloadImagingLibrary() + " " + exe.string(),
                                    "", dir);
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  constexpr int kCases = 44;  // the expect() calls and the ordered pair in bad_input_client.c
  EXPECT_EQ(okLines(r.out), kCases) << r.out;
  EXPECT_NE(r.out.find("\n0 failed"), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find("Sanitizer"), std::string::npos) << "a sanitizer report: " << r.err;
  EXPECT_EQ(r.err.find("runtime error"), std::string::npos) << "a sanitizer report: " << r.err;
}

TEST(RunLegacy, BadInputIsRefusedWithStatus2) {
  const fs::path dir = testDir("interpose", true);
  const std::string bin = SHADOWLAB_BINARY;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"run-legacy --frames f -- true", "--backend is required"},
      {"run-legacy --backend vulkan --frames f -- true", "unknown --backend"},
      {"run-legacy --backend glx -- true", "--frames DIR is required"},
      {"run-legacy --backend glx --frames f", "no program"},
      {"run-legacy --backend glx --frames f -- ./no-such-program", "is not an executable"},
      {"run-legacy --backend glx --keys 'h ctrl' --frames f -- true", "key 'ctrl'"},
      {"run-legacy --backend glx --frames f --timeout -1 -- true", "--timeout"},
      {"run-legacy --backend glx --bogus 1 --frames f -- true", "run-legacy:"},
  };
  for (const auto& [args, message] : cases) {
    const CommandResult r = runBinary("cd " + dir.string() + " && " + bin, args, dir);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
  }
  fs::create_directories(dir / "full");
  std::ofstream(dir / "full" / "x.png") << "x";
  const CommandResult r = runBinary(
      bin, "run-legacy --backend glx --frames " + (dir / "full").string() + " -- /bin/true", dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("is not empty"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace sl
