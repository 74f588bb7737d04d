// readCloudXyz (ros/ros_conversions): a PointCloud2 built byte by byte here (padded rows, an extra
// field, unaligned offsets) and the bad sizes a broken driver sends.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "rviz_projector/ros/ros_conversions.h"

using namespace rviz_projector;

namespace
{
sensor_msgs::PointField field(const std::string& name, std::uint32_t offset,
                              std::uint8_t datatype = sensor_msgs::PointField::FLOAT32)
{
  sensor_msgs::PointField f;
  f.name = name;
  f.offset = offset;
  f.datatype = datatype;
  f.count = 1;
  return f;
}

void put(sensor_msgs::PointCloud2& cloud, std::size_t byte, float value)
{
  std::memcpy(cloud.data.data() + byte, &value, sizeof(float));
}

/// 2 rows x 3 points; point = intensity (4 bytes), then x, y, z at 5, 9, 13 (unaligned), 17-byte
/// points, rows padded to 60 bytes. Point (r, c) = (10r + c, -c, 0.5r).
sensor_msgs::PointCloud2 paddedCloud()
{
  sensor_msgs::PointCloud2 cloud;
  cloud.height = 2;
  cloud.width = 3;
  cloud.point_step = 17;
  cloud.row_step = 60;
  cloud.fields = {field("intensity", 0), field("x", 5), field("y", 9), field("z", 13)};
  cloud.data.assign(cloud.row_step * cloud.height, 0xAB);  // padding bytes are garbage
  for (int r = 0; r < 2; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      const std::size_t base = std::size_t(r) * cloud.row_step + std::size_t(c) * cloud.point_step;
      put(cloud, base, 99.0f);
      put(cloud, base + 5, 10.0f * r + c);
      put(cloud, base + 9, -1.0f * c);
      put(cloud, base + 13, 0.5f * r);
    }
  }
  return cloud;
}
}  // namespace

TEST(CloudXyz, PaddedRowsAndUnalignedFieldsAreReadPointByPoint)
{
  std::vector<Vec3> points{{1, 2, 3}};
  EXPECT_EQ(readCloudXyz(paddedCloud(), points), "");
  ASSERT_EQ(points.size(), 6u);
  for (int r = 0; r < 2; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      const Vec3& p = points[std::size_t(r * 3 + c)];
      EXPECT_EQ(p.x, 10.0 * r + c);
      EXPECT_EQ(p.y, -1.0 * c);
      EXPECT_EQ(p.z, 0.5 * r);
    }
  }
}

TEST(CloudXyz, BrokenCloudsAreRefusedWithAReasonAndNothingRead)
{
  std::vector<Vec3> points;
  sensor_msgs::PointCloud2 cloud = paddedCloud();
  cloud.fields.pop_back();
  EXPECT_EQ(readCloudXyz(cloud, points), "no field 'z'");
  EXPECT_TRUE(points.empty());

  cloud = paddedCloud();
  cloud.fields[1].datatype = sensor_msgs::PointField::FLOAT64;
  EXPECT_EQ(readCloudXyz(cloud, points), "field 'x' is not a single FLOAT32");

  cloud = paddedCloud();
  cloud.fields[3].offset = 14;  // 14 + 4 > 17
  EXPECT_EQ(readCloudXyz(cloud, points), "field 'z' does not fit in point_step");

  cloud = paddedCloud();
  cloud.row_step = 50;  // 3 x 17 = 51
  EXPECT_EQ(readCloudXyz(cloud, points), "width x point_step is larger than row_step");

  cloud = paddedCloud();
  cloud.data.resize(119);
  EXPECT_EQ(readCloudXyz(cloud, points), "data shorter than height x row_step");

  cloud = paddedCloud();
  cloud.is_bigendian = true;
  EXPECT_EQ(readCloudXyz(cloud, points), "big-endian data is not supported");

  // Sizes whose 32-bit products overflow must not pass the checks.
  cloud = paddedCloud();
  const std::uint32_t huge = std::numeric_limits<std::uint32_t>::max();
  cloud.width = huge;
  cloud.row_step = huge;
  EXPECT_EQ(readCloudXyz(cloud, points), "width x point_step is larger than row_step");
  cloud = paddedCloud();
  cloud.height = huge;
  EXPECT_EQ(readCloudXyz(cloud, points), "data shorter than height x row_step");
  EXPECT_TRUE(points.empty());
}
