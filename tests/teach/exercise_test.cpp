// tests/teach/exercise_test.cpp — the graded exercises (teach/exercise.h): for every exercise
// the grader fails an empty answer (for a parameter file: graded as the unmodified starting
// file) and a wrong one, and passes the model answer; bad answers are InputErrors.
#include "teach/exercise.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "apps/command_util.h"
#include "core/base/errors.h"
#include "registry/shadow_error.h"
#include "test_names.h"

namespace fs = std::filesystem;
using sl::teach::Answer;
using sl::teach::AnswerForm;
using sl::teach::Exercise;
using sl::teach::findExercise;
using sl::teach::Grade;

namespace {

// A wrong answer per exercise: the text of the answer file, and a word the fail reason must
// hold (what the measurement found wrong).
struct Case {
  std::string id;
  std::string wrong;        // the answer file's text
  std::string wrongReason;  // a word of the FAIL reason
  std::string wrong2 = "";  // a second wrong answer (the other way to be wrong), or empty
  std::string wrong2Reason = "";
};

const std::vector<Case>& cases() {
  static const std::vector<Case> kCases = {
      // No bias: acne. Far too much: the shadows detach (light leaks into the umbra).
      {"ramp-acne-bias", "0\n", "acne", "40\n", "detach"},
      // 4x4 is a footprint too, but of sixteen samples.
      {"pcf-3x3", "filter=4\n", "1/16"},
      // Nine samples, but four per pass: fewer runs than samples.
      {"pcf-colour-passes", "9\n", "not the number"},
      // Constant bias raised instead of a slope factor; or a slope factor so large that
      // shadows detach.
      {"hw-slope-bias", "offset-units=400\n", "raises the constant", "offset-factor=60\n",
       "detach"},
      // The bleeding scene (after Annen et al. Fig. 9), but with the bleeding reduced away; or
      // no reduction, on a scene without occluders at different depths over one receiver.
      {"vsm-bleeding", "scene=bleeding\nbleed-reduction=0.3\n", "no visible",
       "scene=brabec\nbleed-reduction=0\n", "no visible"},
      // Sixteen samples give seventeen levels, not sixteen.
      {"modern-pcf-levels", "16\n", "not the number"},
  };
  return kCases;
}

// gtest prints a parameter's bytes unless told how: the id names a case.
void PrintTo(const Case& c, std::ostream* os) { *os << c.id; }

fs::path writeAnswer(const fs::path& dir, const std::string& name, const std::string& text) {
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p;
}

std::string answerName(const Exercise& e) {
  return e.form == AnswerForm::kNumber ? "answer.txt" : "answer.params";
}

class ExerciseGrading : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    if (!sl::haveRayTracedReferences()) GTEST_SKIP() << "built without the ray tracer";
  }
};

// An empty answer; for a parameter file, also the unmodified starting file (an empty file is
// graded as the starting file, so both must fail by measurement).
TEST_P(ExerciseGrading, FailsAnEmptyOrUnmodifiedAnswer) {
  const Exercise& e = findExercise(GetParam().id);
  const fs::path dir = sl::test::testDir("exercise", true);
  const Grade g =
      sl::teach::grade(e, sl::teach::readAnswer(e, writeAnswer(dir, answerName(e), "").string()));
  EXPECT_FALSE(g.pass) << g.reason;
  EXPECT_FALSE(g.reason.empty());
  if (e.form == AnswerForm::kParams) {
    const Grade start = sl::teach::grade(e, sl::teach::readAnswer(e, sl::teach::startFilePath(e)));
    EXPECT_FALSE(start.pass) << start.reason;
    EXPECT_EQ(start.reason, g.reason);
  }
}

TEST_P(ExerciseGrading, FailsAWrongAnswerAndSaysWhy) {
  const Case& c = GetParam();
  const Exercise& e = findExercise(c.id);
  const fs::path dir = sl::test::testDir("exercise", true);
  for (const auto& [text, word] :
       {std::pair{c.wrong, c.wrongReason}, std::pair{c.wrong2, c.wrong2Reason}}) {
    if (text.empty()) continue;
    const Grade g = sl::teach::grade(
        e, sl::teach::readAnswer(e, writeAnswer(dir, answerName(e), text).string()));
    EXPECT_FALSE(g.pass) << text << ": " << g.reason;
    EXPECT_NE(g.reason.find(word), std::string::npos) << text << ": " << g.reason;
  }
}

