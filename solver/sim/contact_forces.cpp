// The contact force pass: one pass over the sphere-sphere groups and one over the sphere-wall
// groups, compiled once per (normal model, rolling model) combination and chosen once per step by
// a switch (no model tests inside the loops). Both list their touching contacts and hand them to
// the batch kernels (sim/pair_batch.hpp), which run the contact law (contact/contact_law.hpp).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "solver/contact/normal_damping.hpp"
#include "solver/sim/contact_forces.hpp"
#include "solver/sim/pair_batch.hpp"
#include "solver/sim/contact_pipeline.hpp"
#include "solver/sim/overlap_limits.hpp"
#include "solver/sim/thread_plan.hpp"
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
// does (and its rolling spring, 3 doubles per pair in `rolling`, under EPSD; null otherwise). The
// far sphere of a pair a few pairs ahead is fetched early.
std::size_t list_touching_pairs(const SphereView* __restrict SV, const std::uint32_t* __restrict SI,
                                const std::uint32_t* __restrict SJ, std::uint32_t k_begin,
                                std::uint32_t k_end, std::uint32_t* __restrict touching,
                                std::uint8_t* __restrict live, double* __restrict spring,
                                double* __restrict rolling) {
  std::size_t n = 0;
  for (std::uint32_t k = k_begin; k < k_end; ++k) {
    if (k + 16 < k_end) __builtin_prefetch(&SV[SJ[k + 16]]);
    const SphereView& Si = SV[SI[k]];
    const SphereView& Sj = SV[SJ[k]];
    const double rs = Si.radius_m + Sj.radius_m;
    // The distance exactly as the batch kernel computes it (sim/pair_batch_lanes.hpp), so
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
      if (rolling) {
        double* r = rolling + 3 * static_cast<std::size_t>(k);
        r[0] = r[1] = r[2] = 0.0;
      }
    }
    live[k - k_begin] = touch;
  }
  return n;
}

// `turned`: the wall's orientation is not the identity. Otherwise its frame differs from the
// world's by the origin only, and the rotations below, which would return their argument, are
// skipped.
inline bool turned_wall(const Wall& wall) {
  return wall.pose.orientation.coeffs() != Quat::Identity().coeffs();
}

// A direction of `wall`'s frame in the world's.
inline Vec3 wall_direction_to_world(const Wall& wall, bool turned, const Vec3& v) {
  return turned ? Vec3(wall.pose.orientation * v) : v;
}

// Whether sphere `sv` touches primitive `primitive` of `wall`; fills `hit` (wall frame) when so.
inline bool touches_wall(const Wall& wall, bool turned, const SphereView& sv,
                         std::uint32_t primitive, WallHit& hit) {
  const Vec3 local = turned ? to_wall_frame(wall.pose, sv.position_m)
                            : Vec3(sv.position_m - wall.pose.origin_m);
  return wall.shape->nearest(static_cast<int>(primitive), local, sv.radius_m, hit) &&
         hit.distance < sv.radius_m;
}

// HMNR (contact/normal_damping.hpp): the `touching` contacts of one body pair (or body and wall),
// listed from `scale` on, share one damping scale.
inline void set_group_damping_scale(int touching, double* scale) {
  std::fill_n(scale, touching, hmnr_damping_scale(touching));
}

// One thread's shares of the pass.
template <NormalModel NM, RollingModel RM>
void contact_pass(const ContactInputs& in, ContactPipeline& pipe, ThreadPlan& plan, int t,
                  int team_size);

}  // namespace

std::vector<BatchPairConstants> pack_batch_constants(const InteractionTable& table) {
  const std::size_t nm = table.material_count();
  std::vector<BatchPairConstants> packed(nm * nm);
  for (std::size_t i = 0; i < nm; ++i)
    for (std::size_t j = 0; j < nm; ++j) {
      const PairConstants& pc = table.pair(static_cast<std::uint16_t>(i), static_cast<std::uint16_t>(j));
      packed[i * nm + j] = {pc.e_star_pa, pc.beta, pc.static_friction, pc.rolling_friction,
                            pc.sqrt_tangential_ratio};
    }
  return packed;
}

