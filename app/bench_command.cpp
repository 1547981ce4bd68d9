// `seedcal bench settled-bed|clump-bed [--threads N]`: solver throughput on the peer-benchmark
// scenes (solver/scenes/bench_beds.hpp). Prints progress lines, then one JSON object on the last
// line of stdout.
#include <iostream>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "calibrate/clumps/clump_source.hpp"
#include "solver/scenes/bench_beds.hpp"
#include "store/errors.hpp"
#include "store/version.hpp"

namespace seedcal {

void add_bench_command(CLI::App& app, GlobalOptions& g) {
  struct Args {
    std::string name;
    std::string clump_file = "data/bench/clump9.txt";
    std::int64_t settle_steps = -1, timed_steps = 20000;
    int simd_lanes = 8;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("bench", "solver throughput on the peer-benchmark scenes");
  sub->add_option("name", a->name, "settled-bed or clump-bed")
      ->required()
      ->check(CLI::IsMember({"settled-bed", "clump-bed"}));
  sub->add_option("--clump-file", a->clump_file, "clump of the clump bed (x y z r per line)");
  sub->add_option("--settle-steps", a->settle_steps, "settling steps at 5e-6 s (default: the deck's)")
      ->check(CLI::Range(std::int64_t{0}, std::int64_t{10000000}));
  sub->add_option("--timed-steps", a->timed_steps, "timed steps at 1e-6 s (default 20000)")
      ->check(CLI::Range(std::int64_t{1}, std::int64_t{10000000}));
  sub->add_option("--simd-lanes", a->simd_lanes,
                  "widest contact kernel to use: 8 (AVX-512F), 4 (AVX2) or 1; the CPU may allow "
                  "fewer (default 8; every width gives the same bits)")
      ->check(CLI::IsMember({1, 4, 8}));
  add_common_options(*sub, g);
  sub->callback([a, &g] {
    BenchSpec spec;
    if (a->name == "settled-bed") {
      spec = settled_bed_spec();
    } else {
      auto diag = std::make_shared<ConfigDiagnostics>();
      diag->file = "--clump-file";
      toml::value empty = toml::table{};
      TomlReader reader(empty, "", diag);
      auto spheres = load_clump_spheres(a->clump_file, reader, "clump_file");
      diag->throw_if_any();
      for (const std::string& w : diag->warnings) std::cerr << "seedcal: warning: " << w << "\n";
      spec = clump_bed_spec(std::move(spheres));
    }
    if (a->settle_steps >= 0) spec.settle_steps = static_cast<std::uint64_t>(a->settle_steps);
    spec.timed_steps = static_cast<std::uint64_t>(a->timed_steps);
    spec.threads = g.resolved_threads();
    spec.seed = g.seed;
    spec.simd_lanes = a->simd_lanes;
    std::cout << "seedcal bench " << spec.name << ": " << spec.settle_steps << " settling steps, "
              << spec.timed_steps << " timed steps, " << spec.threads << " thread(s)" << std::endl;
    const BenchResult r = run_bench(spec);
    nlohmann::json j{{"bench", spec.name},
                     {"sphere_steps_per_second", r.sphere_steps_per_second},
                     {"spheres", r.spheres},
                     {"bodies", r.bodies},
                     {"steps", r.steps},
                     {"wall_seconds", r.wall_seconds},
                     {"settle_wall_seconds", r.settle_wall_seconds},
                     {"contacts_per_sphere", r.contacts_per_sphere},
                     {"neighbour_builds", r.neighbour_builds},
                     {"bodies_across_threads", r.bodies_across_threads},
                     {"threads", spec.threads},
                     {"kernel_lanes", r.kernel_lanes},
                     {"profile_s", {{"integrate", r.integrate_s}, {"neighbour", r.neighbour_s},
                                    {"contact", r.contact_s}, {"reduce", r.reduce_s}}},
                     {"contact_model", "hertz_mindlin + cdt (own spin)"},
                     {"seedcal_version", version_string()},
                     {"seed", spec.seed}};
    if (!r.failure.empty()) j["failure"] = r.failure;
    std::cout << j.dump() << std::endl;
    if (!r.failure.empty()) throw RunFailed("bench " + spec.name + ": " + r.failure);
  });
}

}  // namespace seedcal
