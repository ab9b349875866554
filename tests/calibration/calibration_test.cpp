#include <gtest/gtest.h>

#include "foveal/runtime/calibration.hpp"

namespace foveal {
namespace {

// Feeds answers until done; fails the test on a rejected answer.
CalibrationResult run(Calibration& c, const std::vector<Answer>& answers) {
  for (Answer a : answers) {
    EXPECT_FALSE(c.done());
    EXPECT_TRUE(c.answer(a)) << "stage " << calibration_stage_name(c.prompt().stage);
  }
  EXPECT_TRUE(c.done());
  return c.result();
}

using A = Answer;

TEST(Calibration, TheEfrSeedUserEndsAtTwoAndThree) {
  Calibration c;
  EXPECT_EQ(c.prompt().stage, CalibrationStage::dominant_eye);
  std::vector<A> answers = {A::right, A::right, A::right};
  for (int i = 0; i < 5; ++i) answers.push_back(A::different);  // 3.0 .. 2.2 look different
  answers.push_back(A::same);                                   // 2.0 looks like full
  for (int i = 0; i < 5; ++i) answers.push_back(A::same);       // non-dominant 2.2 .. 3.0 fine
  answers.push_back(A::different);                              // 3.2 is too much
  answers.insert(answers.end(), {A::same, A::same, A::same});   // validation
  const CalibrationResult r = run(c, answers);
  EXPECT_EQ(r.dominant_eye, Eye::right);
  EXPECT_TRUE(r.dominant_consistent);
  EXPECT_DOUBLE_EQ(r.sigma_uniform, 2.0);
  EXPECT_DOUBLE_EQ(r.sigma_non_dominant, 3.0);
  EXPECT_TRUE(r.passed());
}

TEST(Calibration, PromptsShowTheSliderOnTheRightEyes) {
  Calibration c;
  for (A a : {A::left, A::left, A::right}) ASSERT_TRUE(c.answer(a));  // majority left
  EXPECT_EQ(c.prompt().stage, CalibrationStage::sigma_uniform);
  EXPECT_DOUBLE_EQ(c.prompt().sigma_left, 3.0);
  EXPECT_DOUBLE_EQ(c.prompt().sigma_right, 3.0);
  ASSERT_TRUE(c.answer(A::different));
  EXPECT_DOUBLE_EQ(c.prompt().sigma_left, 2.8);
  ASSERT_TRUE(c.answer(A::same));  // sigma_UF = 2.8
  EXPECT_EQ(c.prompt().stage, CalibrationStage::sigma_non_dominant);
  // Left is dominant: it stays at sigma_UF, the right eye goes up.
  EXPECT_DOUBLE_EQ(c.prompt().sigma_left, 2.8);
  EXPECT_DOUBLE_EQ(c.prompt().sigma_right, 3.0);
  ASSERT_TRUE(c.answer(A::different));  // at once: sigma_NF = sigma_UF
  EXPECT_EQ(c.prompt().stage, CalibrationStage::validation);
  EXPECT_TRUE(c.prompt().identical);
  for (A a : {A::same, A::different, A::same}) ASSERT_TRUE(c.answer(a));
  ASSERT_TRUE(c.done());
  EXPECT_EQ(c.result().dominant_eye, Eye::left);
  EXPECT_FALSE(c.result().dominant_consistent);
  EXPECT_DOUBLE_EQ(c.result().sigma_non_dominant, 2.8);
  EXPECT_TRUE(c.result().passed());  // one wrong of three is tolerated
}

TEST(Calibration, InattentiveUserFailsValidation) {
  Calibration c;
  const CalibrationResult r = run(c, {A::right, A::right, A::right, A::same, A::different, A::different, A::different, A::same});
  EXPECT_EQ(r.validation_failures, 2);
  EXPECT_FALSE(r.passed());
}

TEST(Calibration, SliderStopsAtItsBounds) {
  Calibration c;
  std::vector<A> answers = {A::right, A::right, A::right};
  for (int i = 0; i < 10; ++i) answers.push_back(A::different);  // 3.0 down to 1.2
  answers.push_back(A::same);                                    // 1.0: sigma_UF
  for (int i = 0; i < 25; ++i) answers.push_back(A::same);       // 1.2 up to 6.0: never different
  answers.insert(answers.end(), {A::same, A::same, A::same});
  const CalibrationResult r = run(c, answers);
  EXPECT_DOUBLE_EQ(r.sigma_uniform, 1.0);
  EXPECT_DOUBLE_EQ(r.sigma_non_dominant, 6.0);
}

TEST(Calibration, AnswersThatDoNotFitThePromptAreRejected) {
  Calibration c;
  EXPECT_FALSE(c.answer(A::same));  // the Miles test wants an eye
  for (A a : {A::right, A::right, A::right}) ASSERT_TRUE(c.answer(a));
  EXPECT_FALSE(c.answer(A::left));  // the slider wants same/different
  EXPECT_EQ(c.prompt().stage, CalibrationStage::sigma_uniform);
  EXPECT_FALSE(parse_answer("maybe"));
  EXPECT_EQ(*parse_answer("d"), A::different);
}

}  // namespace
}  // namespace foveal
