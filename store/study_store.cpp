#include "store/study_store.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <unistd.h>

#include "store/atomic_file.hpp"
#include "store/errors.hpp"
#include "store/hdf5_handle.hpp"

namespace seedcal {

namespace {

constexpr int kFormatVersion = 1;

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

StudyStore StudyStore::open(const std::string& path) {
  if (!std::filesystem::exists(path)) throw InputError(path + ": no study store to resume");
  StudyStore s;
  s.path_ = path;
  std::string stored_checksum;
  try {
    h5::QuietErrors quiet;
    if (H5Fis_hdf5(path.c_str()) <= 0) throw std::runtime_error("not an HDF5 file");
    h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open the file");
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

void StudyStore::write() const {
  namespace fs = std::filesystem;
  const fs::path target(path_);
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  const std::string tmp = path_ + ".tmp." + std::to_string(::getpid());
  {
    h5::QuietErrors quiet;
    h5::Handle f(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
                 "create " + tmp);
    write_string_attr(f, "format", "seedcal study store " + std::to_string(kFormatVersion));
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
    h5::check(H5Fflush(f, H5F_SCOPE_GLOBAL), "flush " + tmp);
  }
  commit_file_atomic(tmp, path_);  // fsync, rename, fsync the folder (atomic_file.hpp)
}

}  // namespace seedcal
