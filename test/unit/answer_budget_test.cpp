// The preview's answer budget: the solve gets what the rest of the answer leaves.
#include <cmath>

#include <gtest/gtest.h>

#include "virtual_origami/core/answer_budget.h"

using virtual_origami::core::AnswerBudget;

TEST(AnswerBudget, BeforeAnyAnswerTheSolveGetsTheBudgetLessTheTimeGone)
{
  const AnswerBudget budget(0.020, 0.001);
  EXPECT_DOUBLE_EQ(budget.expectedAfterSolve(10000), 0.0);
  EXPECT_DOUBLE_EQ(budget.solveSeconds(0.0, 10000), 0.020);
  EXPECT_DOUBLE_EQ(budget.solveSeconds(0.005, 10000), 0.015);
}

TEST(AnswerBudget, WhatTheAnswerSpentAfterItsSolveIsKeptBackFromTheNext)
{
  AnswerBudget budget(0.020, 0.001);
  // Budget set 2 ms in, the solve took 12 ms, the answer 20 ms: 6 ms after the solve.
  budget.record(0.002, 0.012, 0.020, 10000);
  EXPECT_NEAR(budget.expectedAfterSolve(10000), 0.006, 1e-15);
  EXPECT_NEAR(budget.solveSeconds(0.002, 10000), 0.012, 1e-15);
}

TEST(AnswerBudget, ALongerTailCountsAtOnceAShorterOneGradually)
{
  AnswerBudget budget(0.030, 0.001);
  budget.record(0.0, 0.010, 0.014, 500);  // 4 ms after the solve
  budget.record(0.0, 0.010, 0.020, 500);  // 10 ms: taken at once
  EXPECT_NEAR(budget.expectedAfterSolve(500), 0.010, 1e-15);
  budget.record(0.0, 0.010, 0.012, 500);  // 2 ms: a quarter of the way down
  EXPECT_NEAR(budget.expectedAfterSolve(500), 0.008, 1e-15);
  for (int i = 0; i < 60; ++i)
    budget.record(0.0, 0.010, 0.012, 500);
  EXPECT_NEAR(budget.expectedAfterSolve(500), 0.002, 1e-9);
}

TEST(AnswerBudget, APaperOfAnotherSizeStartsAgain)
{
  AnswerBudget budget(0.020, 0.001);
  budget.record(0.0, 0.005, 0.015, 10000);
  EXPECT_NEAR(budget.expectedAfterSolve(10000), 0.010, 1e-15);
  EXPECT_DOUBLE_EQ(budget.expectedAfterSolve(1000), 0.0);
  EXPECT_DOUBLE_EQ(budget.solveSeconds(0.0, 1000), 0.020);
  budget.record(0.0, 0.005, 0.006, 1000);
  EXPECT_NEAR(budget.expectedAfterSolve(1000), 0.001, 1e-15);
  EXPECT_DOUBLE_EQ(budget.expectedAfterSolve(10000), 0.0);
}

TEST(AnswerBudget, ALateSolveStillGetsTheMinimum)
{
  AnswerBudget budget(0.020, 0.001);
  budget.record(0.0, 0.010, 0.025, 10000);  // 15 ms after the solve
  EXPECT_DOUBLE_EQ(budget.solveSeconds(0.010, 10000), 0.001);
  EXPECT_DOUBLE_EQ(budget.solveSeconds(1.0, 10000), 0.001);
}

TEST(AnswerBudget, MeaninglessFiguresChangeNothing)
{
  AnswerBudget budget(0.020, 0.001);
  budget.record(0.0, 0.010, 0.014, 100);
  budget.record(0.0, std::nan(""), 0.050, 100);
  EXPECT_NEAR(budget.expectedAfterSolve(100), 0.004, 1e-15);
  // A solve reported longer than the answer leaves nothing after it, not a negative time.
  budget.record(0.0, 0.030, 0.020, 100);
  EXPECT_NEAR(budget.expectedAfterSolve(100), 0.003, 1e-15);
  budget.setAnswerSeconds(0.050);
  EXPECT_DOUBLE_EQ(budget.answerSeconds(), 0.050);
  EXPECT_NEAR(budget.solveSeconds(0.0, 100), 0.047, 1e-15);
}
