#include "doe/io/csv_table.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "doe/core/errors.hpp"

namespace seedcal::doe {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"') {
      if (quoted && i + 1 < line.size() && line[i + 1] == '"') { cur += '"'; ++i; }
      else quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.push_back(trim(cur));
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(trim(cur));
  return out;
}

std::string where(const std::string& source, int line) { return source + ":" + std::to_string(line); }

}  // namespace

int CsvTable::find(const std::string& name) const {
  for (std::size_t j = 0; j < columns.size(); ++j)
    if (columns[j] == name) return static_cast<int>(j);
  return -1;
}

std::string CsvTable::column_list() const {
  std::string s;
  for (const auto& c : columns) {
    if (!s.empty()) s.append(", ");
    s.append(c);
  }
  return s;
}

int CsvTable::require(const std::string& name, const std::string& what) const {
  const int j = find(name);
  if (j < 0) throw DoeError(source + ": " + what + " " + name + ": no such column (columns: " + column_list() + ")");
  return j;
}

CsvTable parse_csv(const std::string& text, const std::string& source) {
  CsvTable t;
  t.source = source;
  std::istringstream in(text);
  std::string line;
  int lineno = 0;
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    ++lineno;
    if (trim(line).empty()) continue;
    const auto fields = split(line);
    if (t.columns.empty()) {
      t.columns = fields;
      for (std::size_t j = 0; j < fields.size(); ++j) {
        if (fields[j].empty()) throw DoeError(where(source, lineno) + ": header column " + std::to_string(j + 1) + " has no name");
        for (std::size_t k = 0; k < j; ++k)
          if (fields[k] == fields[j]) throw DoeError(where(source, lineno) + ": column " + fields[j] + ": named twice");
      }
      continue;
    }
    if (fields.size() != t.columns.size())
      throw DoeError(where(source, lineno) + ": " + std::to_string(fields.size()) + " fields, the header has " +
                     std::to_string(t.columns.size()));
    std::vector<double> r(fields.size());
    for (std::size_t j = 0; j < fields.size(); ++j) {
      const std::string& f = fields[j];
      const char* b = f.data();
      const char* e = b + f.size();
      if (!f.empty() && *b == '+') ++b;
      const auto res = std::from_chars(b, e, r[j]);
      if (f.empty() || res.ec != std::errc() || res.ptr != e || !std::isfinite(r[j]))
        throw DoeError(where(source, lineno) + ": column " + t.columns[j] + " = '" + f + "': not a finite number");
    }
    rows.push_back(std::move(r));
  }
  if (t.columns.empty()) throw DoeError(source + ": empty file (expected a header row of column names)");
  t.values.resize(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(t.columns.size()));
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < rows[i].size(); ++j) t.values(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = rows[i][j];
  return t;
}

CsvTable read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw DoeError(path + ": cannot open");
  std::stringstream s;
  s << in.rdbuf();
  return parse_csv(s.str(), path);
}

std::string format_csv(const std::vector<std::string>& columns, const Eigen::MatrixXd& values) {
  std::string out;
  for (std::size_t j = 0; j < columns.size(); ++j) {
    if (j) out.push_back(',');
    out.append(columns[j]);
  }
  out.push_back('\n');
  char buf[64];
  for (Eigen::Index i = 0; i < values.rows(); ++i) {
    for (Eigen::Index j = 0; j < values.cols(); ++j) {
      if (j) out.push_back(',');
      const auto r = std::to_chars(buf, buf + sizeof buf, values(i, j));
      out.append(buf, r.ptr);
    }
    out.push_back('\n');
  }
  return out;
}

}  // namespace seedcal::doe
