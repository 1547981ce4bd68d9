#pragma once
// A table of a report: caption, column names and rows of cell text, rendered as an HTML table, a
// Markdown table and a CSV file (report/<id>.csv). Numbers become text here, once, so the three
// renderings agree; a missing or non-finite number is "n/a", never "nan".
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace seedcal::reports {

struct Table {
  std::string id;        // file stem of the CSV (report/<id>.csv): letters, digits, '_' and '-'
  std::string caption;
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> notes;  // shown under the table (HTML, Markdown), not in the CSV

  // Appends a row; throws std::logic_error when its width differs from the columns'.
  void add_row(std::vector<std::string> cells);
};

// Six significant digits ("%.6g"); "n/a" when not finite.
std::string format_number(double v, int significant = 6);
// A JSON value as cell text: null and non-finite numbers "n/a", booleans "yes"/"no", integers
// exactly, other numbers as format_number, strings as they are, arrays "a, b", objects as JSON.
std::string format_value(const nlohmann::json& v, int significant = 6);
// Percent with two decimals and a sign ("-3.51 %"); "n/a" when not a finite number.
std::string format_percent(const nlohmann::json& fraction);

// The JSON number at `key` of an object, or NaN when absent, null or not a number.
double number_or_nan(const nlohmann::json& object, const std::string& key);

// RFC 4180: fields with a comma, quote, CR or LF are quoted, quotes doubled; CRLF-free output
// with one "\n" per record, the header first.
std::string to_csv(const Table& t);
std::string csv_field(const std::string& text);

// A file stem made of [A-Za-z0-9_-] from any text (others become '_').
std::string file_stem(const std::string& text);

}  // namespace seedcal::reports
