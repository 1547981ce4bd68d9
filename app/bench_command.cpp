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
    std::string clump_file;  // default: the scene's (clump9.txt, jinong1-auto-s2.toml)
    std::int64_t settle_steps = -1, timed_steps = 20000;
    int simd_lanes = 8;
    std::string pair_search = "auto";
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("bench", "solver throughput on the peer-benchmark scenes");
  sub->add_option("name", a->name, "settled-bed, clump-bed or fine-clump-bed")
      ->required()
      ->check(CLI::IsMember({"settled-bed", "clump-bed", "fine-clump-bed"}));
  sub->add_option("--clump-file", a->clump_file,
                  "clump of the clump beds (x y z r per line, or a seedcal clump file); default "
                  "data/bench/clump9.txt for clump-bed, data/clumps/jinong1-auto-s2.toml for fine-clump-bed");
  sub->add_option("--settle-steps", a->settle_steps, "settling steps (default: the deck's, at its settling time step)")
      ->check(CLI::Range(std::int64_t{0}, std::int64_t{10000000}));
  sub->add_option("--timed-steps", a->timed_steps, "timed steps at 1e-6 s (default 20000)")
      ->check(CLI::Range(std::int64_t{1}, std::int64_t{10000000}));
  sub->add_option("--simd-lanes", a->simd_lanes,
                  "widest contact kernel to use: 8 (AVX-512F), 4 (AVX2) or 1; the CPU may allow "
                  "fewer (default 8; every width gives the same bits)")
      ->check(CLI::IsMember({1, 4, 8}));
  sub->add_option("--pair-search", a->pair_search,
                  "how the neighbour list finds candidate pairs: auto (two levels when bodies hold many spheres), "
                  "spheres (one grid of spheres) or bodies (bodies first, then their spheres); the same list either "
                  "way (default auto)")
      ->check(CLI::IsMember({"auto", "spheres", "bodies"}));
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
      const bool fine = a->name == "fine-clump-bed";
      const std::string file = !a->clump_file.empty() ? a->clump_file
                               : fine                 ? "data/clumps/jinong1-auto-s2.toml"
                                                      : "data/bench/clump9.txt";
      auto spheres = load_clump_spheres(file, reader, "clump_file");
      diag->throw_if_any();
      for (const std::string& w : diag->warnings) std::cerr << "seedcal: warning: " << w << "\n";
      spec = fine ? fine_clump_bed_spec(std::move(spheres)) : clump_bed_spec(std::move(spheres));
    }
    if (a->settle_steps >= 0) spec.settle_steps = static_cast<std::uint64_t>(a->settle_steps);
    spec.timed_steps = static_cast<std::uint64_t>(a->timed_steps);
    spec.threads = g.resolved_threads();
    spec.seed = g.seed;
    spec.simd_lanes = a->simd_lanes;
    spec.pair_search = a->pair_search == "spheres" ? PairSearch::sphere_grid
                       : a->pair_search == "bodies" ? PairSearch::two_level
                                                    : PairSearch::automatic;
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
                     {"kinetic_energy_j", r.kinetic_energy_j},
                     {"neighbour_builds", r.neighbour_builds},
                     {"bodies_across_threads", r.bodies_across_threads},
                     {"threads", spec.threads},
                     {"kernel_lanes", r.kernel_lanes},
                     {"pair_search", a->pair_search},
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