TEST_P(ExerciseGrading, PassesTheModelAnswer) {
  const Exercise& e = findExercise(GetParam().id);
  const Grade g = sl::teach::grade(e, sl::teach::modelAnswer(e));
  EXPECT_TRUE(g.pass) << g.reason;
  EXPECT_FALSE(g.measured.empty());
}

INSTANTIATE_TEST_SUITE_P(Each, ExerciseGrading, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return sl::testName(info.param.id); });

TEST(Exercises, EveryExerciseHasACaseAModelAndBothFamiliesAppear) {
  std::set<std::string> tested, families;
  for (const Case& c : cases()) tested.insert(c.id);
  for (const Exercise& e : sl::teach::exercises()) {
    EXPECT_TRUE(tested.count(e.id)) << e.id << " has no grading test";
    EXPECT_TRUE(fs::is_regular_file(sl::teach::modelAnswerPath(e))) << e.id;
    if (e.form == AnswerForm::kParams) {
      EXPECT_TRUE(fs::is_regular_file(sl::teach::startFilePath(e))) << e.id;
    }
    families.insert(e.family);
  }
  EXPECT_GE(sl::teach::exercises().size(), 6u);
  EXPECT_EQ(families, (std::set<std::string>{"legacy", "modern"}));
}

TEST(Exercises, BadAnswersAreInputErrors) {
  const fs::path dir = sl::test::testDir("exercise", true);
  EXPECT_THROW(findExercise("no-such-exercise"), sl::InputError);
  const Exercise& params = findExercise("pcf-3x3");
  const Exercise& number = findExercise("ramp-acne-bias");
  // A missing file; a key the exercise does not let the answer set; a key set twice; a line
  // without '='; a number exercise's answer that is neither a number nor a file; a file whose
  // text is not a number.
  EXPECT_THROW(sl::teach::readAnswer(params, (dir / "missing.params").string()), sl::InputError);
  EXPECT_THROW(sl::teach::readAnswer(params, writeAnswer(dir, "a", "shadow-map=64\n").string()),
               sl::InputError);
  EXPECT_THROW(
      sl::teach::readAnswer(params, writeAnswer(dir, "b", "filter=3\nfilter=4\n").string()),
      sl::InputError);
  EXPECT_THROW(sl::teach::readAnswer(params, writeAnswer(dir, "c", "filter 3\n").string()),
               sl::InputError);
  EXPECT_THROW(sl::teach::readAnswer(number, "two"), sl::InputError);
  EXPECT_THROW(sl::teach::readAnswer(number, writeAnswer(dir, "d", "2 steps\n").string()),
               sl::InputError);
  // A value the technique refuses is bad input too, found when the grader renders.
  if (sl::haveRayTracedReferences()) {
    EXPECT_THROW(sl::teach::grade(number, sl::teach::readAnswer(number, "-1")), sl::InputError);
  }
}

TEST(Exercises, CommentsAndBlankLinesAreSkippedAndUnsetKeysKeepTheStartingValues) {
  const fs::path dir = sl::test::testDir("exercise", true);
  const Exercise& e = findExercise("hw-slope-bias");
  const Answer a = sl::teach::readAnswer(
      e, writeAnswer(dir, "a.params", "# a comment\n\n  offset-factor = 1.5 \n").string());
  EXPECT_EQ(a.given, (std::map<std::string, std::string>{{"offset-factor", "1.5"}}));
  const Answer start = sl::teach::readAnswer(e, sl::teach::startFilePath(e));
  EXPECT_EQ(a.all.at("offset-units"), start.all.at("offset-units"));
  EXPECT_EQ(a.all.at("offset-factor"), "1.5");
}

}  // namespace
