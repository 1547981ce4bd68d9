#include "calibrate/config/toml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace seedcal {

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (hi_open ? !(v < hi) : !(v <= hi)) return false;
  return true;
}

std::string Range::describe() const {
  std::ostringstream s;
  s.precision(6);
  if (hi >= 1e307) {
    s << "must be " << (lo_open ? "> " : ">= ") << lo;
  } else if (lo <= -1e307) {
    s << "must be " << (hi_open ? "< " : "<= ") << hi;
  } else {
    s << "must be in " << (lo_open ? "(" : "[") << lo << ", " << hi << (hi_open ? ")" : "]");
  }
  return s.str();
}

namespace {

std::string located(const std::string& file, const toml::value* where, const std::string& key,
                    const std::string& message) {
  std::ostringstream s;
  s << file;
  if (where) {
    const auto loc = where->location();
    if (loc.line() > 0) s << ":" << loc.line();
  }
  s << ": " << key << " " << message;
  return s.str();
}

}  // namespace

void ConfigDiagnostics::add(const toml::value* where, const std::string& key,
                            const std::string& message) {
  problems.push_back(located(file, where, key, message));
}

void ConfigDiagnostics::warn(const toml::value* where, const std::string& key,
                             const std::string& message) {
  warnings.push_back(located(file, where, key, message));
}

void ConfigDiagnostics::throw_if_any() const {
  if (!problems.empty()) throw InputError(problems);
}

toml::value TomlReader::parse_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the file (does it exist and is it readable?)");
  try {
    return toml::parse(in, path);
  } catch (const toml::syntax_error& e) {
    throw InputError(path + ": TOML syntax error:\n" + std::string(e.what()));
  } catch (const std::exception& e) {
    throw InputError(path + ": cannot parse: " + e.what());
  }
}

TomlReader::TomlReader(const toml::value& table, std::string path_prefix,
                       std::shared_ptr<ConfigDiagnostics> diag)
    : table_(&table), prefix_(std::move(path_prefix)), diag_(std::move(diag)) {}

std::string TomlReader::full_key(const std::string& key) const {
  return prefix_.empty() ? key : prefix_ + "." + key;
}

void TomlReader::error(const std::string& key, const std::string& message) {
  const toml::value* v = table_->is_table() && table_->contains(key) ? &table_->at(key) : table_;
  diag_->add(v, full_key(key), message);
}

void TomlReader::warn(const std::string& key, const std::string& message) {
  const toml::value* v = table_->is_table() && table_->contains(key) ? &table_->at(key) : table_;
  diag_->warn(v, full_key(key), message);
}

bool TomlReader::has(const std::string& key) const {
  return table_->is_table() && table_->contains(key);
}

const toml::value* TomlReader::find(const std::string& key) {
  used_.insert(key);
  if (!has(key)) return nullptr;
  return &table_->at(key);
}

std::string TomlReader::value_text(const toml::value& v) const {
  std::ostringstream s;
  if (v.is_string()) s << '"' << v.as_string().str << '"';
  else if (v.is_table()) s << "(a table)";
  else if (v.is_array()) s << "(an array of " << v.as_array().size() << ")";
  else s << v;
  return s.str();
}

static bool as_double(const toml::value& v, double& out) {
  if (v.is_floating()) { out = v.as_floating(); return true; }
  if (v.is_integer()) { out = static_cast<double>(v.as_integer()); return true; }
  return false;
}

double TomlReader::number(const std::string& key, Range range) {
  const toml::value* v = find(key);
  if (!v) { error(key, "is required (" + range.describe() + ")"); return std::nan(""); }
  double d = 0.0;
  if (!as_double(*v, d)) {
    diag_->add(v, full_key(key), "= " + value_text(*v) + ": must be a number; " + range.describe());
    return std::nan("");
  }
  if (!range.contains(d)) {
    std::ostringstream s;
    s.precision(10);
    s << "= " << d << ": " << range.describe();
    diag_->add(v, full_key(key), s.str());
  }
  return d;
}

double TomlReader::number(const std::string& key, Range range, double fallback) {
  if (!has(key)) { used_.insert(key); return fallback; }
  return number(key, range);
}

