// `seedcal export STUDY_DIR --format liggghts|csv --out DIR`: the calibrated seed of a finished
// study (the chosen clump model, the materials and interactions with the calibrated values, the
// contact model) as a LIGGGHTS fragment and settling deck, or as CSV (docs/export.md). The work is
// in calibrate/export/.
#include <iostream>

#include "app/commands.hpp"
#include "calibrate/export/csv_export.hpp"
#include "calibrate/export/finished_study.hpp"
#include "calibrate/export/liggghts_deck.hpp"

namespace seedcal {

namespace {

struct ExportArgs {
  FinishedStudyOptions study;
  std::string format;
  std::string out;
  int count = 300;
};

}  // namespace

void add_export_command(CLI::App& app, GlobalOptions&) {
  auto a = std::make_shared<ExportArgs>();
  CLI::App* sub = app.add_subcommand(
      "export", "write a finished study's calibrated seed for another DEM code: a LIGGGHTS fragment and settling "
                "deck, or CSV");
  sub->add_option("study_dir", a->study.study_dir, "study directory (the --out of `seedcal calibrate`), finished")
      ->required();
  sub->add_option("--format", a->format,
                  "liggghts: DIR/in.seedcal_model (fragment) and DIR/in.settle (deck); csv: DIR/spheres.csv and "
                  "DIR/parameters.csv")
      ->required()
      ->check(CLI::IsMember({"liggghts", "csv"}));
  sub->add_option("--out", a->out, "output directory (created)")->required();
  sub->add_option("--study", a->study.study_file,
                  "the study file, when it is no longer where summary.json's provenance.study_file says");
  sub->add_option("--test", a->study.test,
                  "the study test whose scene gives the materials and contact model (default: the first target)");
  sub->add_option("--count", a->count, "the number of clumps in.settle pours unless told otherwise (default 300)")
      ->check(CLI::Range(1, 100000));
  sub->callback([a] {
    const ExportedModel m = read_finished_study(a->study);
    if (a->format == "liggghts") {
      write_liggghts_export(m, a->out, default_settle_deck(m, a->count));
      std::cout << a->out << "/in.seedcal_model\n" << a->out << "/in.settle\n";
    } else {
      write_csv_export(m, a->out);
      std::cout << a->out << "/spheres.csv\n" << a->out << "/parameters.csv\n";
    }
    std::cout << "(study \"" << m.study_name << "\", model \"" << m.model_name << "\", " << m.seeds.body.spheres.size()
              << " spheres; what does not carry over exactly is in each file's header)\n";
  });
}

}  // namespace seedcal
