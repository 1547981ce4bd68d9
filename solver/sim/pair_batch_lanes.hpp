#pragma once
// The batch kernels (sim/pair_batch.hpp) for a lane type `O` (contact/lanes.hpp) and a rolling
// model RM: O::lanes contacts are gathered into lanes, the contact law (contact/contact_law.hpp)
// computed for all of them at once, and the results added to the bodies one contact at a time in
// batch order. Included only by pair_batch_scalar.cpp, pair_batch_avx2.cpp and
// pair_batch_avx512.cpp, each with its own `O` in an anonymous namespace.
//
// Sphere-sphere, per pair, from the packed views (sim/contact_view.hpp): the normal
// n = (x_j - x_i) / |x_j - x_i|, the overlap d = r_i + r_j - |x_j - x_i|, the contact point
// c = x_i + (r_i - d/2) n, the lever arms from each body's centre of mass, the relative velocity
// of the contact points at the half step and as the dashpots see it, R* = r_i r_j / (r_i + r_j),
// m* = 1 / (1/m_i + 1/m_j). Sphere-wall: the same from the record the wall pass filled (the
// shape's nearest point; R* = r, m* = m, the wall's velocity at the contact point subtracted).
#include <algorithm>
#include <cstdint>
#include <cstring>

#include "solver/contact/contact_law.hpp"
#include "solver/sim/pair_batch.hpp"