void prepare_contact_pass(const ContactInputs& in, ContactPipeline& pipe) {
  ContactPass& p = pipe.pass;
  p.normal = in.options.contact.normal;
  p.rolling = in.options.contact.rolling;
  const std::size_t groups = pipe.pairs.group_count();
  // Touching pairs per body pair: HMNR's damping scale, and the per-body contact counts when they
  // are tracked; otherwise not counted (a pass over every group of the list).
  p.count_groups = p.normal == NormalModel::hmnr || in.options.track_body_contacts;
  if (p.count_groups) pipe.sphere_group_touch.assign(groups, 0);
  else pipe.sphere_group_touch.clear();
  pipe.wall_group_touch.assign(pipe.wall_pairs.group_count(), 0);
  p.stats.assign(static_cast<std::size_t>(std::max(1, in.options.threads)), ThreadStats{});
  for (ThreadStats& ts : p.stats) ts.prefilter = overlap_prefilter_fraction(in.options.guards);

  const InteractionTable& table = in.table;
  const std::size_t nm = table.material_count();
  // The table is fixed for the simulation's life: its constants are packed once.
  if (p.batch_constants.size() != nm * nm) p.batch_constants = pack_batch_constants(table);
  const bool epsd = p.rolling == RollingModel::epsd;
  auto& tang = pipe.pairs.tangential();
  auto& wtang = pipe.wall_pairs.tangential();
  auto& roll = pipe.pairs.rolling();
  auto& wroll = pipe.wall_pairs.rolling();
  PairBatchArgs& batch = p.batch;
  batch.spheres = reinterpret_cast<const double*>(pipe.sphere_view.data());
  batch.sphere_body = in.spheres.body.data();
  batch.sphere_material = in.spheres.material.data();
  batch.bodies = reinterpret_cast<const double*>(pipe.body_view.data());
  batch.pair_constants = p.batch_constants.data();
  batch.materials = nm;
  batch.uniform_constants =
      pipe.one_sphere_material >= 0
          ? &p.batch_constants[static_cast<std::size_t>(pipe.one_sphere_material) * (nm + 1)]
          : nullptr;
  batch.si = pipe.pairs.si().data();
  batch.sj = pipe.pairs.sj().data();
  batch.tangential_m = tang.empty() ? nullptr : tang.data()->data();
  batch.rolling_m = epsd && !roll.empty() ? roll.data()->data() : nullptr;
  batch.body_mass_kg = in.bodies.mass_kg.data();
  batch.body_inertia_kg_m2 =
      in.bodies.principal_inertia.empty() ? nullptr : in.bodies.principal_inertia.data()->data();
  batch.dt_s = in.options.dt_s;
  batch.clip_attractive = in.options.contact.clip_attractive;
  batch.rolling = p.rolling;
  batch.cdt_lever_from_centre_of_mass = in.options.contact.cdt_lever_from_centre_of_mass;
  batch.epsd_damping_ratio = in.options.contact.epsd_damping_ratio;
  batch.overlap_limit_m = pipe.overlap_limit_m.data();
  // The body views' end velocities differ from the half-step ones only when the dashpots use the
  // predicted velocity (Simulation::step, VerletPass::predict_s).
  batch.end_velocities = in.options.contact.dashpot_predicted;
  p.batch_fn = choose_pair_batch(in.options.simd_lanes);
  WallBatchArgs& wall_args = p.wall_args;
  wall_args.bodies = batch.bodies;
  wall_args.pair_constants = batch.pair_constants;
  wall_args.tangential_m = wtang.empty() ? nullptr : wtang.data()->data();
  wall_args.rolling_m = epsd && !wroll.empty() ? wroll.data()->data() : nullptr;
  wall_args.dt_s = batch.dt_s;
  wall_args.clip_attractive = batch.clip_attractive;
  wall_args.rolling = p.rolling;
  wall_args.epsd_damping_ratio = batch.epsd_damping_ratio;
  wall_args.end_velocities = batch.end_velocities;
  p.wall_fn = choose_wall_batch(in.options.simd_lanes);
}

