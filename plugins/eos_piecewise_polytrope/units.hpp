#pragma once
// Conversion between cgs and the code's units G = c = M_sun = 1. The only place these numbers live.
//   c          = 2.99792458e10 cm/s           exact (SI definition of the metre)
//   G          = 6.67430e-8 cm^3 g^-1 s^-2    CODATA 2018 recommended value (rel. uncertainty 2.2e-5)
//   G M_sun    = 1.3271244e26 cm^3 s^-2       IAU 2015 Resolution B3, nominal solar mass parameter
// Derived: M_sun = (G M_sun)/G = 1.98841e33 g; length unit G M_sun/c^2 = 1.476625 km; time unit
// G M_sun/c^3 = 4.925491 microseconds; density unit M_sun/(G M_sun/c^2)^3 = 6.1758e17 g/cm^3;
// pressure (energy density) unit = density unit * c^2 = 5.5507e38 dyn/cm^2.
// M_sun carries G's uncertainty (2.2e-5); G M_sun and hence the length unit are known to 1e-10.
#include <cmath>

namespace bhnsid::eos_piecewise_polytrope::units {

inline constexpr double c_cgs = 2.99792458e10;          ///< cm / s
inline constexpr double g_cgs = 6.67430e-8;             ///< cm^3 / (g s^2)
inline constexpr double gm_sun_cgs = 1.3271244e26;      ///< cm^3 / s^2
inline constexpr double m_sun_g = gm_sun_cgs / g_cgs;   ///< g
inline constexpr double length_cm = gm_sun_cgs / (c_cgs * c_cgs);                 ///< one code length in cm
inline constexpr double time_s = length_cm / c_cgs;                               ///< one code time in s
inline constexpr double density_g_cm3 = m_sun_g / (length_cm * length_cm * length_cm);  ///< one code density in g/cm^3
inline constexpr double pressure_dyn_cm2 = density_g_cm3 * c_cgs * c_cgs;        ///< one code pressure in dyn/cm^2

inline double density_to_code(double rho_g_cm3) { return rho_g_cm3 / density_g_cm3; }
inline double density_to_cgs(double rho_code) { return rho_code * density_g_cm3; }
inline double pressure_to_code(double p_dyn_cm2) { return p_dyn_cm2 / pressure_dyn_cm2; }
inline double pressure_to_cgs(double p_code) { return p_code * pressure_dyn_cm2; }

}  // namespace bhnsid::eos_piecewise_polytrope::units
