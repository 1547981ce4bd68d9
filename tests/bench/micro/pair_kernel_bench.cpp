// The sphere-sphere batch kernel (sim/pair_batch.hpp) alone, on the touching pairs of a jittered
// lattice of lone spheres, at each width this CPU runs (1, 4 or 8 lanes): touching pairs per
// second. The lattice pitch is 1.98 radii, so that every sphere presses on its six lattice
// neighbours, as in a settled bed (about six contacts a sphere against 4.3 in the settled-bed
// scene); the pairs come in neighbour-list order, so the far sphere's records are read as the
// solver reads them.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "solver/broadphase/verlet_list.hpp"
#include "solver/core/materials.hpp"
#include "solver/sim/contact_forces.hpp"
#include "solver/sim/contact_view.hpp"
#include "solver/sim/pair_batch.hpp"

namespace seedcal {
namespace {

struct LatticePairs {
  SphereState state;
  std::vector<SphereView> spheres;
  std::vector<BodyView> bodies;
  std::vector<BodyAccumulator> acc;
  std::vector<std::uint8_t> touched;
  VerletList list;
  std::vector<std::uint32_t> touching;
};

LatticePairs make_lattice_pairs(int n_side) {
  constexpr double r = 0.002, pitch = 1.98 * r, jitter = 0.01 * r;
  LatticePairs L;
  SphereState& s = L.state;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < n_side; ++k)
    for (int j = 0; j < n_side; ++j)
      for (int i = 0; i < n_side; ++i) {
        const auto b = static_cast<std::uint32_t>(s.size());
        const Vec3 p = Vec3(i, j, k) * pitch + jitter * Vec3(u(rng), u(rng), u(rng));
        s.body.push_back(b);
        s.offset_body_m.push_back(Vec3::Zero());
        s.radius_m.push_back(r);
        s.material.push_back(0);
        s.position_m.push_back(p);
        SphereView sv{};
        sv.position_m = p;
        sv.radius_m = r;
        L.spheres.push_back(sv);
        BodyView bv{};
        bv.velocity_m_s = 0.01 * Vec3(u(rng), u(rng), u(rng));
        bv.angular_velocity = 1.0 * Vec3(u(rng), u(rng), u(rng));
        bv.velocity_end_m_s = bv.velocity_m_s;
        bv.angular_velocity_end = bv.angular_velocity;
        bv.inv_mass = 1.0 / (1340.0 * 4.18879 * r * r * r);
        bv.position_m = p;
        L.bodies.push_back(bv);
      }
  L.list.build(s, 0.4 * r, false, 1);
  for (std::uint32_t k = 0; k < L.list.pair_count(); ++k) {
    const Vec3 d = s.position_m[L.list.sj()[k]] - s.position_m[L.list.si()[k]];
    if (d.squaredNorm() < 4.0 * r * r) L.touching.push_back(k);
  }
  BodyAccumulator zero{};  // {} leaves the Eigen members unset
  zero.force_n.setZero();
  zero.torque_n_m.setZero();
  L.acc.assign(s.size(), zero);
  L.touched.assign(s.size(), 0);
  return L;
}

void BM_PairBatch(benchmark::State& state) {
  const int lanes = static_cast<int>(state.range(0));
  if (pair_batch_lanes_used(lanes) != lanes) {
    state.SkipWithError("this CPU does not run that width");
    return;
  }
  LatticePairs L = make_lattice_pairs(static_cast<int>(state.range(1)));
  // Table 6's seed-seed contact (Jinong 1): E 1.65e8 Pa, nu 0.4, e 0.45, mu 0.55, mu_r 0.05.
  const InteractionTable table({{"seed", 1340.0, 1.65e8, 0.4}}, {{"ss", 0, 0, 0.45, 0.55, 0.05}});
  const std::vector<BatchPairConstants> constants = pack_batch_constants(table);
  PairBatchArgs args;
  args.spheres = reinterpret_cast<const double*>(L.spheres.data());
  args.sphere_body = L.state.body.data();
  args.sphere_material = L.state.material.data();
  args.bodies = reinterpret_cast<const double*>(L.bodies.data());
  args.accumulators = reinterpret_cast<double*>(L.acc.data());
  args.touched = L.touched.data();
  args.pair_constants = constants.data();
  args.materials = 1;
  args.uniform_constants = constants.data();  // one material, as the solver passes it
  args.si = L.list.si().data();
  args.sj = L.list.sj().data();
  args.tangential_m = L.list.tangential().data()->data();
  args.dt_s = 1e-6;
  args.rolling = RollingModel::cdt;
  // The end velocities read (dashpots at the predicted velocity) or not (the default half step).
  args.end_velocities = state.range(2) != 0;
  const PairBatchFn fn = choose_pair_batch(lanes);
  PairBatchStats stats;
  for (auto _ : state) {
    fn(args, L.touching.data(), nullptr, L.touching.size(), stats);  // Hertz-Mindlin: no scale
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(L.touching.size()));
  state.counters["pairs"] = static_cast<double>(L.touching.size());
}
// 16^3 = 4,096 spheres (the records in the second-level cache) and 32^3 = 32,768 (in the
// third-level cache or memory, as in the settled bed's 10,000).
BENCHMARK(BM_PairBatch)
    ->ArgNames({"lanes", "side", "end"})
    ->ArgsProduct({{1, 4, 8}, {16, 32}, {0, 1}});

}  // namespace
}  // namespace seedcal