namespace {

template <NormalModel NM, RollingModel RM>
void contact_pass(const ContactInputs& in, ContactPipeline& pipe, ThreadPlan& plan, int t,
                  int team_size) {
  ContactPass& p = pipe.pass;
  constexpr bool epsd = RM == RollingModel::epsd;
  const bool lever_com = in.options.contact.cdt_lever_from_centre_of_mass;
  const BodyState& B = in.bodies;
  const SphereView* __restrict SV = pipe.sphere_view.data();
  const std::uint32_t* __restrict SB = in.spheres.body.data();       // a sphere's body
  const std::uint16_t* __restrict SM = in.spheres.material.data();   // and material
  const double* __restrict OL = pipe.overlap_limit_m.data();  // a sphere's deepest allowed overlap
  const BodyView* __restrict BV = pipe.body_view.data();
  const std::size_t nw = in.walls.size();
  const std::size_t nm = in.table.material_count();

  auto& pairs = pipe.pairs;
  const auto& gs = pairs.group_start();
  const std::size_t groups = pairs.group_count();
  const bool count_groups = p.count_groups;

  auto& wl = pipe.wall_pairs;
  const auto& wgs = wl.group_start();
  const auto& ws = wl.sphere();
  const auto& ww = wl.wall();
  const auto& wp = wl.primitive();
  auto& wtang = wl.tangential();
  auto& wroll = wl.rolling();

  // Each thread takes the sphere pairs and then the wall pairs of one range of bodies, the ranges
  // cut where the work is equal (sim/work_split.hpp). One thread takes everything in list order.
  // Normally one share per thread; should the team be smaller, its threads take the rest in turn.
  const std::vector<WorkShare>& shares = plan.shares;
  const auto team = static_cast<std::size_t>(team_size);
  const auto ti = static_cast<std::size_t>(t);
  // A starts at zero: the force reduction clears it (Simulation::reduce_forces).
  BodyAccumulator* __restrict A = plan.body_acc[ti].data();
  // Every write to A marks its body here (the reduction reads only marked accumulators).
  std::uint8_t* __restrict touched = plan.body_touched[ti].data();
  WallAccumulator* __restrict WA = plan.wall_acc[ti].data();
  for (std::size_t w = 0; w < nw; ++w) {
    WA[w].force_n.setZero();
    WA[w].torque_n_m.setZero();
    WA[w].contact_stiffness_n_m = 0.0;
    WA[w].contacts = 0;
  }
  // A private copy: the per-contact updates must not share a cache line between threads.
  ThreadStats st = p.stats[ti];
  KernelScratch& sc = plan.scratch[ti];
  // CDT: each contact adds its capacity mu_r |Fn| R_i to its body; the force reduction turns the
  // body's total into its rolling torque (contact/rolling_cdt_torque.hpp). Filled here and handed
  // over at the end: the vectors' own records sit side by side in ThreadPlan::cdt_wall, and a
  // push_back into them would write to a line the other threads use.
  std::vector<CdtWallShare> cdt_wall;
  if constexpr (RM == RollingModel::cdt) {
    cdt_wall.swap(plan.cdt_wall[ti]);
    cdt_wall.clear();
  }

  // ---- sphere-sphere: chunks of groups; the touching pairs of a chunk are listed (the others'
  // history cleared) and handed to the batch kernel in list order -------------------------------
  {
    // The thread's share is taken in chunks of about kChunkPairs listed pairs, cut at group
    // boundaries, small enough that a chunk's lists stay in the first-level cache.
    constexpr std::uint32_t kChunkPairs = 1024;
    std::vector<std::uint32_t>& touch_k = sc.touch_k;
    // HMNR's damping scale per touching pair; Hertz-Mindlin's kernel takes none (a scale of 1).
    std::vector<double>& touch_scale = sc.touch_scale;
    double* scale = nullptr;
    PairBatchArgs args = p.batch;
    args.accumulators = reinterpret_cast<double*>(A);
    args.touched = touched;
    PairBatchStats pst;
    pst.prefilter = st.prefilter;
    const std::uint32_t* __restrict GS = gs.data();
    const std::uint32_t* __restrict SI = pairs.si().data();
    const std::uint32_t* __restrict SJ = pairs.sj().data();
    double* __restrict TG = args.tangential_m;
    double* __restrict RG = args.rolling_m;  // null unless EPSD (prepare_contact_pass)
    std::uint8_t* __restrict LIVE = pairs.live().data();
    int* __restrict GT = pipe.sphere_group_touch.data();
    for (std::size_t sh = ti; sh < shares.size(); sh += team)
    for (std::size_t g_begin = shares[sh].sphere_begin; g_begin < shares[sh].sphere_end;) {
      // The next chunk: whole groups up to about kChunkPairs pairs (at least one group).
      std::size_t g_end = group_at_or_after(gs, groups, GS[g_begin] + kChunkPairs);
      g_end = std::min(std::max(g_end, g_begin + 1), shares[sh].sphere_end);
      const std::uint32_t k_begin = GS[g_begin], k_end = GS[g_end];
      const std::size_t span = k_end - k_begin;
      if (touch_k.size() < span) touch_k.resize(span);
      if constexpr (NM == NormalModel::hmnr) {
        if (touch_scale.size() < span) touch_scale.resize(span, 1.0);
        scale = touch_scale.data();
      }
      std::uint32_t* __restrict TK = touch_k.data();
      std::uint8_t* __restrict TF = LIVE + k_begin;  // this chunk's pairs: touching now
      const std::size_t n = list_touching_pairs(SV, SI, SJ, k_begin, k_end, TK, TF, TG, RG);
      std::size_t listed = 0;
      for (std::size_t g = g_begin; count_groups && g < g_end; ++g) {
        int touching = 0;
        for (std::uint32_t k = GS[g]; k < GS[g + 1]; ++k) touching += TF[k - k_begin];
        GT[g] = touching;
        if constexpr (NM == NormalModel::hmnr)
          set_group_damping_scale(touching, scale + listed);
        listed += static_cast<std::size_t>(touching);
      }
      st.sphere_contacts += n;
      p.batch_fn(args, touch_k.data(), scale, n, pst);
      g_begin = g_end;
    }
    st.max_overlap = std::max(st.max_overlap, pst.max_overlap_m);
    st.max_fn = std::max(st.max_fn, pst.max_fn_n);
    st.deep.merge(pst.deep);
  }

  // ---- sphere-wall, one (body, wall) pair per group: the touching pairs are gathered (shape
  // queries, one at a time), their forces computed by the wall batch kernel and added to the
  // bodies and walls in list order --------------------------------------------------------------
  {
    constexpr std::size_t kWallBatch = 256;
    std::vector<WallContactIn>& win = sc.wall_in;
    std::vector<double>& wscale = sc.wall_scale;
    std::vector<WallRollingIn>& wrin = sc.wall_rolling;
    std::vector<WallContactOut>& wout = sc.wall_out;
    std::vector<WallSide>& side = sc.wall_side;
    win.clear();
    wscale.clear();
    wrin.clear();
    side.clear();
    const auto flush = [&] {
      wout.resize(win.size());
      p.wall_fn(p.wall_args, WallBatch{win.data(), wscale.data(), epsd ? wrin.data() : nullptr,
                                       win.size(), wout.data()});
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
        } else if constexpr (epsd) {
          const Vec3 tau(o.rolling_torque_n_m[0], o.rolling_torque_n_m[1], o.rolling_torque_n_m[2]);
          Ab.torque_n_m += tau;
          Aw.torque_n_m -= tau;
        }
        st.note(c.overlap_m, o.normal_force_n, c.radius_m, OL[ws[c.pair]], c.body);
      }
      win.clear();
      wscale.clear();
      wrin.clear();
      side.clear();
    };
    for (std::size_t sh = ti; sh < shares.size(); sh += team)
    for (std::size_t g = shares[sh].wall_begin; g < shares[sh].wall_end; ++g) {
      const std::uint32_t a = wgs[g], e = wgs[g + 1];
      const Wall& wall = in.walls[ww[a]];
      const bool turned = turned_wall(wall);
      int touching = 0;
      for (std::uint32_t k = a; k < e; ++k) {
        const SphereView& Si = SV[ws[k]];
        const double r = Si.radius_m;
        WallHit hit;
        if (!touches_wall(wall, turned, Si, wp[k], hit)) {
          wtang[k].setZero();
          if constexpr (epsd) wroll[k].setZero();
          continue;
        }
        ++touching;
        const Vec3 normal = wall_direction_to_world(wall, turned, hit.normal);
        const Vec3 arm = wall_direction_to_world(wall, turned, hit.point);
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
        c.spare = 0.0;
        c.body = b;
        c.constants = static_cast<std::uint32_t>(SM[ws[k]] * nm + wall.material);
        c.pair = k;
        win.push_back(c);
        wscale.push_back(1.0);
        if constexpr (epsd) {
          // The body's inertia about the contact point (the wall's is infinite).
          const Vec3& spin = wall.pose.angular_velocity_rad_s;
          wrin.push_back({{spin.x(), spin.y(), spin.z()},
                          B.principal_inertia[b].mean() + B.mass_kg[b] * rc.squaredNorm()});
        }
        side.push_back({ww[a], Vec3(cp - wall.pose.origin_m)});
      }
      if constexpr (NM == NormalModel::hmnr)
        set_group_damping_scale(touching, wscale.data() + (wscale.size() - static_cast<std::size_t>(touching)));
      pipe.wall_group_touch[g] = touching;
      st.wall_contacts += static_cast<std::size_t>(touching);
      if (win.size() >= kWallBatch) flush();
    }
    flush();
  }
  if constexpr (RM == RollingModel::cdt) cdt_wall.swap(plan.cdt_wall[ti]);
  p.stats[ti] = st;
}

}  // namespace

