#pragma once
// Free rigid-body rotation over one time step, with the world angular momentum L held constant.
//
// Isotropic bodies (spheres): w = L / I is constant, so the exact flow is a rotation by |w| dt
// about w.
//
// Anisotropic bodies (clumps): the symplectic splitting of Dullweber, Leimkuhler & McLachlan
// (1997), J. Chem. Phys. 107, 5840 ("NO_SQUISH"-type rotor splitting). The free-rotor
// Hamiltonian T = sum_k pi_k^2 / (2 I_k) (pi = body-frame angular momentum) is split into its three
// terms; each term's flow is an exact rotation of the body about one principal axis by
// theta = h pi_k / I_k, under which pi rotates the opposite way: pi <- R_k(-theta) pi. The
// symmetric sequence T1(h/2) T2(h/2) T3(h) T2(h/2) T1(h/2) is second order and time-reversible;
// it conserves |L| exactly (each sub-step is a rotation) and keeps the kinetic energy within a
// bounded O(h^2) error with no drift (tests/physics/free_rotation_test.cpp).
#include <cmath>

#include "solver/core/vec.hpp"

namespace seedcal {

// Each sub-rotation is by the angle 2 atan(theta / 2) = theta - theta^3 / 12 + ... instead of
// theta, built without trigonometry from t = theta / 2 (the Cayley transform): the quaternion
// (1, t e) normalised, and for the momentum cos = (1 - t^2) / (1 + t^2), sin = 2t / (1 + t^2). It
// is an exact rotation applied identically to the orientation and the body-frame momentum, so |L|
// and the splitting's structure are kept; the phase error theta^3 / 12 per step is far below the
// splitting error itself for theta = w dt << 1.

// Rotate the body (orientation q: body -> world) about its own principal axis `Axis` by the flow
// of T_Axis for time h; pi is the body-frame angular momentum. q is left unnormalised (scaled by
// sqrt(1 + t^2)); the caller normalises once.
template <int Axis>
inline void rotor_substep(Quat& q, Vec3& pi, const Vec3& inv_inertia, double h) {
  const double t = 0.5 * h * pi[Axis] * inv_inertia[Axis];
  const double d = 1.0 / (1.0 + t * t);
  const double c = (1.0 - t * t) * d, s = 2.0 * t * d;
  constexpr int a = (Axis + 1) % 3, b = (Axis + 2) % 3;
  // pi <- R_Axis(-theta) pi
  const double pa = pi[a], pb = pi[b];
  pi[a] = c * pa + s * pb;
  pi[b] = -s * pa + c * pb;
  // q <- q * (1, t e_Axis), written out: the general quaternion product spends 28 operations on a
  // factor with two zero components, where these 8 give the same values (the terms dropped are
  // exact zeros) and shorten the chain of dependent operations the five sub-steps form.
  const double w = q.w(), x = q.x(), y = q.y(), z = q.z();
  if constexpr (Axis == 0) q = Quat(w - t * x, x + t * w, y + t * z, z - t * y);
  else if constexpr (Axis == 1) q = Quat(w - t * y, x - t * z, y + t * w, z + t * x);
  else q = Quat(w - t * z, x + t * y, y - t * x, z + t * w);
}

// Normalises a quaternion whose norm is close to 1. A step leaves |q|^2 = 1 + e with e of order
// (|w| h)^2 / 4; one Newton step for 1/sqrt(x) at x = 1 + e, y = (3 - x) / 2, leaves |q| off by
// 3/8 e^2 and needs no square root or division (both sit on the critical path of the integrator's
// body loop). It is used for |e| < 1e-5 (|q| within 4e-11 of 1; the error does not accumulate, each
// step corrects the last); a larger e is normalised exactly.
inline void normalize_near_unit(Quat& q) {
  const double n2 = q.coeffs().squaredNorm();
  const double e = n2 - 1.0;
  if (std::abs(e) < 1e-5) q.coeffs() *= 0.5 * (3.0 - n2);
  else q.coeffs() *= 1.0 / std::sqrt(n2);
}

inline void free_rotation_step(Quat& q, const Vec3& L_world, const Vec3& inv_inertia,
                               bool isotropic, double h) {
  if (isotropic) {
    // Rotation about w = L / I by |w| h (as above, via the unnormalised quaternion (1, w h / 2)).
    const Vec3 half = (0.5 * h * inv_inertia.x()) * L_world;
    q = Quat(1.0, half.x(), half.y(), half.z()) * q;
  } else {
    Vec3 pi = q.conjugate() * L_world;  // q is unit on entry (normalised every step)
    rotor_substep<0>(q, pi, inv_inertia, 0.5 * h);
    rotor_substep<1>(q, pi, inv_inertia, 0.5 * h);
    rotor_substep<2>(q, pi, inv_inertia, h);
    rotor_substep<1>(q, pi, inv_inertia, 0.5 * h);
    rotor_substep<0>(q, pi, inv_inertia, 0.5 * h);
  }
  normalize_near_unit(q);
}

}  // namespace seedcal
