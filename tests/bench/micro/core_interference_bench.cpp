// What two cores of this machine do to each other's memory traffic, with nothing shared: each
// thread reads and writes its own array (x <- 0.999999 x + 1e-9, one pass per iteration), from
// 256 KiB (second-level cache) to 16 MiB (memory), on one thread and on two at once.
// bytes_per_second is the machine's total (Google Benchmark sums it over the threads, against the
// wall time of a pass). Where two threads stream twice what one does, a pass that streams the
// bodies' records can scale with the threads; where they stream little more than one, it cannot,
// however the work is split. The solver's body pass and force
// reduction stream about 240-310 bytes a body and step (tests/bench/README.md).
#include <benchmark/benchmark.h>

#include <vector>

namespace {

void BM_PrivateStream(benchmark::State& state) {
  const auto bytes = static_cast<std::size_t>(state.range(0));
  std::vector<double> a(bytes / sizeof(double), 1.0);
  for (auto _ : state) {
    for (double& x : a) x = 0.999999 * x + 1e-9;
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(bytes));
}
BENCHMARK(BM_PrivateStream)
    ->RangeMultiplier(4)
    ->Range(256 << 10, 16 << 20)
    ->Threads(1)
    ->Threads(2)
    ->UseRealTime();

}  // namespace
