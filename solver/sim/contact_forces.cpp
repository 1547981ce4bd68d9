// The contact force kernel: one pass over the sphere-sphere groups and one over the sphere-wall
// groups, compiled once per (normal model, rolling model) combination and chosen once per step by
// a switch (no model tests inside the loops).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "solver/contact/hertz_mindlin.hpp"
#include "solver/contact/hmnr.hpp"
#include "solver/contact/rolling_cdt.hpp"
#include "solver/contact/rolling_epsd.hpp"
#include "solver/sim/contact_forces.hpp"
#include "solver/sim/pair_batch.hpp"
#include "solver/sim/simulation.hpp"
#include "solver/sim/work_split.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace seedcal {

namespace {

// The batch kernel's first pass over listed pairs [k_begin, k_end): writes the touching ones to
// `touching` (in list order; returns how many) without a branch (about a third of the listed pairs
// do not touch, in no pattern a predictor could learn), sets each pair's flag in `live` (the
// list's VerletList::live() from k_begin on) to whether it touches, and clears the tangential
// spring (3 doubles per pair in `spring`) of a pair that touched at the last pass and no longer
// does. The far sphere of a pair a few pairs ahead is fetched early.
std::size_t list_touching_pairs(const SphereView* __restrict SV, const std::uint32_t* __restrict SI,
                                const std::uint32_t* __restrict SJ, std::uint32_t k_begin,
                                std::uint32_t k_end, std::uint32_t* __restrict touching,
                                std::uint8_t* __restrict live, double* __restrict spring) {
  std::size_t n = 0;
  for (std::uint32_t k = k_begin; k < k_end; ++k) {
    if (k + 16 < k_end) __builtin_prefetch(&SV[SJ[k + 16]]);
    const SphereView& Si = SV[SI[k]];
    const SphereView& Sj = SV[SJ[k]];
    const double rs = Si.radius_m + Sj.radius_m;
    // The distance exactly as the batch kernel computes it (contact/hertz_mindlin_lanes.hpp), so
    // every listed pair has a non-negative overlap there.
    const lanes::V3<double> d{Sj.position_m.x() - Si.position_m.x(),
                              Sj.position_m.y() - Si.position_m.y(),
                              Sj.position_m.z() - Si.position_m.z()};
    const std::uint8_t touch = lanes::dot(d, d) < rs * rs ? 1 : 0;
    touching[n] = k;
    n += touch;
    // A pair that came apart forgets its spring. Only such a pair's spring is written (a rare,
    // well-predicted branch): the others' springs are zero already or the batch kernel rewrites
    // them, so the list's springs are not streamed through at every step (VerletList::live()).
    if (live[k - k_begin] > touch) {
      double* t = spring + 3 * static_cast<std::size_t>(k);
      t[0] = t[1] = t[2] = 0.0;
    }
    live[k - k_begin] = touch;
  }
  return n;
}

// Whether sphere `sv` touches primitive `primitive` of `wall`; fills `hit` (wall frame) when so.
inline bool touches_wall(const Wall& wall, const SphereView& sv, std::uint32_t primitive,
                         WallHit& hit) {
  return wall.shape->nearest(static_cast<int>(primitive), to_wall_frame(wall.pose, sv.position_m),
                             sv.radius_m, hit) &&
         hit.distance < sv.radius_m;
}

}  // namespace

struct ForceKernel {
  // The serial set-up of a step's pass (contact_forces.hpp).
  static void prepare(Simulation& s, ContactPass& p);
  // One thread's shares of the pass.
  template <NormalModel NM, RollingModel RM>
  static void pass(Simulation& s, ContactPass& p, int t, int team);
};

