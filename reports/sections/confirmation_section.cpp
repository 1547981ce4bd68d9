// The optimiser and confirmation trace: per round, what the solver did on the refitted surrogate
// (solutions found, the rule, the prediction at the chosen point) and what the fresh DEM
// replicates at that point gave (mean, sd, relative error and its confidence interval against the
// tolerance), with a plot of the relative error per round.
#include <cmath>
#include <map>

#include "reports/sections/common.hpp"
#include "reports/sections/sections.hpp"

namespace seedcal::reports {

void add_confirmation_section(const StudyData& d, Document& doc) {
  const auto* c = d.stage("confirm");
  const int last = d.last_solve_round();
  if (!c && last == 0) return;
  Section s{"confirmation", "Optimiser and confirmation trace", {}};
  const auto factors = kept_factors(d);

  if (last > 0) {
    Table t{"solver_rounds", "Solve rounds: the surrogate solved for the target(s)",
            {"round", "surrogate", "target reached", "solutions found", "underdetermined", "rule", "predicted at the chosen point", "note"}, {}, {}};
    for (int r = 1; r <= last; ++r) {
      const auto* st = d.stage(std::string("solve_round_") + std::to_string(r));
      if (!st) continue;
      const auto sol = st->value("solution", nlohmann::json::object());
      std::string predicted;
      for (const auto& [name, v] : member(sol, "predicted").items()) predicted += std::string(predicted.empty() ? "" : ", ") + name + " " + format_value(v);
      t.add_row({std::to_string(r), sol.value("surrogate", std::string("n/a")), format_value(sol.value("found", nlohmann::json())),
                 sol.contains("multistart_solutions") ? std::to_string(sol["multistart_solutions"].size()) : "n/a",
                 format_value(sol.value("underdetermined", nlohmann::json())), sol.value("rule", std::string("n/a")), predicted,
                 sol.value("note", std::string())});
    }
    s.table(std::move(t));
  }
  if (!c) {
    s.note("The study stopped before confirmation");
    doc.sections.push_back(std::move(s));
    return;
  }
  const double tol = as_number(c->value("tolerance", nlohmann::json()));
  s.paragraph("Each round runs " + format_value(c->value("replicates", nlohmann::json())) +
              " fresh DEM replicates (unused seeds) at the chosen point; converged when every target's relative error is within +-" +
              format_percent(c->value("tolerance", nlohmann::json())).substr(1) +
              (c->value("hold_unless_significant", false)
                   ? ". While no target's interval excludes zero the point is kept and the next round's replicates join its pool (n counts them all); "
                     "a significant miss moves it (infill, refit, solve)"
                   : "") +
              ". Budget " +
              format_value(c->value("budget", nlohmann::json())) + " DEM runs; stopped: " + c->value("stop_reason", std::string("still running")) + ".");
  Table t{"confirmation_rounds", "Confirmation rounds", {"round"}, {}, {}};
  for (const auto& f : factors) t.columns.push_back(f);
  t.columns.insert(t.columns.end(), {"metric", "target", "n", "mean", "sd", "relative error", "CI low", "CI high", "confidence",
                                     "within tolerance", "resolved", "infill points after", "next"});
  std::map<std::string, std::vector<std::vector<double>>> series;  // metric -> (round, e, lo, hi) in %
  for (const auto& round : c->value("rounds", nlohmann::json::array())) {
    const int r = round.value("round", 0);
    const auto point = round.value("point", nlohmann::json::object());
    for (const auto& [metric, m] : member(round, "targets").items()) {
      std::vector<std::string> row{std::to_string(r)};
      for (const auto& f : factors) row.push_back(format_value(point.value(f, nlohmann::json())));
      const auto ci = m.value("rel_error_ci", nlohmann::json::array());
      row.insert(row.end(), {metric, format_value(m.value("target", nlohmann::json())), format_value(m.value("n", nlohmann::json())),
                             format_value(m.value("mean", nlohmann::json())), format_value(m.value("sd", nlohmann::json())),
                             format_percent(m.value("rel_error", nlohmann::json())), format_percent(ci.size() > 0 ? ci[0] : nlohmann::json()),
                             format_percent(ci.size() > 1 ? ci[1] : nlohmann::json()), format_value(m.value("confidence", nlohmann::json())),
                             format_value(m.value("within_tolerance", nlohmann::json())), format_value(m.value("resolved", nlohmann::json())),
                             round.contains("infill_points") ? std::to_string(round["infill_points"].size()) : "0",
                             round.value("next", std::string())});
      t.add_row(std::move(row));
      series[metric].push_back({static_cast<double>(r), 100.0 * as_number(m.value("rel_error", nlohmann::json())),
                                100.0 * as_number(ci.size() > 0 ? ci[0] : nlohmann::json()),
                                100.0 * as_number(ci.size() > 1 ? ci[1] : nlohmann::json())});
    }
  }
  s.table(std::move(t));
  if (!series.empty()) {
    GnuplotPlot p;
    std::string plots;
    int k = 0;
    const double shift = series.size() > 1 ? 0.08 : 0.0;
    for (auto& [metric, rows] : series) {
      for (auto& row : rows) row[0] += shift * (k - 0.5 * static_cast<double>(series.size() - 1));
      const std::string file = std::string("s") + std::to_string(k) + ".dat";
      p.add_data(file, rows);
      plots += std::string(plots.empty() ? "" : ", ") + gp_quote(file) + " using 1:2:3:4 with yerrorlines lw 2 pt 7 title " + gp_quote(metric);
      ++k;
    }
    int rounds = 0;
    for (const auto& [metric, rows] : series) rounds = std::max(rounds, static_cast<int>(rows.size()));
    p.script = "set title 'Relative error of the confirmed mean per round (bars: confidence interval)'\nset xlabel 'round'\n"
               "set ylabel 'relative error (%)'\nset xrange [0.5:" + std::to_string(rounds) + ".5]\nset xtics 1\nset grid\n"
               "set key outside right top vertical\n";
    if (std::isfinite(tol))
      plots += ", " + gp_number(100.0 * tol) + " with lines lw 1.5 dt 2 lc rgb '#d62728' title " + gp_quote("tolerance +-" + format_number(100.0 * tol) + " %") +
               ", " + gp_number(-100.0 * tol) + " with lines lw 1.5 dt 2 lc rgb '#d62728' notitle";
    p.script += "plot 0 with lines lc rgb '#999999' notitle, " + plots + "\n";
    add_plot(s, "confirmation_trace", "Confirmation trace: relative error of the mean of the fresh replicates per round, with its interval and the tolerance", p);
  }
  doc.sections.push_back(std::move(s));
}

}  // namespace seedcal::reports
