#include "teach/exercise_page.h"

#include <filesystem>
#include <iostream>
#include <sstream>

#include "core/base/html.h"
#include "teach/exercise.h"

namespace sl::teach {

std::string gradedExercisesTeacherHtml(bool progress) {
  std::ostringstream h;
  h << "<section class=step id=graded>\n<h2>Graded exercises</h2>\n<p>The student answers "
       "with a number or a parameter file, and <code>shadowlab exercise grade ID ANSWER</code> "
       "renders and measures the answer (exit status 0 pass, 1 fail). <code>shadowlab exercise "
       "list</code> names them, <code>shadowlab exercise show ID</code> prints the task and "
       "<code>shadowlab exercise start ID --out FILE</code> writes a parameter file to edit. "
       "Each verdict below is the grader's on the model answer, measured when this page was "
       "written.</p>\n";
  for (const Exercise& e : exercises()) {
    if (progress) std::cerr << "[course] graded exercise " << e.id << std::endl;
    const std::string model = modelAnswerPath(e);
    h << "<div class=exercise id=\"graded-" << htmlEscape(e.id) << "\">\n<h3>" << htmlEscape(e.id)
      << ": " << htmlEscape(e.title) << " (" << htmlEscape(e.family) << ", "
      << htmlEscape(e.technique) << ")</h3>\n<p><b>Task:</b> " << htmlWithCode(e.task)
      << "</p>\n<p><b>Graded by:</b> " << htmlEscape(e.measures) << ".</p>\n";
    std::string verdict;
    try {
      const std::string text = readTextFile(model);
      h << "<p class=answer><b>Model answer</b> (<code>assets/exercises/" << htmlEscape(e.id) << "/"
        << htmlEscape(std::filesystem::path(model).filename().string()) << "</code>):</p>\n<pre>"
        << htmlEscape(text) << "</pre>\n";
      const Grade g = grade(e, modelAnswer(e));
      h << "<p" << (g.pass ? "" : " class=error") << "><b>" << (g.pass ? "PASS" : "FAIL")
        << "</b>: " << htmlEscape(g.reason) << "</p>\n";
    } catch (const std::exception& x) {
      h << "<p class=error>The model answer could not be graded: " << htmlEscape(x.what())
        << "</p>\n";
    }
    h << "</div>\n";
  }
  h << "</section>\n";
  return h.str();
}

}  // namespace sl::teach
