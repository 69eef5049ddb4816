#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "brick_pose/registration/competitor_settling.h"

namespace brick_pose
{
namespace registration
{
namespace
{
/// A hypothesis at x_m along a long face, with a combined score of `score`
/// (target coverage alone: the other factors are 1 and 0).
Hypothesis at(double x_m, double score)
{
  Hypothesis hypothesis;
  hypothesis.pose.translation() = Eigen::Vector3d(x_m, 0.0, 0.0);
  hypothesis.view.target_coverage = score;
  hypothesis.view.model_coverage = 1.0;
  hypothesis.view.free_space_violation = 0.0;
  return hypothesis;
}

/// Poses within 12 mm are one hypothesis; polishes agree within 6 mm.
/// The polish moves every start within 0.1 m of the origin onto the origin
/// (one basin, score 0.95), and leaves the others where they are.
CompetitorSettling oneBasin(int& polishes)
{
  CompetitorSettling settling;
  settling.polish = [&polishes](const Hypothesis& start) {
    ++polishes;
    return start.pose.translation().norm() < 0.1 ? at(0.0, 0.95) : start;
  };
  settling.same = [](const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    return (a.translation() - b.translation()).norm() <= 0.012;
  };
  settling.agree = [](const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    return (a.translation() - b.translation()).norm() <= 0.006;
  };
  settling.min_confidence = 0.08;
  settling.max_polishes = 3;
  return settling;
}
}  // namespace

// The search and the alternatives found the competitor at 35 mm three times
// (within a few mm); polished once, it settles on the best. The other two
// copies must not spend the rest of the budget: the distinct competitor at
// 60 mm, close in score, is polished and settles on the best too, so no
// competitor is left within the margin.
TEST(CompetitorSettling, ACopyOfAPolishedStartSpendsNoPolish)
{
  int polishes = 0;
  const std::vector<Hypothesis> scored{at(0.002, 0.92), at(0.035, 0.90), at(0.038, 0.90), at(0.032, 0.89),
                                       at(0.060, 0.88)};
  const Comparison comparison = settleCompetitors(scored, oneBasin(polishes));
  EXPECT_EQ(comparison.competitors_polished, 2);
  EXPECT_EQ(polishes, 3);  // the best and two competitors
  EXPECT_DOUBLE_EQ(comparison.best.view.combined(), 0.95);
  EXPECT_DOUBLE_EQ(comparison.second_best, 0.0);
  EXPECT_FALSE(comparison.loosely_settled);
}

// A competitor that settles elsewhere with a close score is another answer.
TEST(CompetitorSettling, ACompetitorSettledElsewhereKeepsTheMarginSmall)
{
  int polishes = 0;
  const std::vector<Hypothesis> scored{at(0.0, 0.92), at(0.3, 0.91)};
  const Comparison comparison = settleCompetitors(scored, oneBasin(polishes));
  EXPECT_DOUBLE_EQ(comparison.best.view.combined(), 0.95);
  EXPECT_DOUBLE_EQ(comparison.second_best, 0.91);
}

// Without a polish every competitor counts with its fitted score.
TEST(CompetitorSettling, WithoutAPolishFittedScoresCount)
{
  int polishes = 0;
  CompetitorSettling settling = oneBasin(polishes);
  settling.polish = nullptr;
  const std::vector<Hypothesis> scored{at(0.0, 0.92), at(0.035, 0.90)};
  const Comparison comparison = settleCompetitors(scored, settling);
  EXPECT_DOUBLE_EQ(comparison.best.view.combined(), 0.92);
  EXPECT_DOUBLE_EQ(comparison.second_best, 0.90);
  EXPECT_EQ(comparison.competitors_polished, 0);
}
// A polish that stays within the hypothesis is kept though its score is a
// little lower (the coverage cannot resolve a centimetre along a long
// face); one that leaves it for a clearly lower score is not.
TEST(CompetitorSettling, APolishWithinTheHypothesisIsKeptDespiteASmallScoreDrop)
{
  int polishes = 0;
  const CompetitorSettling settling = oneBasin(polishes);
  EXPECT_TRUE(polishKept(at(0.0119, 0.846), at(0.001, 0.814), settling.same, 0.03, 0.1));
  EXPECT_FALSE(polishKept(at(0.0, 0.846), at(0.05, 0.80), settling.same, 0.03, 0.1));
  EXPECT_TRUE(polishKept(at(0.0, 0.846), at(0.05, 0.83), settling.same, 0.03, 0.1));
}

// A polish that stays within the hypothesis but loses a quarter of the score
// went astray (a box pose tilted 6.6 deg): the start is kept.
TEST(CompetitorSettling, APolishWithinTheHypothesisThatLosesMuchIsRefused)
{
  int polishes = 0;
  const CompetitorSettling settling = oneBasin(polishes);
  EXPECT_FALSE(polishKept(at(0.0, 0.998), at(0.004, 0.748), settling.same, 0.03, 0.1));
  EXPECT_TRUE(polishKept(at(0.0, 0.998), at(0.004, 0.93), settling.same, 0.03, 0.1));
}
// A competitor's polish from 37 mm that stops 10 mm short of the best has
// not shown a flat basin: once more from there it reaches the best, and the
// view is not called loose. One that stops short again is.
TEST(CompetitorSettling, AStopShortPolishIsContinuedBeforeTheBasinIsCalledFlat)
{
  int polishes = 0;
  CompetitorSettling settling = oneBasin(polishes);
  // Each polish halves the distance to the best (at 0) and scores 0.95.
  settling.polish = [&polishes](const Hypothesis& start) {
    ++polishes;
    return at(0.5 * start.pose.translation().x(), 0.95);
  };
  const Comparison converging = settleCompetitors({at(0.0, 0.92), at(0.020, 0.90)}, settling);
  EXPECT_FALSE(converging.loosely_settled);  // 20 -> 10 -> 5 mm
  EXPECT_DOUBLE_EQ(converging.second_best, 0.0);

  settling.polish = [&polishes](const Hypothesis& start) {
    ++polishes;
    const double x_m = start.pose.translation().x();
    return at(x_m > 0.0 ? std::max(0.009, 0.5 * x_m) : x_m, 0.95);  // a competitor sticks at 9 mm
  };
  const Comparison flat = settleCompetitors({at(0.0, 0.92), at(0.020, 0.90)}, settling);
  EXPECT_TRUE(flat.loosely_settled);
}
}  // namespace registration
}  // namespace brick_pose
