// One free-rotation step of a body (integrate/free_rotation.hpp): the asymmetric rotor splitting
// of a clump and the exact rotation of a sphere, bodies per second. The bodies are independent,
// as in the solver's body pass, so the processor may overlap their chains of operations.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "solver/integrate/free_rotation.hpp"

namespace seedcal {
namespace {

void BM_FreeRotation(benchmark::State& state) {
  const bool isotropic = state.range(0) != 0;
  constexpr int n = 1024;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Quat> q(n);
  std::vector<Vec3> L(n), inv_inertia(n);
  for (int b = 0; b < n; ++b) {
    q[b] = Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
    L[b] = 1e-7 * Vec3(u(rng), u(rng), u(rng));
    // A nine-sphere seed: principal moments about 1.2e-9, 1.6e-9 and 2.0e-9 kg m2.
    inv_inertia[b] = isotropic ? Vec3::Constant(1.0 / 1.6e-9) : Vec3(1.0 / 1.2e-9, 1.0 / 1.6e-9, 1.0 / 2.0e-9);
  }
  for (auto _ : state) {
    for (int b = 0; b < n; ++b) free_rotation_step(q[b], L[b], inv_inertia[b], isotropic, 1e-6);
    benchmark::DoNotOptimize(q.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * n);
}
BENCHMARK(BM_FreeRotation)->ArgName("isotropic")->Arg(0)->Arg(1);

}  // namespace
}  // namespace seedcal
