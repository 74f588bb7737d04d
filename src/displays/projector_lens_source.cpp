#include "rviz_projector/displays/projector_lens_source.h"

#include <cmath>
#include <utility>

#include "rviz_projector/core/lens_view.h"
#include "rviz_projector/ros/ros_conversions.h"

namespace rviz_projector
{
ProjectorLensSource::ProjectorLensSource()
{
  queue_.attach(nh_);
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
  messages_ = 0;
  calibration_ = LensCalibration();
  frame_id_.clear();
  has_lens_ = false;
  check_ = LensCheck();
  narrow_view_.clear();
}

LensEvent ProjectorLensSource::poll()
{
  event_ = LensEvent();
  queue_.drain();
  return event_;
}

void ProjectorLensSource::callback(const sensor_msgs::CameraInfo::ConstPtr& msg)
{
  ++messages_;
  last_received_ = std::chrono::steady_clock::now();  // the CameraInfo age counts every message
  LensCalibration calibration = toLensCalibration(*msg);
  const bool first = !last_;
  const bool lens_changed = first || !sameLens(calibration, calibration_);
  const bool frame_changed = first || msg->header.frame_id != frame_id_;
  last_ = msg;
  if (!lens_changed && !frame_changed)
  {
    return;  // the same CameraInfo again (a new stamp only): nothing to do
  }
  event_.lens = event_.lens || lens_changed;
  event_.frame = event_.frame || frame_changed;
  frame_id_ = msg->header.frame_id;
  if (!lens_changed)
  {
    return;
  }
  calibration_ = std::move(calibration);
  PinholeModel lens;
  check_ = projectorLens(calibration_, lens, distortion_);
  has_lens_ = check_.ok();
  narrow_view_.clear();
  if (has_lens_)
  {
    lens_ = lens;
    narrow_view_ = narrowViewWarning(lens_);
  }
}

LensCheck projectorLens(const LensCalibration& calibration, PinholeModel& lens, LensDistortion& distortion)
{
  const LensCheck check = PinholeModel::fromCalibration(calibration, lens);
  distortion = LensDistortion();
  if (check.ok() && LensDistortion::fromCalibration(calibration, distortion).ok() && !distortion.none())
  {
    // Drawn through the distortion: the projector's pixels are K's (P is the rectified camera,
    // which a projector does not have). fromCalibration checked K with the fold check.
    PinholeModel raw_lens;
    if (PinholeModel::rawFromCalibration(calibration, raw_lens).ok())
    {
      lens = raw_lens;
    }
    else
    {
      distortion = LensDistortion();  // K unusable: P's pinhole, D not drawn (the warning says so)
    }
  }
  return check;
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
  if (distortion_.none())
  {
    s.distortion = QString::fromStdString(check_.warning);
  }
  else
  {
    s.distortion_drawn = distortionDrawn();
  }
  s.field_of_view = QString::fromStdString(narrow_view_);
  return s;
}
QString ProjectorLensSource::distortionDrawn() const
{
  if (distortion_.none())
  {
    return QString();
  }
  QString text = QString("%1, D =").arg(modelName(distortion_.model()));
  for (const double d : distortion_.coefficients())
  {
    text += QString(" %1").arg(d);
  }
  return text;
}
}  // namespace rviz_projector
