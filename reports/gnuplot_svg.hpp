#pragma once
// Plots as SVG drawn by gnuplot (Debian gnuplot-nox, svg terminal) run as a child process: the
// script and its data files go to a fresh temporary directory, gnuplot runs there with its default
// settings (-d: no ~/.gnuplot), and the SVG it writes is returned as text. No network, no fonts
// embedded, no JavaScript (the terminal's "mouse" option is never used).
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace seedcal::reports {

struct GnuplotPlot {
  int width = 720, height = 440;  // px
  std::string script;             // after the terminal and output lines; data files by name
  std::vector<std::pair<std::string, std::string>> data;  // file name -> content

  // Adds a data file of whitespace-separated rows; rows with a non-finite number are left out
  // (gnuplot would draw "nan" as a gap anyway, and no NaN reaches a report).
  void add_data(const std::string& name, const std::vector<std::vector<double>>& rows);
};

// Runs gnuplot; throws std::runtime_error (with gnuplot's messages) when it cannot be started,
// fails, runs longer than 60 s or writes no SVG. The executable is $SEEDCAL_GNUPLOT when set,
// else `gnuplot` on PATH.
std::string render_gnuplot_svg(const GnuplotPlot& plot);

// A gnuplot single-quoted string literal ('it''s').
std::string gp_quote(std::string_view text);
// A double-quoted string column in a gnuplot data file (double quotes in the text become ').
std::string gp_data_string(std::string_view text);
// A number as gnuplot reads it back exactly ("%.17g"); callers keep NaN out.
std::string gp_number(double v);

}  // namespace seedcal::reports
