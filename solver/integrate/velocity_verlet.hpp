#pragma once
// Velocity Verlet for rigid bodies (Allen & Tildesley, "Computer Simulation of Liquids", 2nd ed.,
// sec. 3.2; for the rotation, the world angular momentum L is kicked like the momentum and the
// free rotation between kicks is integrate/free_rotation.hpp):
//
//   v_{n+1/2} = v_n + dt/2 F_n / m,        L_{n+1/2} = L_n + dt/2 T_n     first half kick
//   x_{n+1}   = x_n + dt v_{n+1/2},        q_{n+1} = free rotation of q_n with L_{n+1/2} over dt
//   F_{n+1}, T_{n+1} from the contacts at x_{n+1}, q_{n+1} (with v_{n+1/2}: contact/contact_law.hpp)
//   v_{n+1}   = v_{n+1/2} + dt/2 F_{n+1} / m,  L_{n+1} = L_{n+1/2} + dt/2 T_{n+1}  second half kick
//
// The Simulation runs one body pass per step (move_bodies over each thread's range of bodies):
// the previous step's second half kick when it is still pending, this step's first half kick,
// the drift and the rotation, fused with placing the spheres and refreshing the contact views,
// so that each body's state is read and written once a step. The second half kick is left pending
// at the end of a step; finish_half_kick applies it when anything reads the bodies between steps.
// The arithmetic is the same either way, so results are the same bits.
#include <cstdint>

#include "solver/core/body_state.hpp"
#include "solver/sim/contact_view.hpp"

namespace seedcal {

// One step of the body pass.
struct VerletPass {
  double dt_s = 0.0;
  bool kick = false;    // apply the previous step's pending second half kick first
  double kick_half_s = 0.0;  // its dt/2
  // Dashpot velocities (contact/contact_law.hpp): 0 for the half-step ones; dt/2 for the
  // predicted v~_{n+1} = v_{n+1/2} + dt/2 F_n / m and L~_{n+1} = L_{n+1/2} + dt/2 T_n (Groot &
  // Warren 1997, eq. 17 with lambda = 1), F_n and T_n the previous step's forces still held by the
  // bodies.
  double predict_s = 0.0;
};

// The body pass over bodies [b_begin, b_end): velocity Verlet's first half (after the pending
// kick), the spheres placed and the contact views written. Sets max_moved_sq to at least the
// largest squared displacement of their spheres since `ref` (the centres at the last neighbour
// build; null: none) and `bad` to at most the lowest body whose new state is not finite.
void move_bodies(BodyState& bodies, SphereState& spheres, BodyView* body_view,
                 SphereView* sphere_view, std::size_t b_begin, std::size_t b_end,
                 const VerletPass& pass, const Vec3* ref, double& max_moved_sq, std::int64_t& bad);

// The second half kick v += h F / m, L += h T (h = dt/2 of the step it belongs to), with the
// angular velocity it implies.
void finish_half_kick(BodyState& bodies, double h, int threads);

// Every sphere at its body's pose.
void place_spheres(const BodyState& bodies, SphereState& spheres, int threads);

}  // namespace seedcal