void ForceKernel::prepare(Simulation& s, ContactPass& p) {
  p.normal = s.options_.contact.normal;
  p.rolling = s.options_.contact.rolling;
  const std::size_t groups = s.pairs_.group_count();
  // Touching pairs per body pair: HMNR's damping scale, and the per-body contact counts when they
  // are tracked; otherwise not counted (a pass over every group of the list).
  p.count_groups = p.normal == NormalModel::hmnr || s.options_.track_body_contacts;
  if (p.count_groups) s.sphere_group_touch_.assign(groups, 0);
  else s.sphere_group_touch_.clear();
  s.wall_group_touch_.assign(s.wall_pairs_.group_count(), 0);
  p.stats.assign(static_cast<std::size_t>(std::max(1, s.options_.threads)), ThreadStats{});
  for (ThreadStats& ts : p.stats) ts.ratio_limit = s.options_.guards.max_overlap_fraction;

  // Hertz-Mindlin or HMNR, with no rolling friction or with CDT: touching sphere pairs go through
  // the batch kernel (sim/pair_batch.hpp), several at a time where the CPU allows; EPSD keeps the
  // pair loop (its rolling spring needs the pair's history and the bodies' inertia).
  if (p.rolling == RollingModel::epsd) return;
  const InteractionTable& table = s.table_;
  const std::size_t nm = table.material_count();
  // The table is fixed for the simulation's life: its constants are packed once.
  if (p.batch_constants.size() != nm * nm) {
    p.batch_constants.resize(nm * nm);
    for (std::size_t i = 0; i < nm; ++i)
      for (std::size_t j = 0; j < nm; ++j) {
        const PairConstants& pc =
            table.pair(static_cast<std::uint16_t>(i), static_cast<std::uint16_t>(j));
        p.batch_constants[i * nm + j] = {pc.e_star_pa, pc.beta, pc.static_friction,
                                         pc.rolling_friction, pc.sqrt_tangential_ratio};
      }
  }
  const bool lever_com = s.options_.contact.cdt_lever_from_centre_of_mass;
  auto& tang = s.pairs_.tangential();
  auto& wtang = s.wall_pairs_.tangential();
  PairBatchArgs& batch = p.batch;
  batch.spheres = reinterpret_cast<const double*>(s.sphere_view_.data());
  batch.sphere_body = s.spheres_.body.data();
  batch.sphere_material = s.spheres_.material.data();
  batch.bodies = reinterpret_cast<const double*>(s.body_view_.data());
  batch.pair_constants = p.batch_constants.data();
  batch.materials = nm;
  batch.si = s.pairs_.si().data();
  batch.sj = s.pairs_.sj().data();
  batch.tangential_m = tang.empty() ? nullptr : tang.data()->data();
  batch.dt_s = s.options_.dt_s;
  batch.clip_attractive = s.options_.contact.clip_attractive;
  batch.cdt = p.rolling == RollingModel::cdt;
  batch.cdt_lever_from_centre_of_mass = lever_com;
  p.batch_fn = choose_pair_batch(s.options_.simd_lanes);
  WallBatchArgs& wall_args = p.wall_args;
  wall_args.bodies = batch.bodies;
  wall_args.pair_constants = batch.pair_constants;
  wall_args.tangential_m = wtang.empty() ? nullptr : wtang.data()->data();
  wall_args.dt_s = batch.dt_s;
  wall_args.clip_attractive = batch.clip_attractive;
  wall_args.cdt = batch.cdt;
  p.wall_fn = choose_wall_batch(s.options_.simd_lanes);
}

