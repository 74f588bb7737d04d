// RigidTransform's composition and inverse against OpenCV's matrix algebra (cv::Rodrigues,
// cv::Matx), and against a hand-computed case.
#include "rviz_projector/core/rigid_transform.h"

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

namespace rviz_projector
{
namespace
{
struct Reference
{
  cv::Matx33d r;
  cv::Vec3d t;
};

Reference reference(const cv::Vec3d& rotation_vector, const cv::Vec3d& t)
{
  cv::Matx33d r;
  cv::Rodrigues(rotation_vector, r);
  return {r, t};
}

RigidTransform fromReference(const Reference& ref)
{
  return RigidTransform::fromMatrix({ref.r(0, 0), ref.r(0, 1), ref.r(0, 2), ref.r(1, 0), ref.r(1, 1), ref.r(1, 2),
                                     ref.r(2, 0), ref.r(2, 1), ref.r(2, 2)},
                                    {ref.t[0], ref.t[1], ref.t[2]});
}

void expectSame(const Reference& expected, const RigidTransform& actual)
{
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      EXPECT_NEAR(expected.r(i, j), actual.rotation()[std::size_t(3 * i + j)], 1e-12) << "R(" << i << "," << j << ")";
    }
  }
  EXPECT_NEAR(expected.t[0], actual.translation().x, 1e-12);
  EXPECT_NEAR(expected.t[1], actual.translation().y, 1e-12);
  EXPECT_NEAR(expected.t[2], actual.translation().z, 1e-12);
}

const Reference a_T_b = reference({0.3, -0.7, 1.1}, {0.5, -1.25, 2.0});
const Reference b_T_c = reference({-1.4, 0.2, 0.6}, {-0.3, 0.8, 0.15});

TEST(RigidTransform, CompositionIsTheMatrixProduct)
{
  const Reference a_T_c{a_T_b.r * b_T_c.r, a_T_b.r * b_T_c.t + a_T_b.t};
  expectSame(a_T_c, fromReference(a_T_b) * fromReference(b_T_c));
}

TEST(RigidTransform, CompositionAppliesTheRightTransformFirst)
{
  // By hand: b_T_c moves x by 1, a_T_b turns 90 degrees about z. The point c = (1, 0, 0) goes to
  // b = (2, 0, 0), then to a = (0, 2, 0).
  const RigidTransform turn = RigidTransform::fromMatrix({0, -1, 0, 1, 0, 0, 0, 0, 1}, {0, 0, 0});
  const RigidTransform shift = RigidTransform::fromMatrix({1, 0, 0, 0, 1, 0, 0, 0, 1}, {1, 0, 0});
  const Vec3 p = (turn * shift).apply({1, 0, 0});
  EXPECT_NEAR(0.0, p.x, 1e-15);
  EXPECT_NEAR(2.0, p.y, 1e-15);
  EXPECT_NEAR(0.0, p.z, 1e-15);
}

TEST(RigidTransform, InverseIsTheMatrixInverse)
{
  const cv::Matx33d r_inverse = a_T_b.r.inv();
  expectSame({r_inverse, -(r_inverse * a_T_b.t)}, fromReference(a_T_b).inverse());
}

TEST(RigidTransform, InverseUndoesTheTransform)
{
  const RigidTransform t = fromReference(b_T_c);
  const Vec3 p{0.7, -2.5, 3.25};
  const Vec3 back = t.inverse().apply(t.apply(p));
  EXPECT_NEAR(p.x, back.x, 1e-12);
  EXPECT_NEAR(p.y, back.y, 1e-12);
  EXPECT_NEAR(p.z, back.z, 1e-12);
}
}  // namespace
}  // namespace rviz_projector
