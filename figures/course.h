// figures/course.h — `shadowlab course --out DIR`: the lessons (teach/lesson.h) in a teaching
// order, with exercises, a teacher's page and the artefact gallery (figures/gallery.h).
//
//   DIR/index.html            the course: the steps in order, what each adds, links to each
//                             step's lesson pages, its report figures (CourseSettings::report)
//                             and the gallery, 2-3 exercises per step
//                             (the `shadowlab render` commands of a picture pair, a link that
//                             opens the pair in the live lab, a question); the exercises as
//                             JSON in <script id=course-data> (the browser test reads it)
//   DIR/teacher.html          the answers, beside the pictures each exercise should produce
//                             and the graded exercises (teach/exercise_page.h)
//   DIR/teacher/<id>-a.png    those pictures, rendered by the real renderer (-b.png: side B)
//   DIR/gallery/              the artefact gallery (writeGallery)
//   DIR/lessons/<technique>/  every lesson (writeLessons), unless the caller wrote them already
//
// The order, what each step adds and the exercises are declared once, in
// assets/course/course.json (read with nlohmann-json). Every page is offline (no network; every
// link but the lab's is relative), has a print stylesheet, and names the command and commit
// that made it. Each page and picture folder is replaced as a whole; the pages are written
// last, after everything they link exists.
#pragma once

#include <string>
#include <vector>

#include "figures/gallery.h"
#include "registry/cli.h"
#include "teach/lesson.h"

namespace sl::figures {

// One exercise: a picture pair (side A, side B) to render or open in the lab, and a question.
// The pair is carried as a GalleryEntry (A = its "wrong" side, B = its "right" side), so that
// the render arguments and the lab link are the gallery's own (galleryRenderArguments,
// galleryLabQuery); its close-up window is the whole frame.
struct CourseExercise {
  std::string id;        // anchors and picture names: "hw-acne"
  std::string tryText;   // what to render or open
  std::string question;  // for the student
  std::string answer;    // for the teacher's page: checked against the rendered pictures
  bool lab = false;      // every option is one the lab's URL names (docs/lab.md)
  std::string gallery;   // the id of the artefact gallery's entry it shows, or empty
  // "compare": the teacher's page runs `shadowlab compare` of A against B when it is written
  // and prints its numbers, so that an answer cites a run, not a typed number; empty: none.
  std::string measure;
  GalleryEntry pair;
};

struct CourseStep {
  std::string id;                       // anchor: "step-hw"
  std::vector<std::string> techniques;  // the lesson pages of this step (one lesson text)
  std::string adds;                     // what this step adds to the ones before it
  std::vector<CourseExercise> exercises;
};

// A topic the course leaves out, what it is and where to read it (the scope page).
struct CourseScopeTopic {
  std::string topic, what, read;
};

struct Course {
  std::string title;
  std::string intro;
  std::string order;   // why the steps come in this order
  std::string naming;  // a name that means another thing elsewhere ("CSM")
  std::vector<CourseScopeTopic> scope;
  std::vector<CourseStep> steps;
};

// assets/course/course.json, parsed (InputError naming the file and the field when malformed).
Course loadCourse();

// The arguments of `shadowlab render` for side A (sideA) or B, without --out, and the whole
// command with --out <id>-a.png or <id>-b.png.
std::vector<std::string> exerciseRenderArguments(const CourseExercise& e, bool sideA);
std::string exerciseRenderCommand(const CourseExercise& e, bool sideA);
// The lab link (labUrl + "?" + the gallery's query): A and B as the two sides. InputError
// when the exercise is not a lab exercise.
std::string exerciseLabLink(const CourseExercise& e, const std::string& labUrl);
// The arguments of `shadowlab compare` of an exercise's A (--a) against its B (--b): the scene,
// size and common options once, each side's params as --a-param / --b-param. InputError when a
// side has an option compare cannot set per side.
std::vector<std::string> exerciseCompareArguments(const CourseExercise& e);

struct CourseSettings {
  LessonSettings lessons;                // how writeCourse renders the lessons
  bool writeLessons = true;              // false: the caller wrote them at lessonsHref
  std::string lessonsHref = "lessons/";  // relative to DIR, ending in "/"
  std::string labUrl = kDefaultLabUrl;
  bool progress = false;  // progress lines on stderr
  // The report's figures each step links (the ones of its lessons, teach/lesson.h
  // figureLinksFor); with no report beside the course (report.href empty) they are named.
  ReportLinks report;
};

struct CourseSummary {
  int steps = 0, exercises = 0, pictures = 0, artefacts = 0;
  std::vector<std::string> lessonErrors;  // "technique: why", one per lesson not written
};

// Renders the exercises' pictures, writes the gallery and (settings.writeLessons) the lessons,
// then the two pages. Throws InputError for bad input, GlError for a GL failure.
CourseSummary writeCourse(const std::string& dir, const CourseSettings& settings);

// The main job's course (figures/figures.cpp): writes OUT/course/ with the lessons the main job
// wrote in OUT/lessons/ (not rendered again), and returns report.html's section linking the
// course, its teacher's page and its gallery; a course that could not be written is named in
// red with the reason.
// Each step links the report's figures of its lessons (`report`: from OUT/course/).
std::string writeCourseForReport(const std::string& outDir, const ReportLinks& report,
                                 bool progress);

// `shadowlab course --out DIR [--lab URL]`.
int runCourseCommand(const cli::Args& args);

}  // namespace sl::figures
