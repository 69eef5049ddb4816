// The registration stage's order: candidates skipped for the frame budget go
// first in the next frame, so every brick of a static scene gets registered.

#include <set>

#include <gtest/gtest.h>

#include "brick_pose/pose/registration_order.h"

namespace brick_pose
{
namespace
{
BrickCandidate candidateAt(const std::string& type, double x_m)
{
  BrickCandidate candidate;
  candidate.type_name = type;
  candidate.centroid_m = Eigen::Vector3d(x_m, 0.0, 1.0);
  return candidate;
}
}  // namespace

TEST(RegistrationOrder, EveryBrickOfAStaticSceneIsRegisteredWithinAFewFrames)
{
  std::vector<BrickCandidate> candidates;
  for (int i = 0; i < 9; ++i) candidates.push_back(candidateAt(i % 2 ? "red" : "green", 0.3 * i));
  RegistrationOrder order;
  std::set<std::size_t> registered;
  // The budget covers 3 candidates a frame; the front end always lists them in the same order.
  for (int frame = 0; frame < 3; ++frame)
  {
    const std::vector<std::size_t> indices = order.order(candidates);
    ASSERT_EQ(indices.size(), candidates.size());
    for (std::size_t rank = 0; rank < 3; ++rank)
    {
      order.attempted(candidates[indices[rank]]);
      registered.insert(indices[rank]);
    }
  }
  EXPECT_EQ(registered.size(), candidates.size()) << "9 bricks, 3 per frame: all within 3 frames";
}

TEST(RegistrationOrder, KeepsTheFrontEndsOrderWhenThereIsNoHistory)
{
  RegistrationOrder order;
  const std::vector<BrickCandidate> candidates = {candidateAt("red", 0.0), candidateAt("red", 1.0)};
  EXPECT_EQ(order.order(candidates), (std::vector<std::size_t>{0, 1}));
}
}  // namespace brick_pose
