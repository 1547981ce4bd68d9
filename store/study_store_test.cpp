// The study store: round trip, crash safety by atomic replacement, corruption detection, the
// numeric tables and the schema versions (docs/store.md).
#include "store/study_store.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "store/errors.hpp"
#include "store/hdf5_handle.hpp"

namespace seedcal {
namespace {

std::string scratch(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / ("seedcal-store-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return (d / "study.h5").string();
}

EvaluationRecord record(double mu) {
  EvaluationRecord r;
  r.stage = "screen";
  r.inputs = {{"seed_seed.static_friction", mu}};
  r.seed = 7;
  r.metrics = {{"shear_strength_pa", 1.2e5 * mu}, {"steps", 1000}};
  r.cpu_seconds = 1.5;
  r.wall_seconds = 0.8;
  r.config_hash = "abc";
  r.seedcal_version = "test";
  return r;
}

TEST(StudyStore, RoundTripsEveryFieldAndStage) {
  const std::string path = scratch("roundtrip");
  StudyHeader h{"hash1", "[study]\nname = \"x\"\n", "test", "2026-01-01T00:00:00Z"};
  {
    StudyStore s = StudyStore::create(path, h);
    s.append(record(0.4));
    s.append(record(0.5));
    s.set_stage("screen", {{"design", {{1, -1}, {-1, 1}}}});
  }
  const StudyStore s = StudyStore::open(path);
  ASSERT_EQ(s.evaluations().size(), 2u);
  EXPECT_EQ(s.evaluations()[0].id, 1u);
  EXPECT_EQ(s.evaluations()[1].id, 2u);
  EXPECT_DOUBLE_EQ(s.evaluations()[1].inputs["seed_seed.static_friction"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(s.evaluations()[1].metrics["shear_strength_pa"].get<double>(), 6e4);
  EXPECT_EQ(s.header().config_text, h.config_text);
  EXPECT_EQ(s.stages()["screen"]["design"][0][1], -1);
  EXPECT_EQ(s.next_id(), 3u);
}

TEST(StudyStore, RefusesToOverwriteAndLeavesNoTemporaryFiles) {
  const std::string path = scratch("overwrite");
  StudyStore::create(path, StudyHeader{"h", "", "v", ""}).append(record(0.3));
  EXPECT_THROW(StudyStore::create(path, StudyHeader{"h", "", "v", ""}), InputError);
  for (const auto& f : std::filesystem::directory_iterator(std::filesystem::path(path).parent_path()))
    EXPECT_EQ(f.path().filename(), "study.h5");
}

TEST(StudyStore, TruncatedFileIsReportedNotReused) {
  const std::string path = scratch("truncated");
  StudyStore s = StudyStore::create(path, StudyHeader{"h", "", "v", ""});
  for (int i = 0; i < 5; ++i) s.append(record(0.1 * i));
  const auto size = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, size / 2);
  EXPECT_THROW(StudyStore::open(path), RunFailed);
}

TEST(StudyStore, CorruptedContentFailsTheChecksum) {
  const std::string path = scratch("corrupt");
  StudyStore s = StudyStore::create(path, StudyHeader{"h", "", "v", ""});
  s.append(record(0.42));
  // Flip bytes of the stored JSON text in place (same length, so HDF5 still opens the file).
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const auto at = bytes.find("0.42");
  ASSERT_NE(at, std::string::npos);
  f.seekp(static_cast<std::streamoff>(at));
  f.write("0.43", 4);
  f.close();
  try {
    StudyStore::open(path);
    FAIL() << "a corrupted store was accepted";
  } catch (const RunFailed& e) {
    EXPECT_NE(std::string(e.what()).find("study.h5"), std::string::npos);
  }
}

// A record as the pipeline writes it: its target's tags in the metrics.
EvaluationRecord tagged(double mu, int target, const std::string& name) {
  EvaluationRecord r = record(mu);
  r.metrics["study_target"] = target;
  r.metrics["study_target_name"] = name;
  return r;
}

std::vector<double> doubles(hid_t file, const std::string& path) {
  h5::Handle set(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose, "open " + path);
  h5::Handle space(H5Dget_space(set), H5Sclose, "get a data space");
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space, &n, nullptr);
  std::vector<double> v(n);
  if (n > 0) h5::check(H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), "read " + path);
  return v;
}

long long int_attr(hid_t obj, const char* name) {
  h5::Handle a(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose, std::string("open ") + name);
  long long v = 0;
  h5::check(H5Aread(a, H5T_NATIVE_LLONG, &v), std::string("read ") + name);
  return v;
}

TEST(StudyStore, WritesTheSchemaVersionAndOneNumericTablePerTarget) {
  const std::string path = scratch("tables");
  StudyStore s = StudyStore::create(path, StudyHeader{"h", "", "v", ""});
  s.append(tagged(0.4, 0, "shear"));
  EvaluationRecord drop = tagged(0.5, 1, "drop/plate");  // a '/' in a name does not open a subgroup
  drop.metrics = {{"study_target", 1}, {"study_target_name", "drop/plate"}, {"rebound_height_m", 0.02},
                  {"settled", true}, {"samples", {1, 2}}, {"failure", {{"message", "x"}}}};
  s.append(drop);
  EvaluationRecord failed = tagged(0.6, 0, "shear");
  failed.status = "unstable";
  failed.metrics.erase("shear_strength_pa");
  s.append(failed);
  EvaluationRecord crashed = record(0.7);  // a worker that died: only the target's index
  crashed.status = "failed";
  crashed.metrics = {{"study_target", 0}};
  s.append(crashed);
  EXPECT_EQ(s.schema_version(), kStudyStoreSchemaVersion);

  h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open the store");
  EXPECT_EQ(int_attr(f, "schema_version"), 2);
  EXPECT_EQ(h5::read_string_attr(f, "format"), "seedcal study store 2");
  // Rows in store order; a run without a metric has NaN there.
  EXPECT_EQ(doubles(f, "/tables/shear/inputs/seed_seed.static_friction"), (std::vector<double>{0.4, 0.6, 0.7}));
  const auto strength = doubles(f, "/tables/shear/metrics/shear_strength_pa");
  ASSERT_EQ(strength.size(), 3u);
  EXPECT_DOUBLE_EQ(strength[0], 1.2e5 * 0.4);
  EXPECT_TRUE(std::isnan(strength[1]));
  EXPECT_TRUE(std::isnan(strength[2]));
  EXPECT_EQ(doubles(f, "/tables/shear/metrics/study_target"), (std::vector<double>{0, 0, 0}));
  EXPECT_EQ(doubles(f, "/tables/shear/cpu_seconds"), (std::vector<double>{1.5, 1.5, 1.5}));
  h5::Handle shear(H5Gopen2(f, "/tables/shear", H5P_DEFAULT), H5Gclose, "open /tables/shear");
  EXPECT_EQ(h5::read_strings(shear, "status"), (std::vector<std::string>{"ok", "unstable", "failed"}));
  EXPECT_EQ(h5::read_strings(shear, "stage"), (std::vector<std::string>{"screen", "screen", "screen"}));
  EXPECT_EQ(h5::read_strings(shear, "model"), (std::vector<std::string>{"", "", ""}));
  EXPECT_EQ(h5::read_string_attr(shear, "target_name"), "shear");
  // Numbers and true/false only: arrays and objects stay in the JSON columns.
  h5::Handle drop_table(H5Gopen2(f, "/tables/drop_plate", H5P_DEFAULT), H5Gclose, "open /tables/drop_plate");
  EXPECT_EQ(h5::read_string_attr(drop_table, "target_name"), "drop/plate");
  EXPECT_EQ(doubles(f, "/tables/drop_plate/metrics/settled"), (std::vector<double>{1.0}));
  EXPECT_EQ(doubles(f, "/tables/drop_plate/metrics/rebound_height_m"), (std::vector<double>{0.02}));
  EXPECT_EQ(H5Lexists(f, "/tables/drop_plate/metrics/samples", H5P_DEFAULT), 0);
  EXPECT_EQ(H5Lexists(f, "/tables/drop_plate/metrics/failure", H5P_DEFAULT), 0);
}

// A store as the first schema wrote it: no schema_version attribute, no /tables.
void make_schema_1(const std::string& path) {
  h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose, "open the store");
  h5::check(H5Adelete(f, "schema_version"), "delete schema_version");
  h5::check(H5Ldelete(f, "tables", H5P_DEFAULT), "delete /tables");
  h5::check(H5Adelete(f, "format"), "delete format");
  h5::write_string_attr(f, "format", "seedcal study store 1");
}

TEST(StudyStore, StoreOfSchemaOneOpensAndResumes) {
  const std::string path = scratch("schema1");
  {
    StudyStore s = StudyStore::create(path, StudyHeader{"h", "", "v", ""});
    s.append(tagged(0.4, 0, "shear"));
    s.append(tagged(0.5, 0, "shear"));
    s.set_stage("screen", {{"kept", {"seed_seed.static_friction"}}});
  }
  make_schema_1(path);
  StudyStore s = StudyStore::open(path);
  EXPECT_EQ(s.schema_version(), 1);
  ASSERT_EQ(s.evaluations().size(), 2u);
  EXPECT_EQ(s.stages()["screen"]["kept"][0], "seed_seed.static_friction");
  s.append(tagged(0.6, 0, "shear"));  // resumes: the next run joins, the file becomes schema 2
  EXPECT_EQ(s.schema_version(), 2);
  const StudyStore again = StudyStore::open(path);
  EXPECT_EQ(again.schema_version(), 2);
  ASSERT_EQ(again.evaluations().size(), 3u);
  EXPECT_EQ(again.evaluations()[2].id, 3u);
  h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open the store");
  EXPECT_EQ(doubles(f, "/tables/shear/inputs/seed_seed.static_friction"), (std::vector<double>{0.4, 0.5, 0.6}));
}

TEST(StudyStore, NewerSchemaIsRefusedWithBothVersions) {
  const std::string path = scratch("newer");
  StudyStore::create(path, StudyHeader{"h", "", "v", ""}).append(record(0.3));
  {
    h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose, "open the store");
    h5::Handle a(H5Aopen(f, "schema_version", H5P_DEFAULT), H5Aclose, "open schema_version");
    const long long future = kStudyStoreSchemaVersion + 1;
    h5::check(H5Awrite(a, H5T_NATIVE_LLONG, &future), "write schema_version");
  }
  try {
    StudyStore::open(path);
    FAIL() << "a store of a newer schema was accepted";
  } catch (const RunFailed& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("schema 3"), std::string::npos) << what;
    EXPECT_NE(what.find("schema 2"), std::string::npos) << what;
  }
}

TEST(StudyStore, GarbageIsNotAStore) {
  const std::string path = scratch("garbage");
  std::ofstream(path) << "not hdf5";
  EXPECT_THROW(StudyStore::open(path), RunFailed);
}

}  // namespace
}  // namespace seedcal
