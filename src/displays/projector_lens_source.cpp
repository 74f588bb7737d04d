#include "rviz_projector/displays/projector_lens_source.h"

#include <cmath>

#include "rviz_projector/core/lens_view.h"
#include "rviz_projector/ros/ros_conversions.h"

namespace rviz_projector
{
ProjectorLensSource::ProjectorLensSource()
{
  nh_.setCallbackQueue(&queue_);
}

ProjectorLensSource::~ProjectorLensSource()
{
  unsubscribe();
}

std::string ProjectorLensSource::subscribe(const std::string& topic)
{
  try
  {
    sub_ = nh_.subscribe(topic, 1, &ProjectorLensSource::callback, this);
  }
  catch (const ros::Exception& e)
  {
    return e.what();
  }
  return std::string();
}

void ProjectorLensSource::unsubscribe()
{
  sub_.shutdown();
}

void ProjectorLensSource::forget()
{
  last_.reset();
  frame_id_.clear();
  has_lens_ = false;
  check_ = LensCheck();
  narrow_view_.clear();
}

bool ProjectorLensSource::poll()
{
  received_ = false;
  queue_.callAvailable();
  return received_;
}

void ProjectorLensSource::callback(const sensor_msgs::CameraInfo::ConstPtr& msg)
{
  received_ = true;
  last_ = msg;
  last_received_ = std::chrono::steady_clock::now();
  frame_id_ = msg->header.frame_id;
  PinholeModel lens;
  check_ = PinholeModel::fromCalibration(toLensCalibration(*msg), lens);
  has_lens_ = check_.ok();
  narrow_view_.clear();
  if (has_lens_)
  {
    lens_ = lens;
    narrow_view_ = narrowViewWarning(lens_);
  }
}

double ProjectorLensSource::secondsSinceInfo() const
{
  if (!last_)
  {
    return std::nan("");
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - last_received_).count();
}

LensStatuses ProjectorLensSource::statuses(const QString& topic) const
{
  LensStatuses s;
  if (!last_)
  {
    s.camera_info = QString("No CameraInfo received on %1").arg(topic);
    return s;
  }
  if (!has_lens_)
  {
    s.camera_info_level = LensStatuses::Error;
    s.camera_info = QString("Unusable CameraInfo: %1; the projector shows background only")
                        .arg(QString::fromStdString(check_.error));
    return s;
  }
  s.camera_info_level = LensStatuses::Ok;
  s.camera_info = QString("%1x%2, fx %3, fy %4, cx %5, cy %6")
                      .arg(lens_.width())
                      .arg(lens_.height())
                      .arg(lens_.fx())
                      .arg(lens_.fy())
                      .arg(lens_.cx())
                      .arg(lens_.cy());
  s.distortion = QString::fromStdString(check_.warning);
  s.field_of_view = QString::fromStdString(narrow_view_);
  return s;
}
}  // namespace rviz_projector