namespace seedcal::lanes {

template <class O>
[[gnu::always_inline]] inline V3<typename O::T> load3(const double* const* p, int offset) {
  return {O::gather(p, offset), O::gather(p, offset + 1), O::gather(p, offset + 2)};
}

// The three components of v into rows[0], rows[1], rows[2] (one double per lane each).
template <class O, int W>
[[gnu::always_inline]] inline void store_rows3(double (*rows)[W], const V3<typename O::T>& v) {
  O::store(rows[0], v.x);
  O::store(rows[1], v.y);
  O::store(rows[2], v.z);
}

// Listed pairs ahead of the batch whose body records and accumulators are prefetched.
inline constexpr std::size_t kPrefetchAhead = 8;

// Prefetches the body records (two lines) and accumulators of the touching pairs [from, to). The
// near body follows the list order and stays in cache; the far body's lines are scattered over a
// bed larger than the core's cache, and without the prefetch the accumulator's load at the end of
// a batch waited for memory (a seventh of the kernel's samples on the settled bed). The spheres'
// records are in cache: the listing pass (list_touching_pairs) just read them.
[[gnu::always_inline]] inline void prefetch_batch_bodies(const PairBatchArgs& a,
                                                         const std::uint32_t* pairs,
                                                         std::size_t from, std::size_t to) {
  namespace L = view_layout;
  for (std::size_t idx = from; idx < to; ++idx) {
    const std::uint32_t k = pairs[idx];
    for (const std::uint32_t s : {a.si[k], a.sj[k]}) {
      const std::uint32_t b = a.sphere_body[s];
      const double* q = a.bodies + static_cast<std::size_t>(b) * L::kBodyStride;
      __builtin_prefetch(q, 0, 3);
      __builtin_prefetch(q + 8, 0, 3);
      __builtin_prefetch(a.accumulators + static_cast<std::size_t>(b) * L::kAccStride, 1, 3);
    }
  }
}

// The body records hold v, w, v_end, w_end back to back (12 doubles): with `End` all four, into
// v, w, ve, we; without, v and w only (ve, we are then left unset and must not be read).
template <class O, bool End>
[[gnu::always_inline]] inline void load_velocities(const double* const* q, V3<typename O::T>& v,
                                                   V3<typename O::T>& w, V3<typename O::T>& ve,
                                                   V3<typename O::T>& we) {
  namespace L = view_layout;
  static_assert(L::kBodyOmega == L::kBodyVelocity + 3 &&
                L::kBodyVelocityEnd == L::kBodyVelocity + 6 &&
                L::kBodyOmegaEnd == L::kBodyVelocity + 9);
  O::load4(q, L::kBodyVelocity, v.x, v.y, v.z, w.x);
  if constexpr (End) {
    O::load4(q, L::kBodyVelocity + 4, w.y, w.z, ve.x, ve.y);
    O::load4(q, L::kBodyVelocity + 8, ve.z, we.x, we.y, we.z);
  } else {
    w.y = O::gather(q, L::kBodyVelocity + 4);
    w.z = O::gather(q, L::kBodyVelocity + 5);
  }
}

// End: the dashpots' velocities differ from the half-step ones (PairBatchArgs::end_velocities).
template <class O, RollingModel RM, bool End>
void pair_batch_lanes(const PairBatchArgs& a, const std::uint32_t* pairs, const double* scale,
                      std::size_t n, PairBatchStats& stats) {
  using T = typename O::T;
  namespace L = view_layout;
  constexpr int W = O::lanes;
  constexpr bool epsd = RM == RollingModel::epsd;
  const ContactSettings settings{a.dt_s, a.clip_attractive, a.epsd_damping_ratio};
  // Largest overlap and normal force over the batch, lane by lane (an unused lane repeats a pair,
  // which does not change a maximum); folded into `stats` at the end.
  T max_overlap = O::splat(stats.max_overlap_m), max_fn = O::splat(stats.max_fn_n);
  // Broadcast instead of gathered lane by lane: the damping scale when there is none (Hertz-Mindlin:
  // 1 for every pair) and the material pair's constants when every sphere is of one material (a
  // bed of one seed, whatever the walls are made of). The same values, so the same bits.
  const bool unit_scale = scale == nullptr;
  const bool one_material = a.uniform_constants != nullptr;
  for (std::size_t base = 0; base < n; base += W) {
    prefetch_batch_bodies(a, pairs, std::min(n, base + kPrefetchAhead),
                          std::min(n, base + kPrefetchAhead + W));
    const int used = n - base < static_cast<std::size_t>(W) ? static_cast<int>(n - base) : W;
    // Unused lanes repeat the last pair; their results are dropped.
    std::uint32_t k[W], bi[W], bj[W];
    const double *pi[W], *pj[W], *qi[W], *qj[W], *hist[W], *pc[W], *sc[W];
    // EPSD: the rolling spring, and each body's principal inertia and mass.
    [[maybe_unused]] const double *roll[W], *ii[W], *ij[W], *mi[W], *mj[W];
    for (int l = 0; l < W; ++l) {
      const std::size_t idx = base + static_cast<std::size_t>(l < used ? l : used - 1);
      k[l] = pairs[idx];
      if (!unit_scale) sc[l] = scale + idx;
      const std::uint32_t s_i = a.si[k[l]], s_j = a.sj[k[l]];
      pi[l] = a.spheres + static_cast<std::size_t>(s_i) * L::kSphereStride;
      pj[l] = a.spheres + static_cast<std::size_t>(s_j) * L::kSphereStride;
      bi[l] = a.sphere_body[s_i];
      bj[l] = a.sphere_body[s_j];
      qi[l] = a.bodies + static_cast<std::size_t>(bi[l]) * L::kBodyStride;
      qj[l] = a.bodies + static_cast<std::size_t>(bj[l]) * L::kBodyStride;
      hist[l] = a.tangential_m + 3 * static_cast<std::size_t>(k[l]);
      if (!one_material) {
        const std::uint16_t mat_i = a.sphere_material[s_i], mat_j = a.sphere_material[s_j];
        pc[l] = &a.pair_constants[static_cast<std::size_t>(mat_i) * a.materials + mat_j].e_star_pa;
      }
      if constexpr (epsd) {
        roll[l] = a.rolling_m + 3 * static_cast<std::size_t>(k[l]);
        ii[l] = a.body_inertia_kg_m2 + 3 * static_cast<std::size_t>(bi[l]);
        ij[l] = a.body_inertia_kg_m2 + 3 * static_cast<std::size_t>(bj[l]);
        mi[l] = a.body_mass_kg + bi[l];
        mj[l] = a.body_mass_kg + bj[l];
      }
    }
    static_assert(offsetof(BatchPairConstants, e_star_pa) == 0);
    // Four consecutive fields of each lane's record at once (a transpose where lanes are vectors).
    V3<T> xi, xj, ci, cj;
    T ri, rj, inv_mi, inv_mj;
    O::load4(pi, L::kSpherePosition, xi.x, xi.y, xi.z, ri);
    O::load4(pj, L::kSpherePosition, xj.x, xj.y, xj.z, rj);
    static_assert(L::kSphereRadius == L::kSpherePosition + 3);
    // The body's inverse mass and centre of mass, side by side in its record.
    O::load4(qi, L::kBodyInvMass, inv_mi, ci.x, ci.y, ci.z);
    O::load4(qj, L::kBodyInvMass, inv_mj, cj.x, cj.y, cj.z);
    static_assert(L::kBodyPosition == L::kBodyInvMass + 1);
    const V3<T> d = xj - xi;
    const T rs = ri + rj;
    const T dist = O::sqrt(dot(d, d));
    const T zero = O::splat(0.0);
    const V3<T> normal = select(dist > zero, (1.0 / dist) * d, V3<T>{zero, zero, O::splat(1.0)});
    const T overlap = rs - dist;
    const T arm_i = ri - 0.5 * overlap;  // sphere centre to contact point
    const T arm_j = rj - 0.5 * overlap;
    const V3<T> cp = xi + arm_i * normal;
    const V3<T> rci = cp - ci, rcj = cp - cj;

    V3<T> vi, wi, vei, wei, vj, wj, vej, wej;
    load_velocities<O, End>(qi, vi, wi, vei, wei);
    load_velocities<O, End>(qj, vj, wj, vej, wej);

    T e_star, beta, mu_s, mu_r, tangential_ratio;
    if (one_material) {
      const BatchPairConstants& c = *a.uniform_constants;
      e_star = O::splat(c.e_star_pa);
      beta = O::splat(c.beta);
      mu_s = O::splat(c.static_friction);
      mu_r = O::splat(c.rolling_friction);
      tangential_ratio = O::splat(c.sqrt_tangential_ratio);
    } else {
      O::load4(pc, 0, e_star, beta, mu_s, mu_r);
      tangential_ratio = O::gather(pc, 4);
    }
    const ContactLaw<T> law{e_star, beta, mu_s, mu_r, tangential_ratio};
    const V3<T> v_rel = (vi + cross(wi, rci)) - (vj + cross(wj, rcj));
    V3<T> v_rel_end = v_rel;
    if constexpr (End) v_rel_end = (vei + cross(wei, rci)) - (vej + cross(wej, rcj));
    const ContactKinematics<T> kin{normal,
                                   overlap,
                                   ri * rj / rs,
                                   1.0 / (inv_mi + inv_mj),
                                   v_rel,
                                   v_rel_end,
                                   unit_scale ? O::splat(1.0) : O::gather(sc, 0)};
    ContactRotation<T, 2> rot;
    rot.arm_i_m = rci;
    rot.arm_j_m = rcj;
    V3<T> t = load3<O>(hist, 0);
    V3<T> m_k{zero, zero, zero};
    if constexpr (RM == RollingModel::cdt) {
      rot.cdt_lever_i_m = a.cdt_lever_from_centre_of_mass ? O::sqrt(dot(rci, rci)) : arm_i;
      rot.cdt_lever_j_m = a.cdt_lever_from_centre_of_mass ? O::sqrt(dot(rcj, rcj)) : arm_j;
    } else if constexpr (epsd) {
      rot.relative_spin = wi - wj;
      rot.relative_spin_end = rot.relative_spin;
      if constexpr (End) rot.relative_spin_end = wei - wej;
      // Each body's inertia about the contact point: the mean principal moment plus m |r|^2.
      const T inertia_i = (O::gather(ii, 0) + O::gather(ii, 1) + O::gather(ii, 2)) / 3.0 +
                          O::gather(mi, 0) * dot(rci, rci);
      const T inertia_j = (O::gather(ij, 0) + O::gather(ij, 1) + O::gather(ij, 2)) / 3.0 +
                          O::gather(mj, 0) * dot(rcj, rcj);
      rot.rolling_inertia_kg_m2 = inertia_i * inertia_j / (inertia_i + inertia_j);
      m_k = load3<O>(roll, 0);
    }
    const ContactResult<T, 2> f = contact_law<O, RM, 2>(law, kin, rot, t, m_k, settings);

    // Back to one pair at a time, in batch order: per lane, the eight doubles to add to body i's
    // accumulator (force, torque, rolling capacity, pad) and the eight to subtract from j's.
    alignas(64) double add_i[W][8], sub_j[W][8];
    O::store_lanes8(add_i, f.force_on_i_n.x, f.force_on_i_n.y, f.force_on_i_n.z,
                    f.torque_i_n_m.x, f.torque_i_n_m.y, f.torque_i_n_m.z,
                    f.roll_capacity_i_n_m, zero);
    O::store_lanes8(sub_j, f.force_on_i_n.x, f.force_on_i_n.y, f.force_on_i_n.z,
                    f.torque_j_n_m.x, f.torque_j_n_m.y, f.torque_j_n_m.z,
                    -f.roll_capacity_j_n_m, zero);
    static_assert(L::kAccForce == 0 && L::kAccTorque == 3 && L::kAccRollCapacity == 6 &&
                  L::kAccStride == 8);
    // The springs (tangential, then EPSD's rolling spring and torque), one row per component.
    // Stored value by value: taking the results' addresses would keep them out of registers.
    alignas(64) double out[epsd ? 9 : 3][W];
    store_rows3<O, W>(out, t);
    if constexpr (epsd) {
      store_rows3<O, W>(out + 3, m_k);
      store_rows3<O, W>(out + 6, f.rolling_torque_n_m);
    }
    for (int l = 0; l < used; ++l) {
      double* acc_i = a.accumulators + static_cast<std::size_t>(bi[l]) * L::kAccStride;
      double* acc_j = a.accumulators + static_cast<std::size_t>(bj[l]) * L::kAccStride;
      O::add8(acc_i, add_i[l]);
      O::sub8(acc_j, sub_j[l]);
      a.touched[bi[l]] = 1;
      a.touched[bj[l]] = 1;
      double* spring = a.tangential_m + 3 * static_cast<std::size_t>(k[l]);
      for (int c = 0; c < 3; ++c) spring[c] = out[c][l];
      if constexpr (epsd) {
        double* rolling = a.rolling_m + 3 * static_cast<std::size_t>(k[l]);
        for (int c = 0; c < 3; ++c) {
          rolling[c] = out[3 + c][l];
          acc_i[L::kAccTorque + c] += out[6 + c][l];
          acc_j[L::kAccTorque + c] -= out[6 + c][l];
        }
      }
    }
    // ThreadStats::note (sim/contact_forces.hpp): the maxima in lanes, a deep overlap (rare) one
    // pair at a time.
    max_overlap = overlap > max_overlap ? overlap : max_overlap;
    max_fn = f.normal_force_n > max_fn ? f.normal_force_n : max_fn;
    const T r_min = ri <= rj ? ri : rj;
    if (O::any(overlap > stats.prefilter * r_min)) {
      alignas(64) double ov[W], r_i[W], r_j[W];
      O::store(ov, overlap);
      O::store(r_i, ri);
      O::store(r_j, rj);
      for (int l = 0; l < used; ++l) {
        const double rm = r_i[l] <= r_j[l] ? r_i[l] : r_j[l];
        if (!(ov[l] > stats.prefilter * rm)) continue;
        const double li = a.overlap_limit_m[a.si[k[l]]], lj = a.overlap_limit_m[a.sj[k[l]]];
        stats.deep.note(ov[l], rm, li <= lj ? li : lj, li <= lj ? bi[l] : bj[l]);
      }
    }
  }
  alignas(64) double lane_overlap[W], lane_fn[W];
  O::store(lane_overlap, max_overlap);
  O::store(lane_fn, max_fn);
  for (int l = 0; l < W; ++l) {
    if (lane_overlap[l] > stats.max_overlap_m) stats.max_overlap_m = lane_overlap[l];
    if (lane_fn[l] > stats.max_fn_n) stats.max_fn_n = lane_fn[l];
  }
}

// The wall batch kernel (sim/pair_batch.hpp): the same contact law, with the wall as the second
// body.
template <class O, RollingModel RM, bool End>
void wall_batch_lanes(const WallBatchArgs& a, const WallBatch& b) {
  using T = typename O::T;
  namespace L = view_layout;
  constexpr int W = O::lanes;
  constexpr bool epsd = RM == RollingModel::epsd;
  const ContactSettings settings{a.dt_s, a.clip_attractive, a.epsd_damping_ratio};
  const WallContactIn* in = b.in;
  const std::size_t n = b.n;
  static_assert(sizeof(WallContactIn) == 16 * sizeof(double));
  for (std::size_t base = 0; base < n; base += W) {
    const int used = n - base < static_cast<std::size_t>(W) ? static_cast<int>(n - base) : W;
    // Unused lanes repeat the last contact; their results are dropped.
    const double *rec[W], *q[W], *pc[W], *hist[W], *sc[W];
    [[maybe_unused]] const double *roll[W], *spin[W];  // EPSD
    for (int l = 0; l < W; ++l) {
      const std::size_t idx = base + static_cast<std::size_t>(l < used ? l : used - 1);
      const WallContactIn& c = in[idx];
      rec[l] = c.normal;
      q[l] = a.bodies + static_cast<std::size_t>(c.body) * L::kBodyStride;
      pc[l] = &a.pair_constants[c.constants].e_star_pa;
      hist[l] = a.tangential_m + 3 * c.pair;
      sc[l] = b.scale + idx;
      if constexpr (epsd) {
        roll[l] = a.rolling_m + 3 * c.pair;
        spin[l] = b.rolling[idx].wall_spin_rad_s;
      }
    }
    static_assert(offsetof(WallContactIn, overlap_m) == 3 * sizeof(double) &&
                  offsetof(WallContactIn, lever_m) == 4 * sizeof(double) &&
                  offsetof(WallContactIn, radius_m) == 7 * sizeof(double) &&
                  offsetof(WallContactIn, wall_velocity_m_s) == 8 * sizeof(double) &&
                  offsetof(WallContactIn, mass_kg) == 11 * sizeof(double) &&
                  offsetof(WallContactIn, rolling_lever_m) == 12 * sizeof(double));
    static_assert(offsetof(WallRollingIn, rolling_inertia_kg_m2) == 3 * sizeof(double));
    V3<T> n_, rc, vw;
    T overlap, radius, mass;
    O::load4(rec, 0, n_.x, n_.y, n_.z, overlap);
    O::load4(rec, 4, rc.x, rc.y, rc.z, radius);
    O::load4(rec, 8, vw.x, vw.y, vw.z, mass);
    V3<T> v, w, ve, we;
    load_velocities<O, End>(q, v, w, ve, we);
    T e_star, beta, mu_s, mu_r;
    O::load4(pc, 0, e_star, beta, mu_s, mu_r);
    const ContactLaw<T> law{e_star, beta, mu_s, mu_r, O::gather(pc, 4)};
    const V3<T> v_rel = (v + cross(w, rc)) - vw;
    V3<T> v_rel_end = v_rel;
    if constexpr (End) v_rel_end = (ve + cross(we, rc)) - vw;
    const ContactKinematics<T> kin{n_, overlap, radius, mass, v_rel, v_rel_end, O::gather(sc, 0)};
    const T zero = O::splat(0.0);
    ContactRotation<T, 1> rot;
    rot.arm_i_m = rc;
    V3<T> t = load3<O>(hist, 0);
    V3<T> m_k{zero, zero, zero};
    if constexpr (RM == RollingModel::cdt) {
      rot.cdt_lever_i_m = O::gather(rec, 12);
    } else if constexpr (epsd) {
      V3<T> ws;
      T inertia;
      O::load4(spin, 0, ws.x, ws.y, ws.z, inertia);
      rot.relative_spin = w - ws;
      rot.relative_spin_end = rot.relative_spin;
      if constexpr (End) rot.relative_spin_end = we - ws;
      rot.rolling_inertia_kg_m2 = inertia;
      m_k = load3<O>(roll, 0);
    }
    const ContactResult<T, 1> f = contact_law<O, RM, 1>(law, kin, rot, t, m_k, settings);
    // Stored value by value: taking the results' addresses would keep them out of registers.
    alignas(64) double row[epsd ? 18 : 12][W];
    store_rows3<O, W>(row, t);
    store_rows3<O, W>(row + 3, f.force_on_i_n);
    store_rows3<O, W>(row + 6, f.torque_i_n_m);
    O::store(row[9], f.roll_capacity_i_n_m);
    O::store(row[10], f.normal_force_n);
    O::store(row[11], f.normal_stiffness_n_m);
    if constexpr (epsd) {
      store_rows3<O, W>(row + 12, m_k);
      store_rows3<O, W>(row + 15, f.rolling_torque_n_m);
    }
    for (int l = 0; l < used; ++l) {
      const std::size_t i = base + static_cast<std::size_t>(l);
      double* spring = a.tangential_m + 3 * in[i].pair;
      WallContactOut& o = b.out[i];
      for (int c = 0; c < 3; ++c) {
        spring[c] = row[c][l];
        o.force_on_sphere_n[c] = row[3 + c][l];
        o.torque_n_m[c] = row[6 + c][l];
      }
      o.roll_capacity_n_m = row[9][l];
      o.normal_force_n = row[10][l];
      o.normal_stiffness_n_m = row[11][l];
      if constexpr (epsd) {
        double* rolling = a.rolling_m + 3 * in[i].pair;
        for (int c = 0; c < 3; ++c) {
          rolling[c] = row[12 + c][l];
          o.rolling_torque_n_m[c] = row[15 + c][l];
        }
      }
    }
  }
}

// The kernels of a lane type, the rolling model and whether the end velocities are read chosen
// once per batch.
template <class O, bool End>
void pair_batch_end(const PairBatchArgs& a, const std::uint32_t* pairs, const double* scale,
                    std::size_t n, PairBatchStats& stats) {
  switch (a.rolling) {
    case RollingModel::none: pair_batch_lanes<O, RollingModel::none, End>(a, pairs, scale, n, stats); break;
    case RollingModel::cdt: pair_batch_lanes<O, RollingModel::cdt, End>(a, pairs, scale, n, stats); break;
    case RollingModel::epsd: pair_batch_lanes<O, RollingModel::epsd, End>(a, pairs, scale, n, stats); break;
  }
}

template <class O>
void pair_batch(const PairBatchArgs& a, const std::uint32_t* pairs, const double* scale,
                std::size_t n, PairBatchStats& stats) {
  if (a.end_velocities) pair_batch_end<O, true>(a, pairs, scale, n, stats);
  else pair_batch_end<O, false>(a, pairs, scale, n, stats);
}

template <class O, bool End>
void wall_batch_end(const WallBatchArgs& a, const WallBatch& b) {
  switch (a.rolling) {
    case RollingModel::none: wall_batch_lanes<O, RollingModel::none, End>(a, b); break;
    case RollingModel::cdt: wall_batch_lanes<O, RollingModel::cdt, End>(a, b); break;
    case RollingModel::epsd: wall_batch_lanes<O, RollingModel::epsd, End>(a, b); break;
  }
}

template <class O>
void wall_batch(const WallBatchArgs& a, const WallBatch& b) {
  if (a.end_velocities) wall_batch_end<O, true>(a, b);
  else wall_batch_end<O, false>(a, b);
}

}  // namespace seedcal::lanes