std::int64_t TomlReader::integer(const std::string& key, std::int64_t lo, std::int64_t hi) {
  const toml::value* v = find(key);
  const std::string rng = "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (!v) { error(key, "is required (" + rng + ")"); return lo; }
  if (!v->is_integer()) { diag_->add(v, full_key(key), "= " + value_text(*v) + ": " + rng); return lo; }
  const std::int64_t i = v->as_integer();
  if (i < lo || i > hi) diag_->add(v, full_key(key), "= " + std::to_string(i) + ": " + rng);
  return i;
}

std::int64_t TomlReader::integer(const std::string& key, std::int64_t lo, std::int64_t hi,
                                 std::int64_t fallback) {
  if (!has(key)) { used_.insert(key); return fallback; }
  return integer(key, lo, hi);
}

bool TomlReader::boolean(const std::string& key, bool fallback) {
  const toml::value* v = find(key);
  if (!v) return fallback;
  if (!v->is_boolean()) {
    diag_->add(v, full_key(key), "= " + value_text(*v) + ": must be true or false");
    return fallback;
  }
  return v->as_boolean();
}

std::string TomlReader::string(const std::string& key) {
  const toml::value* v = find(key);
  if (!v) { error(key, "is required (a string)"); return {}; }
  if (!v->is_string()) { diag_->add(v, full_key(key), "= " + value_text(*v) + ": must be a string"); return {}; }
  return v->as_string().str;
}

std::string TomlReader::string(const std::string& key, const std::string& fallback) {
  if (!has(key)) { used_.insert(key); return fallback; }
  return string(key);
}

static std::string join(const std::vector<std::string>& words) {
  std::string s;
  for (std::size_t i = 0; i < words.size(); ++i) s += (i ? ", " : "") + ("\"" + words[i] + "\"");
  return s;
}

std::string TomlReader::choice(const std::string& key, const std::vector<std::string>& allowed,
                               const std::string& fallback) {
  if (!has(key)) { used_.insert(key); return fallback; }
  return choice(key, allowed);
}

std::string TomlReader::choice(const std::string& key, const std::vector<std::string>& allowed) {
  const std::string s = string(key);
  if (has(key) && table_->at(key).is_string() &&
      std::find(allowed.begin(), allowed.end(), s) == allowed.end()) {
    std::string msg = "= \"" + s + "\": must be one of " + join(allowed);
    const std::string hint = did_you_mean(s, allowed);
    if (!hint.empty()) msg += " (did you mean \"" + hint + "\"?)";
    diag_->add(&table_->at(key), full_key(key), msg);
  }
  return s;
}

std::optional<Eigen::Vector3d> TomlReader::vec3(const std::string& key, Range range, bool required) {
  const toml::value* v = find(key);
  if (!v) {
    if (required) error(key, "is required (an array of 3 numbers)");
    return std::nullopt;
  }
  const auto xs = numbers(key, range, 3, 3);
  if (xs.size() != 3) return std::nullopt;
  return Eigen::Vector3d(xs[0], xs[1], xs[2]);
}

std::vector<double> TomlReader::numbers(const std::string& key, Range range, std::size_t min_len,
                                        std::size_t max_len) {
  const toml::value* v = find(key);
  if (!v) { error(key, "is required (an array of numbers)"); return {}; }
  const std::string want = min_len == max_len ? std::to_string(min_len)
                                              : std::to_string(min_len) + " to " + std::to_string(max_len);
  if (!v->is_array() || v->as_array().size() < min_len || v->as_array().size() > max_len) {
    diag_->add(v, full_key(key), "= " + value_text(*v) + ": must be an array of " + want + " numbers");
    return {};
  }
  std::vector<double> out;
  for (const auto& x : v->as_array()) {
    double d = 0.0;
    if (!as_double(x, d)) {
      diag_->add(&x, full_key(key), "= " + value_text(*v) + ": must hold only numbers");
      return {};
    }
    if (!range.contains(d)) {
      std::ostringstream s;
      s << "= " << value_text(*v) << ": element " << d << " " << range.describe();
      diag_->add(&x, full_key(key), s.str());
    }
    out.push_back(d);
  }
  return out;
}