template <NormalModel NM, RollingModel RM>
void ForceKernel::pass(Simulation& s, ContactPass& p, int t, int team_size) {
  const double dt = s.options_.dt_s;
  const bool clip = s.options_.contact.clip_attractive;
  const double eta_r = s.options_.contact.epsd_damping_ratio;
  const bool lever_com = s.options_.contact.cdt_lever_from_centre_of_mass;
  BodyState& B = s.bodies_;
  // Dashpots use the predicted end-of-step velocities, springs the half-step ones
  // (contact/hertz_mindlin.hpp); both come from the packed views (sim/contact_view.hpp).
  const SphereView* __restrict SV = s.sphere_view_.data();
  const std::uint32_t* __restrict SB = s.spheres_.body.data();       // a sphere's body
  const std::uint16_t* __restrict SM = s.spheres_.material.data();   // and material
  const BodyView* __restrict BV = s.body_view_.data();
  const InteractionTable& table = s.table_;
  const std::size_t nw = s.walls_.size();

  auto& pairs = s.pairs_;
  const auto& gs = pairs.group_start();
  const auto& si = pairs.si();
  const auto& sj = pairs.sj();
  auto& tang = pairs.tangential();
  auto& roll = pairs.rolling();
  const std::size_t groups = pairs.group_count();
  const bool count_groups = p.count_groups;
  std::vector<int>& sphere_group_touch = s.sphere_group_touch_;
  std::vector<int>& wall_group_touch = s.wall_group_touch_;

  auto& wl = s.wall_pairs_;
  const auto& wgs = wl.group_start();
  const auto& ws = wl.sphere();
  const auto& ww = wl.wall();
  const auto& wp = wl.primitive();
  auto& wtang = wl.tangential();
  auto& wroll = wl.rolling();

  constexpr bool batched = RM != RollingModel::epsd;
  const PairBatchArgs& batch = p.batch;
  const PairBatchFn batch_fn = p.batch_fn;
  const std::size_t nm = table.material_count();
  const WallBatchArgs& wall_args = p.wall_args;
  const WallBatchFn wall_fn = p.wall_fn;

  // Each thread takes the sphere pairs and then the wall pairs of one range of bodies, the ranges
  // cut where the work is equal (sim/work_split.hpp). One thread takes everything in list order.
  // Normally one share per thread; should the team be smaller, its threads take the rest in turn.
  const std::vector<WorkShare>& shares = s.work_shares_;
  const auto team = static_cast<std::size_t>(team_size);
  // CDT: each contact adds its capacity mu_r |Fn| R_i to its body; the force reduction turns the
  // body's total into its rolling torque (contact/rolling_cdt.hpp).
  {
    // A starts at zero: the force reduction clears it (Simulation::reduce_forces).
    BodyAccumulator* __restrict A = s.thread_body_acc_[static_cast<std::size_t>(t)].data();
    // Every write to A marks its body here (the reduction reads only marked accumulators).
    std::uint8_t* __restrict touched = s.thread_body_touched_[static_cast<std::size_t>(t)].data();
    WallAccumulator* __restrict WA = s.thread_wall_acc_[static_cast<std::size_t>(t)].data();
    for (std::size_t w = 0; w < nw; ++w) {
      WA[w].force_n.setZero();
      WA[w].torque_n_m.setZero();
      WA[w].contact_stiffness_n_m = 0.0;
      WA[w].contacts = 0;
    }
    // A private copy: the per-contact updates must not share a cache line between threads.
    ThreadStats st = p.stats[static_cast<std::size_t>(t)];
    // Filled here and handed over at the end: the vectors' own records sit side by side in
    // thread_cdt_wall_, and a push_back into them would write to a line the other threads use.
    std::vector<Simulation::CdtWallShare> cdt_wall;
    if constexpr (RM == RollingModel::cdt) {
      cdt_wall.swap(s.thread_cdt_wall_[static_cast<std::size_t>(t)]);
      cdt_wall.clear();
    }

    // ---- sphere-sphere, batched: chunks of groups; the touching pairs of a chunk are listed
    // (the others' history cleared) and handed to the batch kernel in list order ---------------
    if constexpr (batched) {
      // The thread's share is taken in chunks of about kChunkPairs listed pairs, cut at group
      // boundaries, small enough that a chunk's lists stay in the first-level cache.
      constexpr std::uint32_t kChunkPairs = 1024;
      KernelScratch& sc = s.thread_scratch_[static_cast<std::size_t>(t)];
      std::vector<std::uint32_t>& touch_k = sc.touch_k;
      // Hertz-Mindlin reads a scale of one for every pair from a buffer nothing writes to.
      std::vector<double>& touch_scale = NM == NormalModel::hmnr ? sc.touch_scale : sc.ones;
      PairBatchArgs args = batch;
      args.accumulators = reinterpret_cast<double*>(A);
      args.touched = touched;
      PairBatchStats pst;
      pst.ratio_limit = st.ratio_limit;
      const std::uint32_t* __restrict GS = gs.data();
      const std::uint32_t* __restrict SI = si.data();
      const std::uint32_t* __restrict SJ = sj.data();
      double* __restrict TG = batch.tangential_m;
      std::uint8_t* __restrict LIVE = pairs.live().data();
      int* __restrict GT = sphere_group_touch.data();
      for (std::size_t sh = static_cast<std::size_t>(t); sh < shares.size(); sh += team)
      for (std::size_t g_begin = shares[sh].sphere_begin; g_begin < shares[sh].sphere_end;) {
        // The next chunk: whole groups up to about kChunkPairs pairs (at least one group).
        std::size_t g_end = group_at_or_after(gs, groups, GS[g_begin] + kChunkPairs);
        g_end = std::min(std::max(g_end, g_begin + 1), shares[sh].sphere_end);
        const std::uint32_t k_begin = GS[g_begin], k_end = GS[g_end];
        const std::size_t span = k_end - k_begin;
        if (touch_k.size() < span) touch_k.resize(span);
        if (touch_scale.size() < span) touch_scale.resize(span, 1.0);
        std::uint32_t* __restrict TK = touch_k.data();
        std::uint8_t* __restrict TF = LIVE + k_begin;  // this chunk's pairs: touching now
        const std::size_t n = list_touching_pairs(SV, SI, SJ, k_begin, k_end, TK, TF, TG);
        std::size_t listed = 0;
        for (std::size_t g = g_begin; count_groups && g < g_end; ++g) {
          int touching = 0;
          for (std::uint32_t k = GS[g]; k < GS[g + 1]; ++k) touching += TF[k - k_begin];
          GT[g] = touching;
          if constexpr (NM == NormalModel::hmnr) {
            const double scale = hmnr_damping_scale(touching);
            for (int i = 0; i < touching; ++i)
              touch_scale[listed + static_cast<std::size_t>(i)] = scale;
          }
          listed += static_cast<std::size_t>(touching);
        }
        st.sphere_contacts += n;
        batch_fn(args, touch_k.data(), touch_scale.data(), n, pst);
        g_begin = g_end;
      }
      st.max_overlap = std::max(st.max_overlap, pst.max_overlap_m);
      st.max_fn = std::max(st.max_fn, pst.max_fn_n);
      if (pst.worst_ratio > st.worst_ratio) {
        st.worst_ratio = pst.worst_ratio;
        st.worst_body = pst.worst_body;
        st.worst_radius = pst.worst_radius_m;
      }
    } else {
    // ---- sphere-sphere, one body pair per group (EPSD) -----------------------------------------
    for (std::size_t sh = static_cast<std::size_t>(t); sh < shares.size(); sh += team)
    for (std::size_t g = shares[sh].sphere_begin; g < shares[sh].sphere_end; ++g) {
      const std::uint32_t a = gs[g], e = gs[g + 1];
      double scale = 1.0;
      if constexpr (NM == NormalModel::hmnr) {
        int n = 0;
        for (std::uint32_t k = a; k < e; ++k) {
          const double rs = SV[si[k]].radius_m + SV[sj[k]].radius_m;
          if ((SV[sj[k]].position_m - SV[si[k]].position_m).squaredNorm() < rs * rs) ++n;
        }
        scale = hmnr_damping_scale(n);
      }
      int touching = 0;
      for (std::uint32_t k = a; k < e; ++k) {
        const SphereView& Si = SV[si[k]];
        const SphereView& Sj = SV[sj[k]];
        const double ri = Si.radius_m, rj = Sj.radius_m;
        const Vec3 d = Sj.position_m - Si.position_m;
        const double dist2 = d.squaredNorm();
        const double rs = ri + rj;
        if (dist2 >= rs * rs) {
          tang[k].setZero();
          if constexpr (RM == RollingModel::epsd) roll[k].setZero();
          continue;
        }
        ++touching;
        const double dist = std::sqrt(dist2);
        const Vec3 normal = dist > 0.0 ? Vec3(d * (1.0 / dist)) : Vec3::UnitZ();
        const double overlap = rs - dist;
        const std::uint32_t bi = SB[si[k]], bj = SB[sj[k]];
        const BodyView& Bi = BV[bi];
        const BodyView& Bj = BV[bj];
        const Vec3 cp = Si.position_m + (ri - 0.5 * overlap) * normal;
        const Vec3 rci = cp - Bi.position_m;
        const Vec3 rcj = cp - Bj.position_m;
        const Vec3& wi = Bi.angular_velocity;
        const Vec3& wj = Bj.angular_velocity;
        const Vec3 vrel = (Bi.velocity_m_s + wi.cross(rci)) - (Bj.velocity_m_s + wj.cross(rcj));
        const Vec3 vrel_end = (Bi.velocity_end_m_s + Bi.angular_velocity_end.cross(rci)) -
                              (Bj.velocity_end_m_s + Bj.angular_velocity_end.cross(rcj));
        const PairConstants& pc = table.pair(SM[si[k]], SM[sj[k]]);
        const ContactKinematics kin{normal, overlap, ri * rj / rs, 1.0 / (Bi.inv_mass + Bj.inv_mass),
                                    vrel, vrel_end};
        const ContactForce cf = hertz_mindlin(pc, kin, tang[k], dt, scale, clip);
        BodyAccumulator& Ai = A[bi];
        BodyAccumulator& Aj = A[bj];
        touched[bi] = touched[bj] = 1;
        Ai.force_n += cf.force_on_i_n;
        Aj.force_n -= cf.force_on_i_n;
        Ai.torque_n_m += rci.cross(cf.force_on_i_n);
        Aj.torque_n_m -= rcj.cross(cf.force_on_i_n);
        if constexpr (RM == RollingModel::cdt) {
          const double c = pc.rolling_friction * std::abs(cf.normal_force_n);
          Ai.roll_capacity_n_m += c * (lever_com ? rci.norm() : ri - 0.5 * overlap);
          Aj.roll_capacity_n_m += c * (lever_com ? rcj.norm() : rj - 0.5 * overlap);
        } else if constexpr (RM == RollingModel::epsd) {
          const double ii = B.principal_inertia[bi].mean() + B.mass_kg[bi] * rci.squaredNorm();
          const double ij = B.principal_inertia[bj].mean() + B.mass_kg[bj] * rcj.squaredNorm();
          const EpsdInput in{normal, wi - wj, Bi.angular_velocity_end - Bj.angular_velocity_end,
                             pc.rolling_friction, cf.normal_force_n, cf.normal_stiffness_n_m,
                             kin.r_star_m, ii * ij / (ii + ij), eta_r, dt};
          const Vec3 tau = epsd_torque(in, roll[k]);
          Ai.torque_n_m += tau;
          Aj.torque_n_m -= tau;
        }
        st.note(overlap, cf.normal_force_n, std::min(ri, rj), ri <= rj ? bi : bj);
      }
      if (count_groups) sphere_group_touch[g] = touching;
      st.sphere_contacts += static_cast<std::size_t>(touching);
    }
    }

    // ---- sphere-wall, one (body, wall) pair per group --------------------------------------------
    if constexpr (batched) {
      // The touching pairs are gathered (shape queries, one at a time), their forces computed by
      // the wall batch kernel, four at a time where the CPU allows, and added to the bodies and
      // walls in list order.
      constexpr std::size_t kWallBatch = 256;
      KernelScratch& sc = s.thread_scratch_[static_cast<std::size_t>(t)];
      std::vector<WallContactIn>& win = sc.wall_in;
      std::vector<WallContactOut>& wout = sc.wall_out;
      std::vector<WallSide>& side = sc.wall_side;
      win.clear();
      side.clear();
      const auto flush = [&] {
        wout.resize(win.size());
        wall_fn(wall_args, win.data(), win.size(), wout.data());
        for (std::size_t i = 0; i < win.size(); ++i) {
          const WallContactIn& c = win[i];
          const WallContactOut& o = wout[i];
          const Vec3 f(o.force_on_sphere_n[0], o.force_on_sphere_n[1], o.force_on_sphere_n[2]);
          BodyAccumulator& Ab = A[c.body];
          touched[c.body] = 1;
          Ab.force_n += f;
          Ab.torque_n_m += Vec3(o.torque_n_m[0], o.torque_n_m[1], o.torque_n_m[2]);
          WallAccumulator& Aw = WA[side[i].wall];
          Aw.force_n -= f;
          Aw.contact_stiffness_n_m += o.normal_stiffness_n_m;
          ++Aw.contacts;
          Aw.torque_n_m -= side[i].arm_m.cross(f);
          if constexpr (RM == RollingModel::cdt) {
            // The wall takes the reaction of the rolling-resistance couple (a drum or a rotating
            // plate feels it as a torque about its origin).
            Ab.roll_capacity_n_m += o.roll_capacity_n_m;
            cdt_wall.push_back({side[i].wall, c.body, o.roll_capacity_n_m});
          }
          st.note(c.overlap_m, o.normal_force_n, c.radius_m, c.body);
        }
        win.clear();
        side.clear();
      };
      for (std::size_t sh = static_cast<std::size_t>(t); sh < shares.size(); sh += team)
      for (std::size_t g = shares[sh].wall_begin; g < shares[sh].wall_end; ++g) {
        const std::uint32_t a = wgs[g], e = wgs[g + 1];
        const Wall& wall = s.walls_[ww[a]];
        int touching = 0;
        for (std::uint32_t k = a; k < e; ++k) {
          const SphereView& Si = SV[ws[k]];
          const double r = Si.radius_m;
          WallHit hit;
          if (!touches_wall(wall, Si, wp[k], hit)) {
            wtang[k].setZero();
            continue;
          }
          ++touching;
          const Vec3 normal = wall.pose.orientation * hit.normal;
          const Vec3 arm = wall.pose.orientation * hit.point;
          const Vec3 cp = wall.pose.origin_m + arm;
          const std::uint32_t b = SB[ws[k]];
          const Vec3 rc = cp - BV[b].position_m;
          const Vec3 v_wall = wall.velocity_at(cp);
          WallContactIn c;
          for (int i = 0; i < 3; ++i) {
            c.normal[i] = normal[i];
            c.lever_m[i] = rc[i];
            c.wall_velocity_m_s[i] = v_wall[i];
          }
          c.overlap_m = r - hit.distance;
          c.radius_m = r;
          c.mass_kg = B.mass_kg[b];
          c.rolling_lever_m = lever_com ? rc.norm() : hit.distance;
          c.damping_scale = 1.0;
          c.body = b;
          c.constants = static_cast<std::uint32_t>(SM[ws[k]] * nm + wall.material);
          c.pair = k;
          win.push_back(c);
          side.push_back({ww[a], Vec3(cp - wall.pose.origin_m)});
        }
        if constexpr (NM == NormalModel::hmnr) {
          // The group's touching pairs share the body and the wall: one scale for all of them.
          const double scale = hmnr_damping_scale(touching);
          for (std::size_t i = win.size() - static_cast<std::size_t>(touching); i < win.size(); ++i)
            win[i].damping_scale = scale;
        }
        wall_group_touch[g] = touching;
        st.wall_contacts += static_cast<std::size_t>(touching);
        if (win.size() >= kWallBatch) flush();
      }
      flush();
    } else {
    // ---- sphere-wall, one (body, wall) pair per group, EPSD -------------------------------------
    for (std::size_t sh = static_cast<std::size_t>(t); sh < shares.size(); sh += team)
    for (std::size_t g = shares[sh].wall_begin; g < shares[sh].wall_end; ++g) {
      const std::uint32_t a = wgs[g], e = wgs[g + 1];
      const Wall& wall = s.walls_[ww[a]];
      double scale = 1.0;
      if constexpr (NM == NormalModel::hmnr) {
        int n = 0;
        WallHit hit;
        for (std::uint32_t k = a; k < e; ++k) n += touches_wall(wall, SV[ws[k]], wp[k], hit) ? 1 : 0;
        scale = hmnr_damping_scale(n);
      }
      int touching = 0;
      for (std::uint32_t k = a; k < e; ++k) {
        const SphereView& Si = SV[ws[k]];
        const double r = Si.radius_m;
        WallHit hit;
        if (!touches_wall(wall, Si, wp[k], hit)) {
          wtang[k].setZero();
          wroll[k].setZero();
          continue;
        }
        ++touching;
        const double overlap = r - hit.distance;
        const Vec3 normal = wall.pose.orientation * hit.normal;
        const Vec3 cp = wall.pose.origin_m + wall.pose.orientation * hit.point;
        const std::uint32_t b = SB[ws[k]];
        const BodyView& Bb = BV[b];
        const Vec3 rc = cp - Bb.position_m;
        const Vec3& w = Bb.angular_velocity;
        const Vec3 v_wall = wall.velocity_at(cp);
        const Vec3 vrel = Bb.velocity_m_s + w.cross(rc) - v_wall;
        const Vec3 vrel_end = Bb.velocity_end_m_s + Bb.angular_velocity_end.cross(rc) - v_wall;
        const PairConstants& pc = table.pair(SM[ws[k]], wall.material);
        const ContactKinematics kin{normal, overlap, r, B.mass_kg[b], vrel, vrel_end};
        const ContactForce cf = hertz_mindlin(pc, kin, wtang[k], dt, scale, clip);
        BodyAccumulator& Ab = A[b];
        touched[b] = 1;
        Ab.force_n += cf.force_on_i_n;
        Ab.torque_n_m += rc.cross(cf.force_on_i_n);
        WallAccumulator& Aw = WA[ww[a]];
        Aw.force_n -= cf.force_on_i_n;
        Aw.contact_stiffness_n_m += cf.normal_stiffness_n_m;
        ++Aw.contacts;
        Aw.torque_n_m -= (cp - wall.pose.origin_m).cross(cf.force_on_i_n);
        const double ib = B.principal_inertia[b].mean() + B.mass_kg[b] * rc.squaredNorm();
        const EpsdInput in{normal, w - wall.pose.angular_velocity_rad_s,
                           Bb.angular_velocity_end - wall.pose.angular_velocity_rad_s,
                           pc.rolling_friction, cf.normal_force_n, cf.normal_stiffness_n_m, r, ib,
                           eta_r, dt};
        const Vec3 tau = epsd_torque(in, wroll[k]);
        Ab.torque_n_m += tau;
        Aw.torque_n_m -= tau;
        st.note(overlap, cf.normal_force_n, r, b);
      }
      wall_group_touch[g] = touching;
      st.wall_contacts += static_cast<std::size_t>(touching);
    }
    }
    if constexpr (RM == RollingModel::cdt)
      cdt_wall.swap(s.thread_cdt_wall_[static_cast<std::size_t>(t)]);
    p.stats[static_cast<std::size_t>(t)] = st;
  }
}

