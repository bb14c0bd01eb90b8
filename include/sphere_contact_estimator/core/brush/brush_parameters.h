#pragma once

// STL
#include <cstdint>
#include <optional>
#include <string_view>

namespace sphere_contact_estimator
{
/// Vertical pressure distribution q_z over the circular patch; each integrates to F_z.
enum class PressureDistribution
{
  Parabolic,  ///< 2 F_z / (pi a^2) (1 - r^2/a^2), the paper's Sect. 6 choice and the default
  Hertzian,   ///< 3 F_z / (2 pi a^2) sqrt(1 - r^2/a^2)
  Uniform,    ///< F_z / (pi a^2)
};

const char* toString(PressureDistribution pressure);
/// Parses "parabolic", "hertzian" or "uniform".
std::optional<PressureDistribution> parsePressureDistribution(std::string_view name);

/// The direction of a sliding bristle's stress (docs/conventions.md, "Forces"); the numbers are those of the node's
/// sliding_law parameter.
enum class SlidingLaw : std::uint8_t
{
  /// Romano et al. eq. (4b) as written: the stress opposes the bristle tip's full micro-sliding velocity of eq. (1),
  /// which includes the bristle's own motion. A sliding bristle stays on the bound and turns towards the drive no
  /// faster than its tip moves: continuous in the inputs, also at standstill.
  Coulomb = 0,
  /// The approximation of Sect. 6 ("neglecting the contribution of u_t"), used for the paper's Fig. 4: the stress
  /// along the rigid sliding field sigma + A_phi x (in time -V_s - A_omega_z x), discontinuous where that vanishes.
  Rigid = 1,
};

const char* toString(SlidingLaw law);
/// Parses "coulomb" or "rigid".
std::optional<SlidingLaw> parseSlidingLaw(std::string_view name);

/// q_z at the centre over the mean pressure F_z / (pi a^2): 2 (parabolic), 1.5 (Hertzian), 1 (uniform).
double peakFactor(PressureDistribution pressure);

/// Parameters of the brush model of a spherical wheel (Romano et al.), SI units.
struct BrushParameters
{
  double a = 0.05;        ///< contact-patch radius a [m] (or from Hertz: see contactRadiusHertz)
  double k = 1.023e8;     ///< bristle stiffness per unit area k [N/m^3], q_t = k u_t
  double F_z = 3000.0;    ///< vertical load [N]
  double mu = 1.0;        ///< friction coefficient [-]
  PressureDistribution pressure = PressureDistribution::Parabolic;
  /// Sect. 4 kinematics: bristle roots move on circles about the tilting centre (eq. 31) and the
  /// turn coupling chi_psi A_phi u of eq. 32 is kept. Off: Sect. 3, straight paths, chi_psi u
  /// neglected as the paper does there.
  bool tilt = false;
  SlidingLaw sliding_law = SlidingLaw::Coulomb;  ///< direction of a sliding bristle's stress
  int resolution = 32;    ///< transient: lattice spacings across 2a (the steady model follows accuracy_target)
  double standstill_speed = 1.0e-3;  ///< V_r below which the slip form is not used [m/s]
  double accuracy_target = 0.01;     ///< BrushSteady: its error bound; BrushAuto: largest error; of mu F_z
  /// BrushAuto below the noise: when the inputs are uncertain (BrushModel::setInputSpread), its target rises to this
  /// fraction of the forces' standard deviation where that is larger (0: never) [-]
  double auto_noise_fraction = 0.0;

  /// Throws std::invalid_argument naming the first bad value: a, k > 0; F_z, mu >= 0; all finite;
  /// 2 <= resolution <= 1024; standstill_speed > 0; 0 < accuracy_target <= 1; 0 <= auto_noise_fraction <= 1.
  void validate() const;

  /// Pressure q_z [N/m^2] at squared distance r2 [m^2] from the patch centre; 0 outside the patch.
  double qz(double r2) const;
};

bool operator==(const BrushParameters& a, const BrushParameters& b);
inline bool operator!=(const BrushParameters& a, const BrushParameters& b) { return !(a == b); }

/// Hertz contact radius of a sphere of radius R [m] under load F_z [N] on a flat with effective
/// modulus E* [Pa]: a = (3 F_z R / (4 E*))^(1/3).
double contactRadiusHertz(double F_z, double R, double E_star);

}  // namespace sphere_contact_estimator
