// The study store as users read it (docs/store.md): a store written by `seedcal calibrate` on the
// miniature study (tests/cli/mini/mpi_study.toml, two spheres, seconds) is read by
// scripts/read_store.py, which checks that every dataset and attribute docs/store.md lists is in
// the store and read, and that the store holds nothing the document leaves out; the same store
// taken back to schema 1 (no schema_version, no /tables) resumes, answers every run from the
// store and is written at schema 2 again.
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "store/hdf5_handle.hpp"
#include "store/study_store.hpp"
#include "tests/support/cli.hpp"

namespace seedcal::testing {
namespace {

// A Python with h5py and pandas (scripts/setup.sh installs python3-h5py and python3-pandas for
// the system's python3): the one CMake found, else the system's, else the first on PATH.
std::string python_with_h5py() {
  std::vector<std::string> candidates;
  if (const char* p = std::getenv("SEEDCAL_PYTHON")) candidates.emplace_back(p);
  candidates.insert(candidates.end(), {"/usr/bin/python3", "python3"});
  for (const auto& py : candidates)
    if (run_shell(py + " -c 'import h5py, pandas' > /dev/null 2>&1").exit_code == 0) return py;
  return "";
}

class StoreRead : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = scratch_dir("store-read");
    const auto r = run_cli(calibrate_args());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  static void TearDownTestSuite() { std::filesystem::remove_all(dir_); }

  static std::string calibrate_args() {
    return "calibrate " + source_dir() + "/tests/cli/mini/mpi_study.toml --out " + dir_ + "/out --threads 1 --quiet";
  }
  static CliResult read_store(const std::string& py) {
    return run_shell(py + " " + source_dir() + "/scripts/read_store.py " + dir_ + "/out/study.h5 --check-doc " +
                     source_dir() + "/docs/store.md 2>&1");
  }
  static std::string dir_;
};
std::string StoreRead::dir_;

TEST_F(StoreRead, ReadStoreReadsEveryDatasetTheDocumentLists) {
  const std::string py = python_with_h5py();
  ASSERT_FALSE(py.empty()) << "no python3 with h5py and pandas: install python3-h5py python3-pandas (scripts/setup.sh)";
  const auto s = nlohmann::json::parse(read_text(dir_ + "/out/summary.json"));
  EXPECT_EQ(s["schema_version"], kStudyStoreSchemaVersion);
  const auto r = read_store(py);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("schema version 2"), std::string::npos) << r.output;
  // The study's one target, "contact", has its table with the fitted parameter and the metric.
  EXPECT_NE(r.output.find("tables['contact']"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("inputs.materials.glass.youngs_modulus_pa"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("metrics.contact_duration_s"), std::string::npos) << r.output;
}

TEST_F(StoreRead, StoreOfSchemaOneResumes) {
  const std::string path = dir_ + "/out/study.h5";
  const std::size_t runs = StudyStore::open(path).evaluations().size();
  ASSERT_GT(runs, 0u);
  {  // As the first schema wrote it: no schema_version attribute, no /tables.
    h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose, "open the store");
    h5::check(H5Adelete(f, "schema_version"), "delete schema_version");
    h5::check(H5Ldelete(f, "tables", H5P_DEFAULT), "delete /tables");
    h5::check(H5Adelete(f, "format"), "delete format");
    h5::write_string_attr(f, "format", "seedcal study store 1");
  }
  EXPECT_EQ(StudyStore::open(path).schema_version(), 1);
  const auto r = run_cli(calibrate_args() + " --resume");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = nlohmann::json::parse(read_text(dir_ + "/out/summary.json"));
  EXPECT_EQ(s["evaluations_from_store"].get<std::size_t>(), runs) << "a stored run was run again";
  const StudyStore again = StudyStore::open(path);
  EXPECT_EQ(again.schema_version(), kStudyStoreSchemaVersion);
  EXPECT_EQ(again.evaluations().size(), runs);
  const std::string py = python_with_h5py();
  if (py.empty()) return;  // the first test names the missing packages
  const auto read = read_store(py);
  EXPECT_EQ(read.exit_code, 0) << read.output;
}

}  // namespace
}  // namespace seedcal::testing
