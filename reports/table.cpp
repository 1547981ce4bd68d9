#include "reports/table.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace seedcal::reports {

void Table::add_row(std::vector<std::string> cells) {
  if (cells.size() != columns.size())
    throw std::logic_error("table " + id + ": a row of " + std::to_string(cells.size()) + " cells for " +
                           std::to_string(columns.size()) + " columns");
  rows.push_back(std::move(cells));
}

std::string format_number(double v, int significant) {
  if (!std::isfinite(v)) return "n/a";
  if (v == 0.0) return "0";  // also -0
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", significant, v);
  return buf;
}

std::string format_value(const nlohmann::json& v, int significant) {
  if (v.is_null()) return "n/a";
  if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
  if (v.is_number_integer()) return v.dump();
  if (v.is_number()) return format_number(v.get<double>(), significant);
  if (v.is_string()) return v.get<std::string>();
  if (v.is_array()) {
    std::string out;
    for (const auto& x : v) out += std::string(out.empty() ? "" : ", ") + format_value(x, significant);
    return out;
  }
  return v.dump();
}

std::string format_percent(const nlohmann::json& fraction) {
  if (!fraction.is_number() || !std::isfinite(fraction.get<double>())) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%+.2f %%", 100.0 * fraction.get<double>());
  return buf;
}

double number_or_nan(const nlohmann::json& object, const std::string& key) {
  if (!object.is_object()) return std::numeric_limits<double>::quiet_NaN();
  const auto it = object.find(key);
  if (it == object.end() || !it->is_number()) return std::numeric_limits<double>::quiet_NaN();
  return it->get<double>();
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string to_csv(const Table& t) {
  std::string out;
  auto line = [&out](const std::vector<std::string>& cells) {
    for (std::size_t i = 0; i < cells.size(); ++i) out += std::string(i ? "," : "") + csv_field(cells[i]);
    out += "\n";
  };
  line(t.columns);
  for (const auto& r : t.rows) line(r);
  return out;
}

std::string file_stem(const std::string& text) {
  std::string out;
  for (char c : text) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
    out += ok ? c : '_';
  }
  return out.empty() ? "_" : out;
}

}  // namespace seedcal::reports
