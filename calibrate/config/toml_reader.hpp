#pragma once
// Typed, validated reading of a TOML config table. Every problem is collected (not only the first)
// and reported together as an InputError whose messages name the file, the line, the dotted key,
// the value and the allowed range, e.g.
//   data/scenes/jinong1/drum.toml:12: drum.fill_fraction = 1.4: must be in (0, 1)
// Keys a reader never asked for are reported as unknown, with a "did you mean" suggestion.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <toml.hpp>

#include "store/errors.hpp"

namespace seedcal {

// Allowed interval; open or closed at each end.
struct Range {
  double lo = -1e308, hi = 1e308;
  bool lo_open = false, hi_open = false;
  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
  static Range open(double lo, double hi) { return {lo, hi, true, true}; }
  static Range positive() { return {0.0, 1e308, true, false}; }
  static Range non_negative() { return {0.0, 1e308, false, false}; }
  static Range left_open(double lo, double hi) { return {lo, hi, true, false}; }
  bool contains(double v) const;
  std::string describe() const;
};

// Shared by all readers of one file: the problem list.
struct ConfigDiagnostics {
  std::string file;
  std::vector<std::string> problems;
  // What the config allows but the user should know (e.g. a clump with a buried sphere): said on
  // standard error and kept in metrics.json ("warnings"); never stops a run.
  std::vector<std::string> warnings;
  void add(const toml::value* where, const std::string& key, const std::string& message);
  void warn(const toml::value* where, const std::string& key, const std::string& message);
  void throw_if_any() const;
};

class TomlReader {
 public:
  // Parses a file; a syntax error becomes an InputError naming the file and line.
  static toml::value parse_file(const std::string& path);

  TomlReader(const toml::value& table, std::string path_prefix,
             std::shared_ptr<ConfigDiagnostics> diag);

  bool has(const std::string& key) const;
  double number(const std::string& key, Range range);                        // required
  double number(const std::string& key, Range range, double fallback);       // optional
  std::int64_t integer(const std::string& key, std::int64_t lo, std::int64_t hi);
  std::int64_t integer(const std::string& key, std::int64_t lo, std::int64_t hi, std::int64_t fallback);
  bool boolean(const std::string& key, bool fallback);
  std::string string(const std::string& key);
  std::string string(const std::string& key, const std::string& fallback);
  // One of a fixed set of words.
  std::string choice(const std::string& key, const std::vector<std::string>& allowed,
                     const std::string& fallback);
  std::string choice(const std::string& key, const std::vector<std::string>& allowed);
  // An array of strings with a length in [min_len, max_len].
  std::vector<std::string> strings(const std::string& key, std::size_t min_len, std::size_t max_len);
  // A vector of 3 numbers, each in `range`.
  std::optional<Eigen::Vector3d> vec3(const std::string& key, Range range, bool required);
  std::vector<double> numbers(const std::string& key, Range range, std::size_t min_len,
                              std::size_t max_len);
  std::vector<std::vector<double>> number_rows(const std::string& key, std::size_t row_len,
                                               std::size_t min_rows, std::size_t max_rows);

  // Sub-tables and arrays of tables.
  std::optional<TomlReader> table(const std::string& key);
  std::vector<TomlReader> table_array(const std::string& key);
  // Keys of a table whose entries are themselves tables ([materials.glass], ...).
  std::vector<std::string> keys() const;

  // Reports every key of this table that no call above asked for.
  void check_unknown_keys();
  void error(const std::string& key, const std::string& message);
  void warn(const std::string& key, const std::string& message);
  std::string full_key(const std::string& key) const;
  const std::string& prefix() const { return prefix_; }
  const toml::value& value() const { return *table_; }  // the table this reader reads
  ConfigDiagnostics& diagnostics() { return *diag_; }

 private:
  const toml::value* find(const std::string& key);
  std::string value_text(const toml::value& v) const;

  const toml::value* table_;
  std::string prefix_;
  std::shared_ptr<ConfigDiagnostics> diag_;
  std::set<std::string> used_;
};

// Closest candidate by edit distance, or "" when nothing is close.
std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace seedcal