void prepare_contact_pass(Simulation& s, ContactPass& pass) { ForceKernel::prepare(s, pass); }

ThreadStats finish_contact_pass(const ContactPass& pass) {
  ThreadStats total;
  for (const ThreadStats& st : pass.stats) {
    total.sphere_contacts += st.sphere_contacts;
    total.wall_contacts += st.wall_contacts;
    total.max_overlap = std::max(total.max_overlap, st.max_overlap);
    total.max_fn = std::max(total.max_fn, st.max_fn);
    if (st.worst_ratio > total.worst_ratio ||
        (st.worst_ratio == total.worst_ratio && st.worst_body >= 0 &&
         (total.worst_body < 0 || st.worst_body < total.worst_body))) {
      total.worst_ratio = st.worst_ratio;
      total.worst_body = st.worst_body;
      total.worst_radius = st.worst_radius;
    }
  }
  return total;
}

// Dispatch: the model combination is chosen once per step, at run time, from the options.
void run_contact_pass(Simulation& s, ContactPass& pass, int thread, int team) {
  using N = NormalModel;
  using R = RollingModel;
  const RollingModel rm = pass.rolling;
  if (pass.normal == N::hertz_mindlin) {
    if (rm == R::none) ForceKernel::pass<N::hertz_mindlin, R::none>(s, pass, thread, team);
    else if (rm == R::cdt) ForceKernel::pass<N::hertz_mindlin, R::cdt>(s, pass, thread, team);
    else ForceKernel::pass<N::hertz_mindlin, R::epsd>(s, pass, thread, team);
  } else {
    if (rm == R::none) ForceKernel::pass<N::hmnr, R::none>(s, pass, thread, team);
    else if (rm == R::cdt) ForceKernel::pass<N::hmnr, R::cdt>(s, pass, thread, team);
    else ForceKernel::pass<N::hmnr, R::epsd>(s, pass, thread, team);
  }
}

}  // namespace seedcal
