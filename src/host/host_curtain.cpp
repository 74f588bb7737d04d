#include "host_curtain.h"

#include <QCoreApplication>
#include <QWidget>

namespace rviz_projector
{
HostCurtain::HostCurtain()
{
  poll_timer_.setInterval(10);
  connect(&poll_timer_, &QTimer::timeout, this, &HostCurtain::poll);
}

HostCurtain::~HostCurtain() = default;

void HostCurtain::cover(const std::vector<QRect>& areas)
{
  uncover();
  for (const QRect& area : areas)
  {
    auto window = std::make_unique<QWidget>(nullptr, Qt::FramelessWindowHint | Qt::WindowStaysOnTopHint |
                                                         Qt::X11BypassWindowManagerHint);
    window->setAttribute(Qt::WA_QuitOnClose, false);
    window->setAttribute(Qt::WA_ShowWithoutActivating, true);
    window->setAutoFillBackground(true);
    QPalette palette = window->palette();
    palette.setColor(QPalette::Window, Qt::black);
    window->setPalette(palette);
    window->setStyleSheet("background-color: black;");
    window->setGeometry(area);
    window->show();
    window->raise();
    windows_.push_back(std::move(window));
  }
  // Painted before the caller tears the old windows down (posted events only of these windows).
  for (auto& window : windows_)
  {
    window->repaint();
  }
}

void HostCurtain::uncoverWhen(std::function<bool()> ready, double timeout_s)
{
  if (windows_.empty())
  {
    return;
  }
  ready_ = std::move(ready);
  timeout_ms_ = timeout_s * 1000.0;
  since_.start();
  poll_timer_.start();
}

void HostCurtain::poll()
{
  if (!ready_ || ready_() || since_.elapsed() >= timeout_ms_)
  {
    uncover();
  }
}

void HostCurtain::uncover()
{
  poll_timer_.stop();
  ready_ = nullptr;
  windows_.clear();
}
}  // namespace rviz_projector
