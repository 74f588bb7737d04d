// Numbers as calibrate_projector prints and writes them.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

namespace rviz_projector
{
/// `value` with `decimals` decimals; never "-0.000" (a value that rounds to zero prints as 0).
inline std::string fixedDecimals(double value, int decimals)
{
  if (std::abs(value) < 0.5 * std::pow(10.0, -decimals))
  {
    value = 0.0;
  }
  std::ostringstream text;
  text.setf(std::ios::fixed);
  text.precision(decimals);
  text << value;
  return text.str();
}
}  // namespace rviz_projector
