#pragma once
// Reads doubles (any bit pattern, NaN and inf included) from a fuzzer's bytes; zeros when exhausted.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace sphere_contact_estimator::fuzz
{
class Input
{
public:
  Input(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  double next()
  {
    double x = 0.0;
    if (pos_ + sizeof(double) <= size_)
      std::memcpy(&x, data_ + pos_, sizeof(double));
    pos_ += sizeof(double);
    return x;
  }
  /// A value in [lo, hi] from the next double (NaN and inf map to lo).
  double in(double lo, double hi)
  {
    const double x = next();
    if (!(x == x) || x - x != 0.0)
      return lo;
    const double t = std::fabs(std::fmod(x, 2.0)) / 2.0;  // in [0, 1)
    return lo + (hi - lo) * t;
  }
  bool more() const { return pos_ < size_; }

private:
  const std::uint8_t* data_;
  std::size_t size_, pos_ = 0;
};
}  // namespace sphere_contact_estimator::fuzz
