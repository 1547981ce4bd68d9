#pragma once
// A numeric table read from / written to CSV (RFC 4180 subset): one header row of column names,
// then rows of numbers separated by commas; blank lines are skipped, fields are trimmed and may be
// double-quoted. Enough for designs and their responses; nothing DEM-specific.
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace seedcal::doe {

struct CsvTable {
  std::string source;                 // file name, for messages
  std::vector<std::string> columns;
  Eigen::MatrixXd values;             // rows x columns
  // Index of a column, or -1.
  int find(const std::string& name) const;
  // Index of a column; throws DoeError "SOURCE: column NAME: not found (columns: a, b, c)".
  int require(const std::string& name, const std::string& what = "column") const;
  std::string column_list() const;
};

// Throws DoeError with "FILE:LINE: column NAME = 'TEXT': not a number" and the like.
CsvTable read_csv(const std::string& path);
CsvTable parse_csv(const std::string& text, const std::string& source);

// Shortest round-trip representation of every number (std::to_chars).
std::string format_csv(const std::vector<std::string>& columns, const Eigen::MatrixXd& values);

}  // namespace seedcal::doe