std::vector<std::string> TomlReader::strings(const std::string& key, std::size_t min_len,
                                             std::size_t max_len) {
  const toml::value* v = find(key);
  const std::string want = min_len == max_len ? std::to_string(min_len)
                                              : std::to_string(min_len) + " to " + std::to_string(max_len);
  if (!v) { error(key, "is required (an array of " + want + " strings)"); return {}; }
  std::vector<std::string> out;
  if (v->is_array() && v->as_array().size() >= min_len && v->as_array().size() <= max_len) {
    for (const auto& x : v->as_array()) {
      if (!x.is_string()) { out.clear(); break; }
      out.push_back(x.as_string().str);
    }
    if (out.size() == v->as_array().size()) return out;
  }
  diag_->add(v, full_key(key), "= " + value_text(*v) + ": must be an array of " + want + " strings");
  return {};
}

std::vector<std::vector<double>> TomlReader::number_rows(const std::string& key, std::size_t row_len,
                                                         std::size_t min_rows, std::size_t max_rows) {
  const toml::value* v = find(key);
  if (!v) { error(key, "is required (an array of arrays)"); return {}; }
  if (!v->is_array() || v->as_array().size() < min_rows || v->as_array().size() > max_rows) {
    diag_->add(v, full_key(key), "= " + value_text(*v) + ": must be an array of " +
                                     std::to_string(min_rows) + " to " + std::to_string(max_rows) +
                                     " rows of " + std::to_string(row_len) + " numbers");
    return {};
  }
  std::vector<std::vector<double>> rows;
  for (const auto& r : v->as_array()) {
    std::vector<double> row;
    bool ok = r.is_array() && r.as_array().size() == row_len;
    if (ok)
      for (const auto& x : r.as_array()) {
        double d = 0.0;
        if (!as_double(x, d) || !std::isfinite(d)) { ok = false; break; }
        row.push_back(d);
      }
    if (!ok) {
      diag_->add(&r, full_key(key), "= " + value_text(r) + ": each row must be " +
                                        std::to_string(row_len) + " finite numbers");
      return {};
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

std::optional<TomlReader> TomlReader::table(const std::string& key) {
  const toml::value* v = find(key);
  if (!v) return std::nullopt;
  if (!v->is_table()) {
    diag_->add(v, full_key(key), "= " + value_text(*v) + ": must be a table");
    return std::nullopt;
  }
  return TomlReader(*v, full_key(key), diag_);
}

std::vector<TomlReader> TomlReader::table_array(const std::string& key) {
  const toml::value* v = find(key);
  std::vector<TomlReader> out;
  if (!v) return out;
  if (!v->is_array()) {
    diag_->add(v, full_key(key), "= " + value_text(*v) + ": must be an array of tables ([[" + key + "]])");
    return out;
  }
  std::size_t i = 0;
  for (const auto& t : v->as_array()) {
    if (!t.is_table()) {
      diag_->add(&t, full_key(key), "entry " + std::to_string(i) + " must be a table");
    } else {
      out.emplace_back(t, full_key(key) + "[" + std::to_string(i) + "]", diag_);
    }
    ++i;
  }
  return out;
}

std::vector<std::string> TomlReader::keys() const {
  std::vector<std::string> k;
  if (!table_->is_table()) return k;
  for (const auto& [name, _] : table_->as_table()) k.push_back(name);
  std::sort(k.begin(), k.end());
  return k;
}

void TomlReader::check_unknown_keys() {
  if (!table_->is_table()) return;
  std::vector<std::string> known(used_.begin(), used_.end());
  for (const auto& name : keys()) {
    if (used_.count(name)) continue;
    std::string msg = "is not a known key";
    const std::string hint = did_you_mean(name, known);
    if (!hint.empty()) msg += " (did you mean \"" + hint + "\"?)";
    else if (!known.empty()) msg += "; known keys here: " + join(known);
    diag_->add(&table_->at(name), full_key(name), msg);
  }
}

std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates) {
  // Levenshtein distance; suggest when at most a third of the word differs.
  auto dist = [](const std::string& a, const std::string& b) {
    std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
      cur[0] = i;
      for (std::size_t j = 1; j <= b.size(); ++j)
        cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      std::swap(prev, cur);
    }
    return prev[b.size()];
  };
  std::string best;
  std::size_t best_d = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const auto& c : candidates) {
    const std::size_t d = dist(word, c);
    if (d < best_d) { best_d = d; best = c; }
  }
  return best;
}

}  // namespace seedcal
