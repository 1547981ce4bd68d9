#pragma once
// A scene's schema, declared once: every key of its rig table (name, unit, allowed range, default,
// meaning, and the member of the solver's spec it sets) and every metric its runner writes (name,
// unit, meaning). The one declaration drives
//   - reading and validating the rig table (SceneSchema::read: TomlReader's typed readers, so a bad
//     value names the file, line, key, value and range and exits 2);
//   - the default, taken from the solver spec's own member initialiser (the spec holds the value
//     the solver uses, the schema only points at it);
//   - the metrics: a runner's metrics object may hold only declared keys (check_metrics, a
//     programming error otherwise), so metrics.json and the docs cannot drift apart;
//   - the key and metric tables of docs/scenes/KIND.md, which `seedcal keys KIND --markdown`
//     writes and scripts/scene_keys.sh checks against the committed docs in the test suite.
// Checks that tie two keys together (a fit window's ends in order, a ring wider than its travel)
// stay in the runner, after read().
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "calibrate/config/physics_config.hpp"
#include "calibrate/config/toml_reader.hpp"

namespace seedcal {

// One rig key as the docs show it.
struct SchemaKey {
  std::string key, unit, range, default_text, meaning;
};
// One metric as the docs show it.
struct SchemaMetric {
  std::string key, unit, meaning;
};

// What a schema is, without its spec type: the docs table and `seedcal keys` read this.
struct SchemaTable {
  std::string kind;     // the scene kind (`kind = "..."`)
  std::string table;    // where its keys live, e.g. "[piling.paper] / [piling.quick]"
  std::vector<SchemaKey> keys;
  std::vector<SchemaMetric> metrics;
};

// The materials a rig key names: the config's [materials] and the material of the seeds, which
// must have an [[interaction]] with every wall material they touch.
struct SchemaMaterials {
  const PhysicsConfig& phys;
  std::uint16_t seed_material;
};

// Text of a default value, as the tables show it (shortest round trip, e.g. 0.0618, 2e-04 -> 0.0002).
std::string schema_number_text(double v);
// An allowed range as the tables show it: [0.005, 5], (0, 100], > 0.
std::string schema_range_text(const Range& r);

// The metrics every scene writes beside its own (the run report: add_run_report, and a seed
// scene's fidelity and particle): declared once here.
const std::vector<SchemaMetric>& run_report_metrics();

// Markdown of a schema's key table and metric table (the blocks between the markers of
// docs/scenes/KIND.md).
std::string keys_markdown(const SchemaTable& t);
std::string metrics_markdown(const SchemaTable& t);
// The run report's metrics (docs/scenes/README.md).
std::string run_report_markdown();

template <class Spec>
class SceneSchema {
 public:
  SceneSchema(std::string kind, std::string table) {
    doc_.kind = std::move(kind);
    doc_.table = std::move(table);
  }

