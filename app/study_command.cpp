// `seedcal study multicontact|stiffness|moisture --out DIR`: the paper's section 4 studies
// (calibrate/studies/paper_studies.hpp, docs/studies.md), `seedcal study tradeoff`: speed
// against accuracy of one scene (calibrate/studies/tradeoff_study.hpp), and `seedcal study trend`:
// an index against one setting, checked in pooled sd (calibrate/studies/trend_study.hpp). Writes DIR/KIND.json
// (with seed, options and version) and DIR/KIND.csv, prints the JSON, and renders DIR/report.html
// and report.md of every study in DIR (reports/studies_report.hpp).
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>

#include <unistd.h>

#include "app/commands.hpp"
#include "app/executors/mpi_executor.hpp"
#include "calibrate/studies/paper_studies.hpp"
#include "calibrate/studies/tradeoff_study.hpp"
#include "calibrate/studies/trend_study.hpp"
#include "reports/studies_report.hpp"
#include "store/atomic_file.hpp"
#include "store/errors.hpp"

namespace seedcal {
namespace {

// --dry-run and --quiet of every DEM study.
struct PlanFlags {
  bool dry_run = false;
  bool quiet = false;
};

void add_plan_flags(CLI::App* sub, PlanFlags& f) {
  sub->add_flag("--dry-run", f.dry_run, "print the planned DEM runs and their CPU time on this machine, and run nothing");
  sub->add_flag("--quiet", f.quiet, "no progress line on the terminal");
}

// Prices the study's runs and says so before the first one: on stdout for a dry run (then returns
// null: nothing is to run), else on stderr, and returns the progress line the study reports to.
std::unique_ptr<StudyProgress> start_study(const std::string& kind, const std::vector<PlannedRuns>& plan, int threads,
                                           int slots, const PlanFlags& f) {
  const StudyPlanEstimate e = estimate_study_plan(plan, threads);
  for (const std::string& line : describe_study_plan(kind, e, slots))
    (f.dry_run ? std::cout : std::cerr) << (f.dry_run ? "" : "seedcal: ") << line << "\n";
  if (f.dry_run) return nullptr;
  return std::make_unique<StudyProgress>(kind, e, slots, !f.quiet && ::isatty(STDERR_FILENO));
}

struct StudyArgs {
  PlanFlags plan;
  PaperStudyOptions o;
  std::string out = "out/study";
  std::string variety = "jinong1";
  bool drum = false;
};

struct TradeoffArgs {
  PlanFlags plan;
  TradeoffOptions o;
  std::string out = "out/tradeoff";
};

struct TrendArgs {
  PlanFlags plan;
  TrendOptions o;
  std::string out = "out/trend";
};

// KIND.json and KIND.csv, then the report of every study in the directory.
void write_study(const std::string& kind, const nlohmann::json& j, const std::string& csv, const std::string& out) {
  std::filesystem::create_directories(out);
  write_json_atomic(out + "/" + kind + ".json", j);
  write_file_atomic(out + "/" + kind + ".csv", csv);
  std::cout << j.dump(2) << "\n";
  reports::render_studies_report(out);
}

void finish(const std::string& kind, nlohmann::json j, const StudyArgs& a, const GlobalOptions& g) {
  j["provenance"] = {{"seedcal_version", version_string()}, {"seed", g.seed}, {"threads", a.o.threads},
                     {"variety", a.variety}};
  write_study(kind, j, study_csv(j), a.out);
}

void check_file(const std::string& option, const std::string& path) {
  if (!std::filesystem::exists(path)) throw InputError(option + " = " + path + ": no such file");
}

// Options every DEM study shares, resolved when its command runs.
void prepare(StudyArgs& a, const GlobalOptions& g) {
  refuse_several_tasks("seedcal study");
  a.o.threads = g.resolved_threads();
  a.o.seed = g.seed;
  a.o.out_dir = a.out;
  check_file("--free-drop", a.o.free_drop_scene);
}

void add_dem_options(CLI::App* sub, StudyArgs& a) {
  sub->add_option("--free-drop", a.o.free_drop_scene, "free_drop scene file")->capture_default_str();
  sub->add_option("--set", a.o.sets, "override for every scene: key=value (e.g. particle.clump_file=...)");
  sub->add_option("--repeats", a.o.repeats, "free-drop repeats (seeds)")->check(CLI::Range(1, 1000))->capture_default_str();
  sub->add_option("--out", a.out, "output directory")->capture_default_str();
  add_plan_flags(sub, a.plan);
}

}  // namespace

void add_study_command(CLI::App& app, GlobalOptions& g) {
  auto a = std::make_shared<StudyArgs>();
  a->o.free_drop_scene = "data/scenes/jinong1/free_drop.toml";
  a->o.drum_scene = "data/scenes/jinong1/drum.toml";
  // The paper's section 4 model: Jinong 1, automatic filling at smoothness 2 (188 spheres in EDEM).
  a->o.sets = {"particle.model=auto-s2"};  // data/varieties/jinong1.toml [models]
  CLI::App* sub = app.add_subcommand("study", "the paper's section 4 studies (multicontact, stiffness, moisture) the speed-accuracy tradeoff and scene trend checks");
  sub->require_subcommand(1);

  CLI::App* mc = sub->add_subcommand("multicontact", "HM vs HMNR: free drop (10 repeats) and, with --drum, the drum at 5 rpm");
  add_dem_options(mc, *a);
  mc->add_flag("--drum", a->drum, "also run the drum scene under both models (long: minutes to hours)");
  mc->add_option("--drum-scene", a->o.drum_scene, "drum scene file")->capture_default_str();
  mc->add_option("--drum-repeats", a->o.drum_repeats, "drum runs per model")->check(CLI::Range(1, 100))->capture_default_str();
  add_common_options(*mc, g);
  mc->callback([a, &g] {
    prepare(*a, g);
    if (!a->drum) a->o.drum_scene.clear();
    else check_file("--drum-scene", a->o.drum_scene);
    const auto progress = start_study("multicontact", multicontact_plan(a->o), a->o.threads, 1, a->plan);
    if (!progress) return;
    a->o.progress = progress.get();
    auto j = multicontact_study(a->o);
    progress->clear();
    finish("multicontact", j, *a, g);
  });

  CLI::App* st = sub->add_subcommand("stiffness", "free drop under HMNR at several Young's moduli: contact points and rebound");
  add_dem_options(st, *a);
  st->add_option("--youngs-modulus-pa", a->o.youngs_moduli_pa, "seed Young's moduli, Pa")
      ->check(CLI::Range(1e3, 1e12))->capture_default_str();
  add_common_options(*st, g);
  st->callback([a, &g] {
    prepare(*a, g);
    const auto progress = start_study("stiffness", stiffness_plan(a->o), a->o.threads, 1, a->plan);
    if (!progress) return;
    a->o.progress = progress.get();
    auto j = stiffness_study(a->o);
    progress->clear();
    finish("stiffness", j, *a, g);
  });

  auto t = std::make_shared<TradeoffArgs>();
  t->o.scene = "data/scenes/jinong1/bulk_density.toml";
  t->o.sets = {"fidelity=quick"};
  CLI::App* tr = sub->add_subcommand("tradeoff", "speed against accuracy: one scene's index at several time-step "
                                                 "fractions and Young's moduli, with CPU seconds");
  tr->add_option("--scene", t->o.scene, "scene file")->capture_default_str();
  tr->add_option("--metric", t->o.metric, "index key of metrics.json (default: the scene's index)");
  tr->add_option("--set", t->o.sets, "override for every row: key=value")->capture_default_str();
  tr->add_option("--rayleigh-fractions", t->o.rayleigh_fractions, "time-step fractions of the Rayleigh step")
      ->check(CLI::Range(1e-4, 1.0))->capture_default_str();
  tr->add_option("--youngs-modulus-pa", t->o.youngs_moduli_pa, "Young's moduli of --material, Pa")
      ->check(CLI::Range(1e3, 1e12))->capture_default_str();
  tr->add_option("--material", t->o.material, "material whose Young's modulus is swept")->capture_default_str();
  tr->add_option("--tolerance", t->o.tolerance, "relative change of the index a user accepts")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  tr->add_option("--repeats", t->o.repeats, "seeds per row")->check(CLI::Range(1, 1000))->capture_default_str();
  tr->add_option("--out", t->out, "output directory")->capture_default_str();
  tr->add_option("--jobs", t->o.jobs, "a row's repeats at once, one thread each (default 1)")
      ->check(CLI::Range(1, 1000))->capture_default_str();
  add_plan_flags(tr, t->plan);
  add_common_options(*tr, g);
  tr->callback([t, &g] {
    refuse_several_tasks("seedcal study");  // several tasks would each run it whole
    t->o.threads = g.threads_per_job(t->o.jobs);
    t->o.seed = g.seed;
    t->o.out_dir = t->out;
    check_file("--scene", t->o.scene);
    const auto progress = start_study("tradeoff", tradeoff_plan(t->o), t->o.threads, t->o.jobs, t->plan);
    if (!progress) return;
    t->o.progress = progress.get();
    auto j = tradeoff_study(t->o);
    progress->clear();
    j["provenance"] = {{"seedcal_version", version_string()}, {"seed", g.seed}, {"threads", t->o.threads},
                       {"jobs", t->o.jobs}};
    write_study("tradeoff", j, tradeoff_csv(j), t->out);
  });

  auto tn = std::make_shared<TrendArgs>();
  CLI::App* te = sub->add_subcommand("trend", "does a scene's index rise (or fall) with one setting, by more than "
                                              "--sd-multiple pooled sd, over the same seeds at every level");
  te->add_option("--scene", tn->o.scene, "scene file")->required();
  te->add_option("--vary", tn->o.key, "dotted TOML path that changes (e.g. seed_seed.static_friction)")->required();
  te->add_option("--levels", tn->o.levels, "its values, in the order the trend is read")->required()->expected(2, 100);
  te->add_option("--expect", tn->o.expect, "rise or fall along --levels")->check(CLI::IsMember({"rise", "fall"}))->capture_default_str();
  te->add_option("--metric", tn->o.metric, "index key of metrics.json (default: the scene's index)");
  te->add_option("--set", tn->o.sets, "override for every level: key=value");
  te->add_option("--repeats", tn->o.repeats, "seeds per level")->check(CLI::Range(2, 1000))->capture_default_str();
  te->add_option("--sd-multiple", tn->o.sd_multiple, "required change, in pooled sd")->check(CLI::Range(0.0, 100.0))->capture_default_str();
  te->add_option("--out", tn->out, "output directory")->capture_default_str();
  te->add_option("--jobs", tn->o.jobs, "simulations at once, one thread each (default 1)")
      ->check(CLI::Range(1, 1000))->capture_default_str();
  add_plan_flags(te, tn->plan);
  add_common_options(*te, g);
  te->callback([tn, &g] {
    refuse_several_tasks("seedcal study");  // several tasks would each run it whole
    tn->o.threads = g.threads_per_job(tn->o.jobs);
    tn->o.seed = g.seed;
    tn->o.out_dir = tn->out;
    check_file("--scene", tn->o.scene);
    const auto progress = start_study("trend", trend_plan(tn->o), tn->o.threads, tn->o.jobs, tn->plan);
    if (!progress) return;
    tn->o.progress = progress.get();
    auto j = trend_study(tn->o);
    progress->clear();
    j["provenance"] = {{"seedcal_version", version_string()}, {"seed", g.seed}, {"threads", tn->o.threads},
                       {"jobs", tn->o.jobs}};
    std::cerr << j["verdict"].get<std::string>() << "\n";
    write_study("trend", j, trend_csv(j), tn->out);
  });

  CLI::App* mo = sub->add_subcommand("moisture", "Young's modulus against moisture and the dimensions after soaking");
  mo->add_option("--variety", a->variety, "variety name (data/varieties/NAME.toml) or file")->capture_default_str();
  mo->add_option("--out", a->out, "output directory")->capture_default_str();
  add_common_options(*mo, g);
  mo->callback([a, &g] { finish("moisture", moisture_study(a->variety), *a, g); });
}

}  // namespace seedcal
