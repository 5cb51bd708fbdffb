// teach/lesson.h — `shadowlab lesson TECHNIQUE --out DIR`: one
// self-contained HTML page that teaches a technique pass by pass.
//
//   DIR/index.html                     the lesson (no network; every link relative)
//   DIR/<technique>_<dump file>.png    the pass images of each technique shown (teach/pass_dump.h)
//   DIR/diff-mask.png, diff-image.png  legacy against modern, where the technique has a twin
//                                      (-4x4 for the second footprint of PCF and fast PCF)
//   DIR/why-<block>-<n>.png            the pictures of the "why" blocks, rendered for the page
//
// The page holds: the paper's idea in our words with its section, equation and figure numbers
// (assets/lessons/*.json, read with nlohmann-json); the legacy pass strip with captions and GL
// state cards; the modern twin's passes with the GLSL lines they run beside them (the ranges
// passes.json gives, read from the embedded shaders); legacy against modern for the mask and
// the image, with counts, difference images and the reason for image differences
// (registry/twins.h gives the pair and its bound); the command that re-makes each picture; and
// the known departures (every `DEVIATION (...)` comment of the technique's source files).
// The "why" blocks of the lesson text answer a student's questions with pictures rendered at
// lesson time and numbers read from the page's own GL traces (the texgen planes beside the
// twin's matrix rows; each 4x4 phase's kernel and texture matrix). PCF and fast PCF show the
// 2x2 and the 4x4 pair of the twin table. State cards highlight the lines the pass table
// declares (PassSpec::keyState) and fold setup and repeated lines; printed, one pass per page.
// A pass whose passes.json entry has no "state" shows "state card: not recorded".
// A technique without a twin (the later papers, the references) shows its own passes.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "registry/cli.h"

namespace sl::figures {

// What the lessons render: the scene and sizes. Small sizes keep the main job fast.
struct LessonSettings {
  std::string scene = "brabec";
  int width = 400;
  int height = 300;
  int shadowMapTexels = 512;
};

// `shadowlab lesson TECHNIQUE --out DIR [--scene S] [--size WxH] [--shadow-map N]`: renders,
// then writes DIR as a whole (core/base/output_files.h: all or none). Bad input -> InputError.
int runLessonCommand(const cli::Args& args);

// The main job's lessons: one folder per technique under `lessonsDir` (lessonsDir/<name>/).
struct LessonLink {
  std::string technique;
  std::string href;   // "<name>/index.html", relative to lessonsDir
  std::string title;  // the lesson's title
  std::string error;  // why it could not be written; empty when written
};
std::vector<LessonLink> writeLessons(const std::string& lessonsDir,
                                     const std::vector<std::string>& techniques,
                                     const LessonSettings& settings, bool progress);

// The report's section linking the lessons (hrefs prefixed with `base`, e.g. "lessons/"); a
// lesson that could not be written is listed in red with the reason.
std::string lessonIndexHtml(const std::vector<LessonLink>& links, const std::string& base);

// Techniques registered in this build that have no entry in assets/lessons/*.json (a test
// asserts there are none), and the title of a technique's lesson (InputError when none).
std::vector<std::string> techniquesWithoutLesson();
std::string lessonTitle(const std::string& technique);
// Techniques registered in this build whose lesson text has no "why" block with a rendered
// picture (a "renders" entry); a test asserts there are none.
std::vector<std::string> techniquesWithoutWhyPicture();
// How many pictures the "why" blocks of a technique's lesson render (InputError: no lesson).
size_t whyPictureCount(const std::string& technique);

}  // namespace sl::figures
