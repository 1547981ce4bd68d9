#include "store/study_store.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <unistd.h>

#include "store/atomic_file.hpp"
#include "store/errors.hpp"
#include "store/hdf5_handle.hpp"

namespace seedcal {

namespace {

// ---- small HDF5 helpers ---------------------------------------------------------------------

using h5::read_string_attr;
using h5::read_strings;
using h5::write_string_attr;
using h5::write_strings;

template <class T>
void write_numbers(hid_t group, const char* name, const std::vector<T>& values, hid_t mem_type) {
  const hsize_t n = values.size();
  h5::Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose, "create a data space");
  h5::Handle set(H5Dcreate2(group, name, mem_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                 H5Dclose, std::string("create dataset ") + name);
  if (n > 0) h5::check(H5Dwrite(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), std::string("write ") + name);
}

template <class T>
std::vector<T> read_numbers(hid_t group, const char* name, hid_t mem_type) {
  h5::Handle set(H5Dopen2(group, name, H5P_DEFAULT), H5Dclose, std::string("open dataset ") + name);
  h5::Handle space(H5Dget_space(set), H5Sclose, "get a data space");
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space, &n, nullptr);
  std::vector<T> out(n);
  if (n > 0) h5::check(H5Dread(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), std::string("read ") + name);
  return out;
}

void write_int_attr(hid_t obj, const char* name, long long value) {
  h5::Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create a scalar space");
  h5::Handle attr(H5Acreate2(obj, name, H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                  std::string("create attribute ") + name);
  h5::check(H5Awrite(attr, H5T_NATIVE_LLONG, &value), std::string("write attribute ") + name);
}

// An integer attribute, or `absent` when the object has none of that name.
long long read_int_attr(hid_t obj, const char* name, long long absent) {
  const htri_t exists = H5Aexists(obj, name);
  h5::check(exists, std::string("look for attribute ") + name);
  if (exists == 0) return absent;
  h5::Handle attr(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose, std::string("open attribute ") + name);
  long long value = 0;
  h5::check(H5Aread(attr, H5T_NATIVE_LLONG, &value), std::string("read attribute ") + name);
  return value;
}

// ---- the numeric tables (/tables, schema 2; docs/store.md) -----------------------------------

// A link name from a target name or a key: '/' would open a subgroup and "." names the group
// itself.
std::string link_name(std::string s, const std::string& fallback) {
  for (char& c : s)
    if (c == '/') c = '_';
  return s.empty() || s == "." ? fallback : s;
}

// The target a record belongs to, from the tags the pipeline puts in its metrics
// (calibrate/pipeline/evaluation.cpp, request_record): the target's index `study_target` (every
// record has it, a crashed worker's too) and its name `study_target_name`.
std::string target_key(const EvaluationRecord& e) {
  const auto index = e.metrics.find("study_target");
  if (index != e.metrics.end() && index->is_number_integer()) return "#" + std::to_string(index->get<long long>());
  const auto name = e.metrics.find("study_target_name");
  return name != e.metrics.end() && name->is_string() ? "=" + name->get<std::string>() : std::string();
}

// A table's target name: the first name among its records, else one made from the key.
std::string target_name(const std::string& key, const std::vector<const EvaluationRecord*>& rows) {
  for (const EvaluationRecord* e : rows) {
    const auto name = e->metrics.find("study_target_name");
    if (name != e->metrics.end() && name->is_string()) return name->get<std::string>();
  }
  return key.empty() ? std::string() : key[0] == '#' ? "target_" + key.substr(1) : key.substr(1);
}

// A JSON scalar as a table value: numbers as they are, true/false as 1/0; false for anything else.
bool numeric(const nlohmann::json& v, double& out) {
  if (v.is_number()) out = v.get<double>();
  else if (v.is_boolean()) out = v.get<bool>() ? 1.0 : 0.0;
  else return false;
  return true;
}

// One column per key that has a number in some row, NaN in the rows without one.
using Columns = std::map<std::string, std::vector<double>>;
void add_numbers(Columns& columns, const nlohmann::json& object, std::size_t row, std::size_t rows) {
  if (!object.is_object()) return;
  for (const auto& [key, value] : object.items()) {
    double x = 0.0;
    if (!numeric(value, x)) continue;
    auto [it, fresh] = columns.try_emplace(link_name(key, "_"));
    if (fresh) it->second.assign(rows, std::numeric_limits<double>::quiet_NaN());
    it->second[row] = x;
  }
}

void write_columns(hid_t parent, const char* name, const Columns& columns) {
  h5::Handle g(H5Gcreate2(parent, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
               std::string("create group ") + name);
  for (const auto& [key, values] : columns) write_numbers(g, key.c_str(), values, H5T_NATIVE_DOUBLE);
}

// /tables/<link>: one row per run of `target`, in store order.
void write_table(hid_t tables, const std::string& link, const std::string& target,
                 const std::vector<const EvaluationRecord*>& rows) {
  h5::Handle g(H5Gcreate2(tables, link.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
               "create the table of target " + target);
  write_string_attr(g, "target_name", target);
  std::vector<std::uint64_t> ids, seeds;
  std::vector<double> cpu, wall;
  std::vector<std::string> stage, status, model;
  Columns inputs, metrics;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const EvaluationRecord& e = *rows[k];
    ids.push_back(e.id);
    seeds.push_back(e.seed);
    cpu.push_back(e.cpu_seconds);
    wall.push_back(e.wall_seconds);
    stage.push_back(e.stage);
    status.push_back(e.status);
    const auto m = e.metrics.find("study_model");
    model.push_back(m != e.metrics.end() && m->is_string() ? m->get<std::string>() : std::string());
    add_numbers(inputs, e.inputs, k, rows.size());
    add_numbers(metrics, e.metrics, k, rows.size());
  }
  write_numbers(g, "id", ids, H5T_NATIVE_UINT64);
  write_numbers(g, "seed", seeds, H5T_NATIVE_UINT64);
  write_numbers(g, "cpu_seconds", cpu, H5T_NATIVE_DOUBLE);
  write_numbers(g, "wall_seconds", wall, H5T_NATIVE_DOUBLE);
  write_strings(g, "stage", stage);
  write_strings(g, "status", status);
  write_strings(g, "model", model);
  write_columns(g, "inputs", inputs);
  write_columns(g, "metrics", metrics);
}

void write_tables(hid_t file, const std::vector<EvaluationRecord>& evaluations) {
  std::map<std::string, std::vector<const EvaluationRecord*>> by_target;
  for (const auto& e : evaluations) by_target[target_key(e)].push_back(&e);
  h5::Handle t(H5Gcreate2(file, "tables", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "create /tables");
  std::set<std::string> links;  // two names that differ only in '/' get _2, _3, ... (target_name tells them apart)
  for (const auto& [key, rows] : by_target) {
    const std::string target = target_name(key, rows);
    const std::string base = link_name(target, "unnamed");
    std::string link = base;
    for (int n = 2; !links.insert(link).second; ++n) link = base + "_" + std::to_string(n);
    write_table(t, link, target, rows);
  }
}

}  // namespace

std::string fnv1a_hex(const std::string& text) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

nlohmann::json EvaluationRecord::to_json() const {
  return {{"id", id}, {"stage", stage}, {"inputs", inputs}, {"seed", seed}, {"metrics", metrics},
          {"cpu_seconds", cpu_seconds}, {"wall_seconds", wall_seconds}, {"status", status},
          {"message", message}, {"config_hash", config_hash}, {"seedcal_version", seedcal_version}};
}

EvaluationRecord EvaluationRecord::from_json(const nlohmann::json& j) {
  EvaluationRecord r;
  r.id = j.at("id").get<std::uint64_t>();
  r.stage = j.at("stage").get<std::string>();
  r.inputs = j.at("inputs");
  r.seed = j.at("seed").get<std::uint64_t>();
  r.metrics = j.at("metrics");
  r.cpu_seconds = j.at("cpu_seconds").get<double>();
  r.wall_seconds = j.at("wall_seconds").get<double>();
  r.status = j.at("status").get<std::string>();
  r.message = j.value("message", "");
  r.config_hash = j.value("config_hash", "");
  r.seedcal_version = j.value("seedcal_version", "");
  return r;
}

std::uint64_t StudyStore::next_id() const {
  std::uint64_t id = 1;
  for (const auto& e : evaluations_) id = std::max(id, e.id + 1);
  return id;
}

std::string StudyStore::checksum() const {
  nlohmann::json all = nlohmann::json::array();
  for (const auto& e : evaluations_) all.push_back(e.to_json());
  return fnv1a_hex(header_.config_hash + "\n" + all.dump() + "\n" + stages_.dump());
}

StudyStore StudyStore::create(const std::string& path, const StudyHeader& header) {
  if (std::filesystem::exists(path))
    throw InputError(path + ": a study store already exists here (use --resume to continue it, or "
                            "another --out directory)");
  StudyStore s;
  s.path_ = path;
  s.header_ = header;
  s.write();
  return s;
}

namespace {
struct NewerSchema {
  int version;
};
}  // namespace

StudyStore StudyStore::open(const std::string& path) {
  if (!std::filesystem::exists(path)) throw InputError(path + ": no study store to resume");
  StudyStore s;
  s.path_ = path;
  std::string stored_checksum;
  try {
    h5::QuietErrors quiet;
    if (H5Fis_hdf5(path.c_str()) <= 0) throw std::runtime_error("not an HDF5 file");
    h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open the file");
    // The tables (schema 2) are derived from the records, so nothing else differs on reading.
    s.schema_version_ = static_cast<int>(read_int_attr(f, "schema_version", 1));
    if (s.schema_version_ > kStudyStoreSchemaVersion) throw NewerSchema{s.schema_version_};
    s.header_.config_hash = read_string_attr(f, "config_hash");
    s.header_.config_text = read_string_attr(f, "config_text");
    s.header_.seedcal_version = read_string_attr(f, "seedcal_version");
    s.header_.created_utc = read_string_attr(f, "created_utc");
    stored_checksum = read_string_attr(f, "content_checksum");
    h5::Handle g(H5Gopen2(f, "evaluations", H5P_DEFAULT), H5Gclose, "open /evaluations");
    const auto records = read_strings(g, "record_json");
    const auto ids = read_numbers<std::uint64_t>(g, "id", H5T_NATIVE_UINT64);
    const auto seeds = read_numbers<std::uint64_t>(g, "seed", H5T_NATIVE_UINT64);
    const auto cpu = read_numbers<double>(g, "cpu_seconds", H5T_NATIVE_DOUBLE);
    const auto wall = read_numbers<double>(g, "wall_seconds", H5T_NATIVE_DOUBLE);
    const auto stage = read_strings(g, "stage");
    const auto status = read_strings(g, "status");
    const auto inputs = read_strings(g, "inputs_json");
    const auto metrics = read_strings(g, "metrics_json");
    const std::size_t n = records.size();
    if (ids.size() != n || seeds.size() != n || cpu.size() != n || wall.size() != n ||
        stage.size() != n || status.size() != n || inputs.size() != n || metrics.size() != n)
      throw std::runtime_error("/evaluations columns differ in length");
    for (std::size_t k = 0; k < n; ++k) {
      EvaluationRecord r = EvaluationRecord::from_json(nlohmann::json::parse(records[k]));
      // The per-field columns must say what the record says (a reader may use either).
      if (r.id != ids[k] || r.seed != seeds[k] || r.cpu_seconds != cpu[k] ||
          r.wall_seconds != wall[k] || r.stage != stage[k] || r.status != status[k] ||
          r.inputs.dump() != inputs[k] || r.metrics.dump() != metrics[k])
        throw std::runtime_error("evaluation " + std::to_string(k) +
                                 ": the columns disagree with the record");
      s.evaluations_.push_back(std::move(r));
    }
    h5::Handle st(H5Gopen2(f, "stages", H5P_DEFAULT), H5Gclose, "open /stages");
    s.stages_ = nlohmann::json::parse(read_string_attr(st, "stages_json"));
  } catch (const NewerSchema& n) {
    throw RunFailed(path + ": written by a newer seedcal (store schema " + std::to_string(n.version) +
                    "; this build reads schema " + std::to_string(kStudyStoreSchemaVersion) +
                    " and older): resume it with that version, or start the study afresh in another --out");
  } catch (const std::exception& e) {
    throw RunFailed(path + ": not a readable study store (" + e.what() +
                    "); it may be truncated or corrupted: move it away to start the study afresh");
  }
  if (s.checksum() != stored_checksum)
    throw RunFailed(path + ": the content checksum does not match (stored " + stored_checksum +
                    ", computed " + s.checksum() + "): the file is corrupted; it is not reused");
  return s;
}

void StudyStore::append(EvaluationRecord record) {
  if (record.id == 0) record.id = next_id();
  evaluations_.push_back(std::move(record));
  write();
}

void StudyStore::set_config_hash(const std::string& hash) {
  header_.config_hash = hash;
  write();
}

void StudyStore::set_stage(const std::string& name, const nlohmann::json& content) {
  stages_[name] = content;
  write();
}

void StudyStore::write() {
  namespace fs = std::filesystem;
  const fs::path target(path_);
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  const std::string tmp = path_ + ".tmp." + std::to_string(::getpid());
  {
    h5::QuietErrors quiet;
    h5::Handle f(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
                 "create " + tmp);
    write_string_attr(f, "format", "seedcal study store " + std::to_string(kStudyStoreSchemaVersion));
    write_int_attr(f, "schema_version", kStudyStoreSchemaVersion);
    write_string_attr(f, "config_hash", header_.config_hash);
    write_string_attr(f, "config_text", header_.config_text);
    write_string_attr(f, "seedcal_version", header_.seedcal_version);
    write_string_attr(f, "created_utc", header_.created_utc);
    write_string_attr(f, "content_checksum", checksum());
    // One column per field (readable from any HDF5 tool) plus the whole record as JSON.
    h5::Handle g(H5Gcreate2(f, "evaluations", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                 "create /evaluations");
    std::vector<std::uint64_t> ids, seeds;
    std::vector<double> cpu, wall;
    std::vector<std::string> stage, status, inputs, metrics, record;
    for (const auto& e : evaluations_) {
      ids.push_back(e.id);
      seeds.push_back(e.seed);
      cpu.push_back(e.cpu_seconds);
      wall.push_back(e.wall_seconds);
      stage.push_back(e.stage);
      status.push_back(e.status);
      inputs.push_back(e.inputs.dump());
      metrics.push_back(e.metrics.dump());
      record.push_back(e.to_json().dump());
    }
    write_numbers(g, "id", ids, H5T_NATIVE_UINT64);
    write_numbers(g, "seed", seeds, H5T_NATIVE_UINT64);
    write_numbers(g, "cpu_seconds", cpu, H5T_NATIVE_DOUBLE);
    write_numbers(g, "wall_seconds", wall, H5T_NATIVE_DOUBLE);
    write_strings(g, "stage", stage);
    write_strings(g, "status", status);
    write_strings(g, "inputs_json", inputs);
    write_strings(g, "metrics_json", metrics);
    write_strings(g, "record_json", record);
    h5::Handle st(H5Gcreate2(f, "stages", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                  "create /stages");
    write_string_attr(st, "stages_json", stages_.dump());
    // The same runs again as numbers, one table per target, for readers that do not parse JSON.
    write_tables(f, evaluations_);
    h5::check(H5Fflush(f, H5F_SCOPE_GLOBAL), "flush " + tmp);
  }
  commit_file_atomic(tmp, path_);  // fsync, rename, fsync the folder (atomic_file.hpp)
  schema_version_ = kStudyStoreSchemaVersion;
}

}  // namespace seedcal
