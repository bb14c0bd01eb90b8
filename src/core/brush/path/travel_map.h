#pragma once

// STL
#include <cmath>

namespace sphere_contact_estimator::path
{
// The pressure law's map from its variable s to travel tau, in which 1/f is bounded: f ~ t (simple zeros at both
// ends of the path): tau = L / (1 + e^-s) on the real line; f ~ sqrt t: tau = L sin^2(s/2) on [0, pi]; f constant:
// tau = s. Gives tau, L - tau (without cancellation), dtau/ds and its derivative.
class TravelMap
{
public:
  TravelMap(int m, double L) : m_(m), L_(L) {}

  void at(double s, double& tau, double& rest, double& g, double& g_s) const
  {
    if (m_ == 2)
    {
      const double e = std::exp(-std::abs(s));  // tau = L / (1 + e^-s), rest = L / (1 + e^s)
      const double small = L_ * e / (1.0 + e), large = L_ / (1.0 + e);
      tau = s >= 0.0 ? large : small;
      rest = s >= 0.0 ? small : large;
      g = tau * rest / L_;
      g_s = g * (rest - tau) / L_;
    }
    else if (m_ == 1)
    {
      const double sh = std::sin(0.5 * s), ch = std::cos(0.5 * s);
      tau = L_ * sh * sh;
      rest = L_ * ch * ch;
      g = L_ * sh * ch;
      g_s = 0.5 * (rest - tau);
    }
    else
    {
      tau = s;
      rest = L_ - s;
      g = 1.0;
      g_s = 0.0;
    }
  }
  double of(double tau) const
  {
    if (m_ == 2)
      return std::log(tau / (L_ - tau));
    if (m_ == 1)
      return 2.0 * std::atan2(std::sqrt(tau), std::sqrt(std::max(0.0, L_ - tau)));
    return tau;
  }
  /// s of the trailing edge (infinite for m = 2).
  double end() const { return m_ == 2 ? INFINITY : (m_ == 1 ? M_PI : L_); }
  /// The longest step: the map's own scale, over which f and g change by O(1), so that the steps' Gauss rule and the
  /// error estimates beside it (Simpson's, the quartic through a step's points) see a smooth integrand.
  double longestStep() const { return m_ == 2 ? 1.0 : (m_ == 1 ? 0.3 : 0.15 * L_); }

private:
  int m_;
  double L_;
};

}  // namespace sphere_contact_estimator::path
