#pragma once
// Time-step estimates for Hertzian contacts.
namespace seedcal {

// Rayleigh time step of a sphere (Li, Xu & Thornton 2005; EDEM Theory Reference Guide):
//   dt_R = pi R sqrt(rho / G) / (0.1631 nu + 0.8766)
double rayleigh_time_step_s(double radius_m, double density_kg_m3, double shear_modulus_pa,
                            double poisson_ratio);

// Hertz impact of two elastic bodies at normal approach speed v (Johnson 1985, "Contact
// Mechanics", sec. 11.4):
//   dn_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5)
//   F_max  = 4/3 E* sqrt(R*) dn_max^(3/2)
//   t_c    = 2.9432 dn_max / v       (2.9432 = 2 int_0^1 dx / sqrt(1 - x^(5/2)))
struct HertzImpact {
  double max_overlap_m;
  double max_force_n;
  double contact_time_s;
};
HertzImpact hertz_impact(double m_star_kg, double r_star_m, double e_star_pa, double speed_m_s);

}  // namespace seedcal
