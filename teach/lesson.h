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
#include <map>
#include <string>
#include <vector>

#include "registry/cli.h"

namespace sl::figures {

// A figure of the report as the lessons name it. figures/ fills these from its figure list
// (figures/figure_spec.h figureList, which teach/ cannot include): the id (report.html#id), the
// paper's figure and title, and the techniques the figure shows.
struct FigureRef {
  std::string id;                       // "brabec-fig7"
  std::string title;                    // "Brabec & Seidel 2001, Figure 7 (a-h): ..."
  std::vector<std::string> techniques;  // figures/figure_spec.h figureTechniques
};

// Where a page finds the report's figures.
struct ReportLinks {
  std::vector<FigureRef> figures;  // every figure of the list
  // report.html relative to the page's folder ("../../report.html" from OUT/lessons/T/); empty
  // when no report is written beside the page (`shadowlab lesson`, `shadowlab course`).
  std::string href;
  // The figures that report holds: listed id -> the id of its <article> there (an --only run
  // holds some; a --set run names its version's folder).
  std::map<std::string, std::string> anchors;
};

// What the lessons render: the scene and sizes (small sizes keep the main job fast), and the
// report figures they link.
struct LessonSettings {
  std::string scene = "brabec";
  int width = 400;
  int height = 300;
  int shadowMapTexels = 512;
  ReportLinks report;
};

// The techniques a technique's lesson teaches: those its lesson text names (legacy.pcf's
// lesson: legacy.pcf and modern.pcf); the technique alone when it has no lesson text.
std::vector<std::string> lessonSubjects(const std::string& technique);
// Whether `figure` shows one of `subjects` (a lesson's, lessonSubjects): the one relation
// behind every link between the lessons, the course's steps and the report's figures.
bool figureShows(const FigureRef& figure, const std::vector<std::string>& subjects);

// A report figure as a page links it: `href` is empty when the report is not beside the page
// or does not hold the figure.
struct FigureLink {
  std::string id;
  std::string title;
  std::string href;  // "../../report.html#brabec-fig7"
};
// The figures of `report` that show the lessons of `techniques` (one lesson, or a course
// step's), in the figure list's order.
std::vector<FigureLink> figureLinksFor(const std::vector<std::string>& techniques,
                                       const ReportLinks& report);
// Those links as HTML (a <ul class="report-figures">; a figure without href is named), and the
// sentence a page shows when it names one: the command that makes it.
std::string figureLinksHtml(const std::vector<FigureLink>& links);
std::string unlinkedFiguresHtml();

// `shadowlab lesson TECHNIQUE --out DIR [--scene S] [--size WxH] [--shadow-map N]`: renders,
// then writes DIR as a whole (core/base/output_files.h: all or none). Bad input -> InputError.
// `figures`: the report's figures, named on the page (no report is written beside it).
int runLessonCommand(const cli::Args& args, const std::vector<FigureRef>& figures);

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
