// apps/cmd_exercise.cpp — `shadowlab exercise`: the graded exercises (teach/exercise.h).
//
//   exercise list                 one line per exercise: id, legacy|modern, answer form, title
//   exercise show ID              the task, the answer's form and (file exercises) the starting
//   file exercise start ID --out FILE  writes the starting file (never over an existing file)
//   exercise grade ID ANSWER      renders and measures the answer: "PASS id: reason" (exit 0) or
//                                 "FAIL id: reason" (exit 1) on stdout
// Bad input (unknown id, missing file, malformed answer): one line on stderr, exit 2.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "apps/commands.h"
#include "core/base/errors.h"
#include "core/base/output_files.h"
#include "teach/exercise.h"

namespace sl {
namespace {

const char* kExerciseHelp =
    R"(usage: shadowlab exercise list
       shadowlab exercise show ID
       shadowlab exercise start ID --out FILE
       shadowlab exercise grade ID ANSWER
Graded exercises: the student edits a parameter file or answers with a number, and shadowlab
grades the answer by rendering and measuring it (160x120 frames; docs/course.md).
  list                  every exercise: id, legacy or modern, answer form, title
  show ID               the task, the answer's form and the keys a parameter file may set;
                        for a parameter-file exercise, the starting file
  start ID --out FILE   writes the starting parameter file to FILE (FILE must not exist)
  grade ID ANSWER       ANSWER: a number, or a file (a number, or key=value lines); prints
                        "PASS ID: reason" or "FAIL ID: reason"
Exit status: 0 pass (or done), 1 fail, 2 bad input (unknown id, missing file, malformed
answer, a value the technique refuses), 3 GL failure.
)";

void expectArguments(const std::vector<std::string>& a, size_t n, const std::string& form) {
  if (a.size() != n)
    throw InputError("usage: shadowlab exercise " + form + " (try: shadowlab exercise --help)");
}

int listExercises() {
  for (const teach::Exercise& e : teach::exercises())
    std::cout << e.id << "  " << e.family << "  " << teach::answerFormName(e.form) << "  "
              << e.title << "\n";
  return 0;
}

// `...` marks code in the task texts; on a terminal it is kept as written.
int show(const teach::Exercise& e) {
  std::cout << e.id << " (" << e.family << ", " << e.technique << "): " << e.title << "\n\n"
            << e.task << "\n\nAnswer: ";
  if (e.form == teach::AnswerForm::kNumber) {
    std::cout << "a number: shadowlab exercise grade " << e.id << " NUMBER\n";
    return 0;
  }
  std::string keys;
  for (const std::string& k : e.keys) keys += (keys.empty() ? "" : ", ") + k;
  std::cout << "a parameter file (key=value lines; keys: " << keys << "):\n"
            << "  shadowlab exercise start " << e.id << " --out answer.params\n"
            << "  (edit answer.params)\n"
            << "  shadowlab exercise grade " << e.id << " answer.params\n\n"
            << "The starting file:\n"
            << teach::readTextFile(teach::startFilePath(e));
  return 0;
}

int start(const teach::Exercise& e, const std::string& out) {
  const std::string text = teach::readTextFile(teach::startFilePath(e));
  std::error_code ec;
  if (std::filesystem::exists(out, ec))
    throw InputError("--out " + out + " exists; exercise start never overwrites an answer");
  OutputSet outputs;
  const std::string path = outputs.addFile("--out", out);
  outputs.beginWriting();
  std::ofstream o(path, std::ios::binary);
  o << text;
  o.close();
  if (!o) throw InputError("--out " + out + ": cannot write");
  outputs.commit();
  std::cout << "wrote " << out << "\n";
  return 0;
}

int gradeCommand(const teach::Exercise& e, const std::string& answer) {
  const teach::Answer a = teach::readAnswer(e, answer);
  const teach::Grade g = teach::grade(e, a);
  std::cout << (g.pass ? "PASS " : "FAIL ") << e.id << ": " << g.reason << "\n";
  return g.pass ? 0 : kExitOther;
}

}  // namespace

int exercise(int argc, char** argv) {
  std::vector<std::string> a(argv + 1, argv + argc);  // after "exercise"
  for (const std::string& s : a)
    if (s == "--help" || s == "-h") {
      std::cout << kExerciseHelp;
      return 0;
    }
  if (a.empty()) throw InputError("exercise: no subcommand (try: shadowlab exercise --help)");
  const std::string sub = a.front();
  if (sub == "list") {
    expectArguments(a, 1, "list");
    return listExercises();
  }
  if (sub == "show") {
    expectArguments(a, 2, "show ID");
    return show(teach::findExercise(a[1]));
  }
  if (sub == "start") {
    expectArguments(a, 4, "start ID --out FILE");
    if (a[2] != "--out")
      throw InputError(
          "usage: shadowlab exercise start ID --out FILE (try: shadowlab exercise "
          "--help)");
    return start(teach::findExercise(a[1]), a[3]);
  }
  if (sub == "grade") {
    expectArguments(a, 3, "grade ID ANSWER");
    return gradeCommand(teach::findExercise(a[1]), a[2]);
  }
  throw InputError("exercise: unknown subcommand '" + sub +
                   "' (list, show, start, grade; try: shadowlab exercise --help)");
}

}  // namespace sl
