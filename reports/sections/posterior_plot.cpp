// The posterior of two calibrated parameters (/stages/posterior, calibrate/pipeline/posterior_stage.cpp):
// its density over the surrogate box as a map, the 95 % highest-density region's edge (the band
// around the solution curve of a single target), the traced solution curve of the last solve round,
// the chosen point and each parameter's 95 % credible interval.
#include <cmath>

#include "reports/sections/common.hpp"
#include "reports/sections/sections.hpp"

namespace seedcal::reports {

void add_posterior_plot_section(const StudyData& d, Document& doc) {
  const nlohmann::json* post = d.stage("posterior");
  if (!post || !post->contains("region_grid") || !(*post)["region_grid"].is_object()) return;
  const auto& g = (*post)["region_grid"];
  const auto& xs = g.value("x", nlohmann::json::array());
  const auto& ys = g.value("y", nlohmann::json::array());
  const auto& w = g.value("weight", nlohmann::json::array());
  const int n = static_cast<int>(std::lround(std::sqrt(static_cast<double>(w.size()))));
  if (n < 3 || static_cast<std::size_t>(n) * static_cast<std::size_t>(n) != w.size()) return;
  const auto& interval = member(*post, "calibrated_interval");
  // The grid's two factors in its own order (the kept factors'); an older store has none.
  const auto names = strings_of(g.value("factors", nlohmann::json::array()));
  if (names.size() != 2) return;
  const int last = d.last_solve_round();
  const nlohmann::json* round = last > 0 ? d.stage("solve_round_" + std::to_string(last)) : nullptr;
  // Rows of the grid: the first factor varies fastest (doe::posterior's grid).
  std::string text;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(n) + static_cast<std::size_t>(i);
      text += gp_number(as_number(xs[k])) + " " + gp_number(as_number(ys[k])) + " " + gp_number(as_number(w[k])) + "\n";
    }
    text += "\n";
  }
  GnuplotPlot p;
  p.width = 760;
  p.height = 560;
  p.data.emplace_back("density.dat", text);
  p.data.emplace_back("hpd.dat", "");
  std::vector<std::vector<double>> curve, chosen;
  if (round) {
    const auto& sol = round->value("solution", nlohmann::json::object());
    for (const auto& c : sol.value("curve", nlohmann::json::array()))
      curve.push_back({as_number(c.value(names[0], nlohmann::json())), as_number(c.value(names[1], nlohmann::json()))});
  }
  if (d.summary && d.summary->calibrated.count(names[0]) && d.summary->calibrated.count(names[1]))
    chosen.push_back({d.summary->calibrated.at(names[0]), d.summary->calibrated.at(names[1])});
  p.add_data("curve.dat", curve);
  p.add_data("chosen.dat", chosen);
  const double threshold = as_number(g.value("hpd95_threshold", nlohmann::json()));
  // The box: the grid's cell centres less and plus half a cell.
  const double dx = (as_number(xs[static_cast<std::size_t>(n - 1)]) - as_number(xs.front())) / (n - 1);
  const double dy = (as_number(ys.back()) - as_number(ys.front())) / (n - 1);
  const double x_lo = as_number(xs.front()) - 0.5 * dx, x_hi = as_number(xs[static_cast<std::size_t>(n - 1)]) + 0.5 * dx;
  const double y_lo = as_number(ys.front()) - 0.5 * dy, y_hi = as_number(ys.back()) + 0.5 * dy;
  std::string arrows;
  int a = 1;
  for (int q = 0; q < 2; ++q) {
    const auto& iv = member(interval, names[static_cast<std::size_t>(q)]);
    if (!iv.is_array() || iv.size() != 2) continue;
    for (const auto& e : iv) {
      const std::string v = gp_number(as_number(e));
      arrows += q == 0 ? "set arrow " + std::to_string(a++) + " from " + v + ", graph 0 to " + v + ", graph 1 nohead dt 2 lw 1.5 lc rgb '#1f77b4'\n"
                       : "set arrow " + std::to_string(a++) + " from graph 0, first " + v + " to graph 1, first " + v + " nohead dt 2 lw 1.5 lc rgb '#1f77b4'\n";
    }
  }
  p.script = "set title 'Posterior of the calibrated parameters over the surrogate box'\nset xlabel " + gp_quote(names[0]) +
             "\nset ylabel " + gp_quote(names[1]) + "\nset cblabel 'posterior weight' offset 1.5,0\n"
             "set xrange [" + gp_number(x_lo) + ":" + gp_number(x_hi) + "]\nset yrange [" + gp_number(y_lo) + ":" + gp_number(y_hi) + "]\n"
             "set rmargin 12\n"
             "set palette defined (0 '#ffffff', 1 '#9ecae1', 2 '#08306b')\nset view map\nunset surface\n";
  if (std::isfinite(threshold) && threshold > 0.0)
    p.script += "set contour base\nset cntrparam levels discrete " + gp_number(threshold) +
                "\nset table 'hpd.dat'\nsplot 'density.dat' using 1:2:3 with lines notitle\nunset table\nunset contour\n";
  p.script += arrows + "set bmargin 7\nset key at screen 0.5, screen 0.01 center bottom horizontal box opaque\n"
              "plot 'density.dat' using 1:2:3 with image notitle, "
              "'hpd.dat' using 1:2 with lines lw 2.5 lc rgb '#000000' title '95 % highest-density region', "
              "'curve.dat' using 1:2 with points pt 7 ps 0.6 lc rgb '#d62728' title 'solution curve of the surrogate', "
              "NaN with lines dt 2 lw 1.5 lc rgb '#1f77b4' title '95 % intervals', "
              "'chosen.dat' using 1:2 with points pt 3 ps 3 lw 3 lc rgb '#ff7f0e' title 'calibrated point'\n";
  Section s{"posterior", "Posterior of the calibrated parameters", {}};
  s.paragraph("Density of the parameters given the targets over the surrogate box (uniform prior; every target's GP with its "
              "run-to-run noise fixed, and the laboratory's sd where the study gives one; docs/calibrate.md, \"Posterior\"). "
              "A band that fills the box means the targets do not pin the parameters down within their scatter.");
  add_plot(s, "posterior_region", "Posterior density with its 95 % region, the solution curve and the calibrated point", p);
  doc.sections.push_back(std::move(s));
}

}  // namespace seedcal::reports
