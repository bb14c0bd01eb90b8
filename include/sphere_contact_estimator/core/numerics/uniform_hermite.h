#pragma once

// STL
#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace sphere_contact_estimator
{
/// Cubic Hermite interpolation of K functions sampled together at n evenly spaced nodes on [0, 1], from
/// values and slopes. Boost's cardinal_cubic_hermite holds one function per object and checks its domain
/// with a division on every call; for a table read on every odometry message the K channels share one
/// index here and the caller guarantees the range (measured: half the time of three Boost objects).
template <int K>
class UniformHermite
{
public:
  UniformHermite() = default;
  /// @param n nodes at u_i = i / (n - 1), n >= 2
  explicit UniformHermite(std::size_t n) : n_(n), inv_du_(static_cast<double>(n - 1)), data_(2 * K * n) {}

  /// Value and slope d/du of channel c at node i.
  void set(std::size_t i, int c, double value, double slope)
  {
    data_[2 * K * i + c] = value;
    data_[2 * K * i + K + c] = slope / inv_du_;  // stored times du
  }

  /// All channels at u in [0, 1].
  std::array<double, K> operator()(double u) const
  {
    const double s = std::clamp(u, 0.0, 1.0) * inv_du_;
    const std::size_t i = std::min(static_cast<std::size_t>(s), n_ - 2);
    const double t = s - static_cast<double>(i), r = 1.0 - t;
    const double h00 = r * r * (1.0 + 2.0 * t), h10 = r * r * t, h01 = t * t * (3.0 - 2.0 * t), h11 = -t * t * r;
    const double* a = &data_[2 * K * i];
    const double* b = a + 2 * K;
    std::array<double, K> out;
    for (int c = 0; c < K; ++c)
      out[c] = h00 * a[c] + h10 * a[K + c] + h01 * b[c] + h11 * b[K + c];
    return out;
  }

  bool empty() const { return data_.empty(); }

private:
  std::size_t n_ = 0;
  double inv_du_ = 0.0;
  std::vector<double> data_;  // per node: K values, then K slopes times du
};

}  // namespace sphere_contact_estimator