ThreadStats finish_contact_pass(const ContactPass& pass) {
  ThreadStats total;
  for (const ThreadStats& st : pass.stats) {
    total.sphere_contacts += st.sphere_contacts;
    total.wall_contacts += st.wall_contacts;
    total.max_overlap = std::max(total.max_overlap, st.max_overlap);
    total.max_fn = std::max(total.max_fn, st.max_fn);
    total.deep.merge(st.deep);
  }
  return total;
}

// Dispatch: the model combination is chosen once per step, at run time, from the options.
void run_contact_pass(const ContactInputs& in, ContactPipeline& pipe, ThreadPlan& plan, int thread,
                      int team) {
  using N = NormalModel;
  using R = RollingModel;
  const RollingModel rm = pipe.pass.rolling;
  if (pipe.pass.normal == N::hertz_mindlin) {
    if (rm == R::none) contact_pass<N::hertz_mindlin, R::none>(in, pipe, plan, thread, team);
    else if (rm == R::cdt) contact_pass<N::hertz_mindlin, R::cdt>(in, pipe, plan, thread, team);
    else contact_pass<N::hertz_mindlin, R::epsd>(in, pipe, plan, thread, team);
  } else {
    if (rm == R::none) contact_pass<N::hmnr, R::none>(in, pipe, plan, thread, team);
    else if (rm == R::cdt) contact_pass<N::hmnr, R::cdt>(in, pipe, plan, thread, team);
    else contact_pass<N::hmnr, R::epsd>(in, pipe, plan, thread, team);
  }
}

}  // namespace seedcal