  // A real number in `range`; unit "" for a pure number (a fraction, a ratio).
  SceneSchema& number(const char* key, double Spec::*member, Range range, const char* unit, const char* meaning) {
    add(key, unit, schema_range_text(range), schema_number_text(Spec{}.*member), meaning,
        [key, member, range](TomlReader& rig, const SchemaMaterials&, Spec& spec) {
          spec.*member = rig.number(key, range, spec.*member);
        });
    return *this;
  }
  // An integer in [lo, hi].
  SceneSchema& integer(const char* key, int Spec::*member, int lo, int hi, const char* meaning) {
    add(key, "", std::to_string(lo) + " .. " + std::to_string(hi), std::to_string(Spec{}.*member), meaning,
        [key, member, lo, hi](TomlReader& rig, const SchemaMaterials&, Spec& spec) {
          spec.*member = static_cast<int>(rig.integer(key, lo, hi, spec.*member));
        });
    return *this;
  }
  SceneSchema& flag(const char* key, bool Spec::*member, const char* meaning) {
    add(key, "", "true / false", Spec{}.*member ? "true" : "false", meaning,
        [key, member](TomlReader& rig, const SchemaMaterials&, Spec& spec) {
          spec.*member = rig.boolean(key, spec.*member);
        });
    return *this;
  }
  // One of a fixed set of words, each standing for a value of the member's type.
  template <class E>
  SceneSchema& choice(const char* key, E Spec::*member, std::vector<std::pair<std::string, E>> words,
                      const char* meaning) {
    std::vector<std::string> names;
    std::string range, fallback;
    for (const auto& [w, v] : words) {
      names.push_back(w);
      range += (range.empty() ? "" : " / ") + w;
      if (v == Spec{}.*member) fallback = w;
    }
    if (fallback.empty()) throw std::logic_error(std::string("schema key ") + key + ": the default is not a word");
    add(key, "", range, fallback, meaning,
        [key, member, words, names, fallback](TomlReader& rig, const SchemaMaterials&, Spec& spec) {
          const std::string w = rig.choice(key, names, fallback);
          for (const auto& [name, v] : words)
            if (name == w) spec.*member = v;
        });
    return *this;
  }
  // A [materials] name (required); the seeds touch it (`how`, said when the pair has no interaction).
  SceneSchema& material(const char* key, std::uint16_t Spec::*member, const char* how, const char* meaning) {
    add(key, "", "a `[materials]` name", "required", meaning,
        [key, member, how](TomlReader& rig, const SchemaMaterials& m, Spec& spec) {
          spec.*member = m.phys.material(rig, key, rig.string(key));
          m.phys.require_interaction(rig, key, m.seed_material, spec.*member, how);
        });
    return *this;
  }
  // Three numbers (x, y, z), each in `range`; `required`, or else the spec's value.
  SceneSchema& vec3(const char* key, Eigen::Vector3d Spec::*member, Range range, bool required, const char* unit,
                    const char* meaning) {
    const Eigen::Vector3d d = Spec{}.*member;
    add(key, unit, schema_range_text(range) + " each",
        required ? std::string("required")
                 : schema_number_text(d.x()) + ", " + schema_number_text(d.y()) + ", " + schema_number_text(d.z()),
        meaning, [key, member, range, required](TomlReader& rig, const SchemaMaterials&, Spec& spec) {
          spec.*member = rig.vec3(key, range, required).value_or(spec.*member);
        });
    return *this;
  }
  // A list of min_len .. max_len numbers, each in `range`.
  SceneSchema& numbers(const char* key, std::vector<double> Spec::*member, Range range, std::size_t min_len,
                       std::size_t max_len, const char* unit, const char* meaning) {
    const Spec defaults{};
    std::string d;
    for (double v : defaults.*member) d += (d.empty() ? "" : ", ") + schema_number_text(v);
    add(key, unit,
        schema_range_text(range) + ", " + std::to_string(min_len) + " to " + std::to_string(max_len) + " values", d,
        meaning, [key, member, range, min_len, max_len](TomlReader& rig, const SchemaMaterials&, Spec& spec) {
          if (rig.has(key)) spec.*member = rig.numbers(key, range, min_len, max_len);
        });
    return *this;
  }
  // The last key's default as the docs say it, where it is not the spec's own (e.g. a value a
  // variety supplies).
  SceneSchema& default_is(const char* text) {
    doc_.keys.back().default_text = text;
    return *this;
  }
  // A metric the runner writes (besides the run report's).
  SceneSchema& metric(const char* key, const char* unit, const char* meaning) {
    doc_.metrics.push_back({key, unit, meaning});
    return *this;
  }

  // Reads every declared key of `rig` into `spec` (an absent key keeps the spec's value).
  void read(TomlReader& rig, const SchemaMaterials& materials, Spec& spec) const {
    for (const auto& r : readers_) r(rig, materials, spec);
  }

  // Throws std::logic_error naming the first key of `metrics` that neither this schema nor the
  // run report declares (a runner that writes an undeclared metric is a programming error).
  void check_metrics(const nlohmann::json& metrics) const {
    for (const auto& [k, v] : metrics.items()) {
      bool known = k == "index_key" || k == "warnings";
      for (const SchemaMetric& m : doc_.metrics) known = known || m.key == k;
      for (const SchemaMetric& m : run_report_metrics()) known = known || m.key == k;
      if (!known)
        throw std::logic_error("scene " + doc_.kind + " writes metric `" + k +
                               "`, which its schema does not declare (calibrate/scenes/" + doc_.kind +
                               "_scene.cpp)");
    }
  }

  const SchemaTable& doc() const { return doc_; }

 private:
  using Reader = std::function<void(TomlReader&, const SchemaMaterials&, Spec&)>;
  void add(const char* key, const char* unit, std::string range, std::string fallback, const char* meaning,
           Reader r) {
    doc_.keys.push_back({key, unit, std::move(range), std::move(fallback), meaning});
    readers_.push_back(std::move(r));
  }

  SchemaTable doc_;
  std::vector<Reader> readers_;
};

// Each scene kind's schema, declared in its runner's file (calibrate/scenes/KIND_scene.cpp).
SchemaTable free_drop_schema_table();
SchemaTable bulk_density_schema_table();
SchemaTable direct_shear_schema_table();
SchemaTable piling_schema_table();
SchemaTable drum_schema_table();
// Every scene kind with a schema (for `seedcal keys` and the docs check).
std::vector<SchemaTable> scene_schema_tables();

}  // namespace seedcal
