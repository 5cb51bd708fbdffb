// teach/exercise.h — the graded exercises of `shadowlab exercise` (docs/course.md, "Graded
// exercises"): a student changes a parameter file or answers with a number, and the program
// grades the answer by measuring it: it renders the answer (or the frame the question is
// about) and measures the mask against the ray-traced truth with the one definition of shadow
// error (registry/shadow_error.h), the levels of the visibility mask, or the passes the frame
// ran (by pass id, from the technique's pass table). Nothing is graded by comparing text.
//
// The exercises are declared once, in exercise.cpp; each has a folder assets/exercises/<id>/
// with its model answer (model.txt: a number; model.params: a parameter file) and, for a
// parameter-file exercise, the file the student starts from (start.params).
//
// A parameter file: one `key=value` a line; blank lines and lines starting with '#' are
// skipped. Only the keys the exercise names may appear (an unknown or repeated key is bad
// input); a key the answer leaves out keeps the starting file's value, so an empty answer is
// graded as the unmodified starting file. The keys `scene` (a --scene name) and `filter` (the
// --filter side) set those options; every other key is a --param of the exercise's technique.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sl::teach {

enum class AnswerForm { kNumber, kParams };
const char* answerFormName(AnswerForm form);  // "number", "parameter file"

struct Exercise {
  std::string id;         // "ramp-acne-bias": the folder of assets/exercises/
  std::string family;     // "legacy" or "modern": the side of the course it exercises
  std::string technique;  // the technique the grader renders
  std::string title;      // one line
  std::string task;       // what the student does; `...` marks a command, key or file
  AnswerForm form = AnswerForm::kNumber;
  std::vector<std::string> keys;  // kParams: the keys the answer may set
  std::string measures;           // for the teacher: what the grader measures and when it passes
};

// Every graded exercise, in the course's order (legacy before modern within a topic).
const std::vector<Exercise>& exercises();
// InputError ("unknown exercise 'x' (shadowlab exercise list names them)") when none has `id`.
const Exercise& findExercise(const std::string& id);

// assets/exercises/<id>/ and its files: the model answer and (kParams) the starting file.
std::string exerciseFolder(const Exercise& e);
std::string modelAnswerPath(const Exercise& e);
std::string startFilePath(const Exercise& e);  // InputError for a number exercise

struct Answer {
  std::string source;                        // what it was read from: "the value 3", a path
  std::optional<double> number;              // kNumber; empty: no number given
  std::map<std::string, std::string> given;  // kParams: the keys the answer set
  std::map<std::string, std::string> all;    // kParams: the starting file's keys, then `given`
};

// The answer to `e` given on the command line: for a number exercise, a decimal number or a
// file holding one (an empty file is an answer without a number); for a parameter-file
// exercise, a file. InputError for a missing or unreadable file, a malformed number or line,
// or a key the exercise does not let the answer set.
Answer readAnswer(const Exercise& e, const std::string& valueOrFile);
Answer modelAnswer(const Exercise& e);

struct Grade {
  bool pass = false;
  std::string reason;  // one sentence: what was measured, and why that passes or fails
  std::vector<std::pair<std::string, double>> measured;  // name -> value, as measured
};

// Renders and measures (160x120 frames): InputError for a value the technique refuses (a
// --param out of its range, an unknown scene), GlError for a GL failure or a build without the
// ray-traced references.
Grade grade(const Exercise& e, const Answer& answer);

// The text of a parameter file or a number file as the student sees it (the file's bytes).
std::string readTextFile(const std::string& path);

}  // namespace sl::teach
