// Plots of the last solve round's surrogates: the fitted surface over the two leading kept factors
// (a filled contour map with the others held at the chosen point) with the target contour, the
// traced solution curve (or the multi-start solutions, projected), the DEM runs (projected) and
// the chosen point; for one kept factor, the fitted curve. And the leave-one-out check: each run's
// observed response against its prediction by the surrogate fitted without it.
#include <algorithm>
#include <cmath>

#include "reports/sections/common.hpp"
#include "reports/sections/sections.hpp"

namespace seedcal::reports {
namespace {

long index_of(const std::vector<std::string>& v, const std::string& x) {
  const auto it = std::find(v.begin(), v.end(), x);
  return it == v.end() ? -1 : static_cast<long>(it - v.begin());
}

// Rows (a, b) of the named pair of factors from a list of {factor: value} objects.
std::vector<std::vector<double>> pairs_of(const nlohmann::json& points, const std::string& a, const std::string& b) {
  std::vector<std::vector<double>> rows;
  if (!points.is_array()) return rows;
  for (const auto& p : points)
    if (p.is_object()) rows.push_back({as_number(p.value(a, nlohmann::json())), as_number(p.value(b, nlohmann::json()))});
  return rows;
}

// Column j of the data's natural rows.
std::vector<double> column(const nlohmann::json& rows, long j) {
  std::vector<double> out;
  for (const auto& r : rows) out.push_back(j >= 0 && static_cast<std::size_t>(j) < r.size() ? as_number(r[static_cast<std::size_t>(j)]) : NAN);
  return out;
}

void contour_plot(const nlohmann::json& grid, const nlohmann::json& tg, const nlohmann::json& fit, const nlohmann::json& solution,
                  const std::vector<std::string>& factors, bool single_target, Section& s, const std::string& suffix) {
  const auto gf = strings_of(grid["factors"]);
  const auto& xs = grid["x"];
  const auto& ys = grid["y"];
  const auto& z = tg["z"];
  const std::string name = tg.value("name", std::string("?"));
  const double target = as_number(tg.value("target", nlohmann::json()));
  std::string text;
  for (std::size_t j = 0; j < ys.size() && j < z.size(); ++j) {
    for (std::size_t i = 0; i < xs.size() && i < z[j].size(); ++i) {
      const double zz = as_number(z[j][i]);
      if (!std::isfinite(zz)) continue;
      text += gp_number(as_number(xs[i])) + " " + gp_number(as_number(ys[j])) + " " + gp_number(zz) + "\n";
    }
    text += "\n";
  }
  GnuplotPlot p;
  p.width = 760;
  p.height = 560;
  p.data.emplace_back("grid.dat", text);
  p.data.emplace_back("target.dat", "");  // rewritten by the target contour when there is one
  const auto& natural = fit.value("data", nlohmann::json::object()).value("natural", nlohmann::json::array());
  const auto xa = column(natural, index_of(factors, gf[0])), xb = column(natural, index_of(factors, gf[1]));
  std::vector<std::vector<double>> data_rows;
  for (std::size_t i = 0; i < xa.size(); ++i) data_rows.push_back({xa[i], xb[i]});
  p.add_data("data.dat", data_rows);
  const bool curve = single_target && solution.contains("curve") && factors.size() == 2;
  p.add_data("curve.dat", curve ? pairs_of(solution["curve"], gf[0], gf[1]) : std::vector<std::vector<double>>{});
  p.add_data("solutions.dat", single_target && !curve ? pairs_of(solution.value("multistart_solutions", nlohmann::json::array()), gf[0], gf[1])
                                                      : std::vector<std::vector<double>>{});
  p.add_data("chosen.dat", pairs_of(nlohmann::json::array({solution.value("chosen", nlohmann::json::object())}), gf[0], gf[1]));
  std::string held;
  for (const auto& [f, v] : member(grid, "held").items()) held += std::string(held.empty() ? "" : ", ") + f + " = " + format_value(v);
  p.script = "set title " + gp_quote(name + ": " + tg.value("surrogate", std::string("surrogate")) + " surface" +
                                     (held.empty() ? std::string() : " (" + held + ")")) +
             "\nset xlabel " + gp_quote(gf[0]) + "\nset ylabel " + gp_quote(gf[1]) + "\nset cblabel " + gp_quote(name) + " offset 1.5,0" +
             "\nset xrange [" + gp_number(as_number(xs.front())) + ":" + gp_number(as_number(xs.back())) + "]\nset yrange [" +
             gp_number(as_number(ys.front())) + ":" + gp_number(as_number(ys.back())) + "]\n" +
             "set palette cubehelix start 0.5 cycles -1.2 saturation 1.0\nset view map\nunset surface\nset contour base\n"
             "set cntrparam levels auto 8\nset table 'levels.dat'\nsplot 'grid.dat' using 1:2:3 with lines notitle\nunset table\n";
  if (std::isfinite(target))
    p.script += "set cntrparam levels discrete " + gp_number(target) +
                "\nset table 'target.dat'\nsplot 'grid.dat' using 1:2:3 with lines notitle\nunset table\n";
  p.script += "unset contour\nset bmargin 7\nset key at screen 0.5, screen 0.01 center bottom horizontal box opaque\n"
              "plot 'grid.dat' using 1:2:3 with image notitle, "
              "'levels.dat' using 1:2 with lines lw 0.6 lc rgb '#555555' notitle, "
              "'target.dat' using 1:2 with lines lw 3 lc rgb '#000000' title " + gp_quote("surrogate = target " + format_number(target)) + ", " +
              (curve ? "'curve.dat' using 1:2 with points pt 7 ps 0.6 lc rgb '#d62728' title 'traced solution curve', "
                     : "'solutions.dat' using 1:2 with points pt 6 ps 1.2 lc rgb '#d62728' title 'multi-start solutions (projected)', ") +
              "'data.dat' using 1:2 with points pt 5 ps 1.2 lc rgb '#ffffff' notitle, "
              "'data.dat' using 1:2 with points pt 4 ps 1.2 lw 1.5 lc rgb '#000000' title " +
              gp_quote(factors.size() > 2 ? "DEM runs (projected)" : "DEM runs") + ", "
              "'chosen.dat' using 1:2 with points pt 3 ps 3 lw 3 lc rgb '#ff7f0e' title 'chosen point'\n";
  add_plot(s, "surface_contour" + suffix,
           "Fitted surface of " + name + " over " + gf[0] + " and " + gf[1] +
               (held.empty() ? std::string() : ", the other kept factors at the chosen point"),
           p);
}

void profile_plot(const nlohmann::json& grid, const nlohmann::json& tg, const nlohmann::json& fit, const nlohmann::json& solution,
                  Section& s, const std::string& suffix) {
  const std::string f = strings_of(grid["factors"]).front(), name = tg.value("name", std::string("?"));
  std::vector<std::vector<double>> curve;
  for (std::size_t i = 0; i < grid["x"].size() && i < tg["z"].size(); ++i) curve.push_back({as_number(grid["x"][i]), as_number(tg["z"][i])});
  const auto data = fit.value("data", nlohmann::json::object());
  const auto xs = column(data.value("natural", nlohmann::json::array()), 0);
  const auto& obs = data.value("observed", nlohmann::json::array());
  std::vector<std::vector<double>> runs;
  for (std::size_t i = 0; i < xs.size() && i < obs.size(); ++i) runs.push_back({xs[i], as_number(obs[i])});
  GnuplotPlot p;
  p.add_data("curve.dat", curve);
  p.add_data("runs.dat", runs);
  const double chosen = as_number(solution.value("chosen", nlohmann::json::object()).value(f, nlohmann::json()));
  const double target = as_number(tg.value("target", nlohmann::json()));
  p.script = "set title " + gp_quote(name + ": " + tg.value("surrogate", std::string("surrogate")) + " fit") + "\nset xlabel " +
             gp_quote(f) + "\nset ylabel " + gp_quote(name) + "\nset grid\nset key outside right top vertical\n";
  if (std::isfinite(chosen))
    p.script += "set arrow 1 from " + gp_number(chosen) + ", graph 0 to " + gp_number(chosen) + ", graph 1 nohead lw 2 lc rgb '#ff7f0e'\n";
  p.script += "plot 'curve.dat' using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'surrogate', 'runs.dat' using 1:2 with points pt 7 "
              "lc rgb '#333333' title 'DEM runs'" +
              (std::isfinite(target) ? ", " + gp_number(target) + " with lines lw 2 dt 2 lc rgb '#d62728' title 'target'" : std::string()) +
              ", NaN with lines lw 2 lc rgb '#ff7f0e' title 'chosen value'\n";
  add_plot(s, "surface_profile" + suffix, "Fitted surrogate of " + name + " against " + f + " with the target and the chosen value", p);
}

void loo_section(const StudyData& d, const nlohmann::json& st, int round, Document& doc) {
  Section s{"cross-validation", "Leave-one-out cross-validation", {}};
  const auto factors = strings_of(st.value("factors", nlohmann::json::array()));
  const auto names = target_names(d);
  const auto& targets = st.value("targets", nlohmann::json::array());
  for (std::size_t ti = 0; ti < targets.size(); ++ti) {
    const auto& t = targets[ti];
    const std::string name = t.value("name", std::string("?")), suffix = target_suffix(names, ti);
    if (!t.contains("data")) {
      s.note(needs_newer_store("the leave-one-out predictions of " + name));
      continue;
    }
    const auto& obs = t["data"].value("observed", nlohmann::json::array());
    const auto& nat = t["data"].value("natural", nlohmann::json::array());
    const auto gp = t.value("gp", nlohmann::json::object()).value("loo_predicted", nlohmann::json::array());
    const auto quad = t.value("quadratic", nlohmann::json::object()).value("loo_predicted", nlohmann::json::array());
    Table tab{"loo_predictions" + suffix, "Leave-one-out predictions of " + name + " (round " + std::to_string(round) + ")", {"run"}, {}, {}};
    for (const auto& f : factors) tab.columns.push_back(f);
    tab.columns.insert(tab.columns.end(), {"observed", "GP LOO prediction", "quadratic LOO prediction"});
    std::vector<std::vector<double>> gp_rows, quad_rows;
    double lo = INFINITY, hi = -INFINITY;
    for (std::size_t i = 0; i < obs.size(); ++i) {
      std::vector<std::string> row{std::to_string(i + 1)};
      for (std::size_t j = 0; j < factors.size(); ++j) row.push_back(i < nat.size() && j < nat[i].size() ? format_value(nat[i][j]) : "n/a");
      const double y = as_number(obs[i]), g = i < gp.size() ? as_number(gp[i]) : NAN, q = i < quad.size() ? as_number(quad[i]) : NAN;
      row.insert(row.end(), {format_number(y), format_number(g), format_number(q)});
      tab.add_row(std::move(row));
      gp_rows.push_back({y, g});
      quad_rows.push_back({y, q});
      for (double v : {y, g, q})
        if (std::isfinite(v)) { lo = std::min(lo, v); hi = std::max(hi, v); }
    }
    s.table(std::move(tab));
    if (!std::isfinite(lo)) continue;
    const double pad = 0.05 * std::max(hi - lo, 1e-12 * std::max(std::fabs(hi), 1.0));
    GnuplotPlot p;
    p.width = 560;
    p.height = 520;
    p.add_data("gp.dat", gp_rows);
    p.add_data("quad.dat", quad_rows);
    p.script = "set title " + gp_quote(name + ": leave-one-out predicted against observed") + "\nset xlabel " +
               gp_quote("observed " + name) + "\nset ylabel " + gp_quote("predicted without that run") + "\nset xrange [" +
               gp_number(lo - pad) + ":" + gp_number(hi + pad) + "]\nset yrange [" + gp_number(lo - pad) + ":" + gp_number(hi + pad) +
               "]\nset size ratio -1\nset grid\nset key top left box opaque\n"
               "plot x with lines lc rgb '#999999' dt 2 title 'predicted = observed', "
               "'gp.dat' using 1:2 with points pt 7 ps 1.1 lc rgb '#1f77b4' title " +
               gp_quote("Gaussian process (LOO RMSE " + format_value(t.value("gp", nlohmann::json::object()).value("loo_rmse", nlohmann::json())) + ")") +
               ", 'quad.dat' using 1:2 with points pt 4 ps 1.1 lw 1.5 lc rgb '#d62728' title " +
               gp_quote("quadratic (LOO RMSE " + format_value(t.value("quadratic", nlohmann::json::object()).value("loo_rmse", nlohmann::json())) + ")") + "\n";
    add_plot(s, "gp_loo" + suffix, "Leave-one-out cross-validation of the surrogates of " + name + " (round " + std::to_string(round) + ")", p);
  }
  doc.sections.push_back(std::move(s));
}

}  // namespace

void add_surface_plot_sections(const StudyData& d, Document& doc) {
  const int last = d.last_solve_round();
  if (last == 0) return;
  const auto& st = *d.stage(std::string("solve_round_") + std::to_string(last));
  Section s{"surface-plot", "Fitted surface, target contour and solution", {}};
  const auto factors = strings_of(st.value("factors", nlohmann::json::array()));
  const auto names = target_names(d);
  const auto& solution = st.value("solution", nlohmann::json::object());
  if (!st.contains("surface_grid")) {
    s.note(needs_newer_store("the contour plot (a prediction grid of the surrogate)"));
  } else {
    const auto& grid = st["surface_grid"];
    const auto gf = strings_of(grid.value("factors", nlohmann::json::array()));
    const auto& fits = st.value("targets", nlohmann::json::array());
    const auto& tgs = grid.value("targets", nlohmann::json::array());
    s.paragraph("Solution rule: " + solution.value("rule", std::string("n/a")) + ". " +
                (solution.value("underdetermined", false) ? "The targets do not determine every kept factor: the solutions form a set, "
                                                            "from which the rule picks one. " : "") +
                solution.value("note", std::string()));
    for (std::size_t ti = 0; ti < tgs.size(); ++ti) {
      const auto& fit = ti < fits.size() ? fits[ti] : nlohmann::json::object();
      if (gf.size() >= 2 && grid.contains("y")) contour_plot(grid, tgs[ti], fit, solution, factors, tgs.size() == 1, s, target_suffix(names, ti));
      else if (gf.size() == 1) profile_plot(grid, tgs[ti], fit, solution, s, target_suffix(names, ti));
    }
  }
  doc.sections.push_back(std::move(s));
  loo_section(d, st, last, doc);
}

}  // namespace seedcal::reports
