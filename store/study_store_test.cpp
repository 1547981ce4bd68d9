// The study store: round trip, crash safety by atomic replacement, corruption detection.
#include "store/study_store.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "store/errors.hpp"

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

TEST(StudyStore, GarbageIsNotAStore) {
  const std::string path = scratch("garbage");
  std::ofstream(path) << "not hdf5";
  EXPECT_THROW(StudyStore::open(path), RunFailed);
}

}  // namespace
}  // namespace seedcal
