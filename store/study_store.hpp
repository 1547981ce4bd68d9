#pragma once
// The study store: every DEM evaluation of a study (stage, inputs in natural units, seed, metrics,
// CPU and wall time, status, config hash, seedcal version) and the designs and fits of each stage,
// in DIR/study.h5.
//
// Crash safety: the store is rewritten to a temporary file, flushed to disk (fsync) and renamed
// over study.h5 after every append, so a kill at any moment leaves either the previous or the new
// complete file, never a half-written one. A content checksum (FNV-1a 64 over the canonical JSON of
// the records) is stored as an attribute and verified on open: a truncated or corrupted file is
// reported, never silently reused.
//
// The layout (every group, dataset and attribute, with units) is docs/store.md; scripts/read_store.py
// reads it into pandas data frames.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace seedcal {

// The layout this build writes, stored as the root attribute `schema_version` and in summary.json.
// 1: the layout without that attribute (/evaluations, /stages); 2: adds the attribute and /tables,
// one numeric table per target (docs/store.md). A store of any version up to this one opens and
// resumes, and is written at this version from its next change on.
inline constexpr int kStudyStoreSchemaVersion = 2;

struct EvaluationRecord {
  std::uint64_t id = 0;
  std::string stage;
  nlohmann::json inputs = nlohmann::json::object();   // parameter path -> natural value
  std::uint64_t seed = 0;
  nlohmann::json metrics = nlohmann::json::object();  // the scene's metrics.json
  double cpu_seconds = 0.0;
  double wall_seconds = 0.0;
  std::string status = "ok";  // ok, or the failure status
  std::string message;
  std::string config_hash;
  std::string seedcal_version;

  nlohmann::json to_json() const;
  static EvaluationRecord from_json(const nlohmann::json& j);
};

struct StudyHeader {
  std::string config_hash;   // of the study file's effective content
  std::string config_text;   // the study file as read (after overrides)
  std::string seedcal_version;
  std::string created_utc;
};

class StudyStore {
 public:
  // A new store at `path` (refuses to overwrite an existing file).
  static StudyStore create(const std::string& path, const StudyHeader& header);
  // An existing store; throws RunFailed when the file is not a readable study store, its
  // checksum does not match (truncated or corrupted) or its schema is newer than this build's.
  static StudyStore open(const std::string& path);

  void append(EvaluationRecord record);  // assigns the id if 0; written before it returns
  void set_stage(const std::string& name, const nlohmann::json& content);
  // Records the study's fingerprint under the current rule (a store from an earlier build that
  // computed the same study's fingerprint another way); written before it returns.
  void set_config_hash(const std::string& hash);

  const StudyHeader& header() const { return header_; }
  const std::vector<EvaluationRecord>& evaluations() const { return evaluations_; }
  const nlohmann::json& stages() const { return stages_; }
  const std::string& path() const { return path_; }
  // The schema version of the file as read (1 for a store without the attribute); a store that
  // has been written since has kStudyStoreSchemaVersion.
  int schema_version() const { return schema_version_; }
  std::uint64_t next_id() const;

 private:
  void write();
  std::string checksum() const;

  std::string path_;
  StudyHeader header_;
  std::vector<EvaluationRecord> evaluations_;
  nlohmann::json stages_ = nlohmann::json::object();
  int schema_version_ = kStudyStoreSchemaVersion;
};

// FNV-1a 64-bit hash as 16 hex digits (config and content fingerprints).
std::string fnv1a_hex(const std::string& text);

}  // namespace seedcal
