#pragma once

// STL
#include <algorithm>
#include <cstdint>

namespace sphere_contact_estimator::path
{
/// The events along a path that make up its structure (PathIntegrals::signature). Two paths whose sequences of
/// events are equal have no change of structure between them as far as the events tell; the across-path quadrature
/// splits where they differ. Each event carries small counts that tell one structure from another.
enum class PathEvent : std::uint32_t
{
  EntersAdhering = 1,       ///< the bristle adheres at the leading edge
  EntersSliding = 2,        ///< it slides from the leading edge (the bound vanishes there and grows slower than |w|)
  ReAdhesionStretches = 3,  ///< rigid law: how many stretches of G the front half crosses
  ReAdhesion = 4,           ///< a sliding bristle re-adheres (rigid: in the given stretch of G)
  Onset = 5,                ///< an adhering bristle reaches the bound: in which stretch, and how many roots follow
  FoldsBeforeOnset = 6,     ///< interior maxima of |u|^2 - f^2 before the first onset
  LeavesAdhering = 7,       ///< uniform pressure: no onset before the trailing edge (the bound does not vanish there)
  TrailingEdgeOnset = 8,    ///< the bound vanishes at the trailing edge: an onset there, up to rounding
};

/// The running hash of a path's events.
class Signature
{
public:
  explicit Signature(std::uint64_t& value) : value_(value) {}

  void add(PathEvent event, unsigned first = 0, unsigned second = 0)
  {
    const unsigned code = static_cast<unsigned>(event) << 16 | std::min(first, 255u) << 8 | std::min(second, 255u);
    value_ = value_ * 31u + code + 1u;
  }

private:
  std::uint64_t& value_;
};

}  // namespace sphere_contact_estimator::path
