#pragma once
// A design of experiments: runs x columns in coded units (-1 low, +1 high, 0 centre), the kind of
// each run, its standard order, and conversion to and from natural units.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace seedcal::doe {

enum class PointType { factorial, center, axial, edge, space_filling };
const char* to_string(PointType t);

// A factor and its natural range: coded -1 is `low`, +1 is `high`; x = (xi - centre) / half_range
// (Myers, Montgomery & Anderson-Cook, Response Surface Methodology, 3rd ed., sec. 2.8).
struct Factor {
  std::string name;
  double low = -1.0;
  double high = 1.0;
};

struct Design {
  std::vector<std::string> names;    // column names: the factors, then any dummy columns
  Eigen::MatrixXd coded;             // runs x columns
  std::vector<PointType> type;       // one per run
  std::vector<int> std_order;        // standard (unrandomised) order, 1-based, one per run
  int n_dummy = 0;                   // trailing columns that carry no factor (error estimate)

  int runs() const { return static_cast<int>(coded.rows()); }
  int columns() const { return static_cast<int>(coded.cols()); }
  int factors() const { return columns() - n_dummy; }
};

// Builds a Design from a coded matrix with default names x1..xk and standard order 1..n.
Design make_design(Eigen::MatrixXd coded, PointType type, int n_dummy = 0);

// Default factor names: x1, x2, ...; dummy columns: dummy1, dummy2, ...
std::vector<std::string> default_names(int factors, int dummies = 0);

// Appends n centre runs (all columns 0).
void add_center_points(Design& d, int n);

// Randomised run order with a seed: Fisher-Yates over a std::mt19937_64 stream (the engine's
// output is fixed by the standard, unlike std::shuffle's algorithm, so the order is portable).
void randomize_run_order(Design& d, std::uint64_t seed);

// Coded <-> natural for the first factors.size() columns (dummy columns are left coded).
Eigen::MatrixXd to_natural(const Eigen::MatrixXd& coded, const std::vector<Factor>& factors);
Eigen::MatrixXd to_coded(const Eigen::MatrixXd& natural, const std::vector<Factor>& factors);

// Throws DoeError unless every factor has a name and low < high.
void check_factors(const std::vector<Factor>& factors, int expected);

}  // namespace seedcal::doe
