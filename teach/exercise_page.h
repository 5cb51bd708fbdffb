// teach/exercise_page.h — the graded exercises (teach/exercise.h) on the course's teacher's
// page (figures/course.cpp): each exercise's task, what the grader measures, its model answer
// (assets/exercises/<id>/model.*) and the grader's verdict on that model answer, measured when
// the page is written.
#pragma once

#include <string>

namespace sl::teach {

// The teacher's page section <section id=graded>; an exercise whose model answer could not be
// graded or failed is shown with the reason in red (class=error). `progress`: one line per
// exercise on stderr.
std::string gradedExercisesTeacherHtml(bool progress);

}  // namespace sl::teach
