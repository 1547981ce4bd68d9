// Crash safety and parallel backends of `seedcal calibrate` on data/studies/ci.toml (the Jinong 1
// quick direct shear, ~25 DEM runs): a study killed with SIGKILL part-way resumes without redoing
// or losing a finished evaluation; the same study under `mpirun -n 3` (rank 0 plans, ranks 1 and 2 run)
// gives the same evaluations, value for value, and the same calibrated parameters, since every
// simulation is deterministic for its seed and thread count.
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <thread>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "store/study_store.hpp"
#include "tests/support/cli.hpp"

namespace seedcal::testing {
namespace {

std::size_t stored_runs(const std::string& path) {
  if (!std::filesystem::exists(path)) return 0;
  try {
    return StudyStore::open(path).evaluations().size();
  } catch (const std::exception&) {
    return 0;  // being replaced this instant: ask again
  }
}

std::map<std::uint64_t, EvaluationRecord> by_seed(const std::string& path) {
  std::map<std::uint64_t, EvaluationRecord> m;
  const StudyStore store = StudyStore::open(path);
  for (const auto& r : store.evaluations()) {
    EXPECT_EQ(m.count(r.seed), 0u) << "seed " << r.seed << " stored twice";
    m[r.seed] = r;
  }
  return m;
}

TEST(CalibrateResumeMpi, KilledStudyResumesAndMpiMatches) {
  const std::string dir = scratch_dir("calibrate-resume");
  const std::string study = source_dir() + "/data/studies/ci.toml";
  const std::string out = dir + "/killed";

  // 1. Start the study and SIGKILL it once 8 runs are stored.
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string bin = seedcal_binary();
    ::execl(bin.c_str(), bin.c_str(), "calibrate", study.c_str(), "--out", out.c_str(), "--jobs", "2", "--threads",
            "1", "--quiet", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto t0 = std::chrono::steady_clock::now();
  while (stored_runs(out + "/study.h5") < 8) {
    ASSERT_LT(std::chrono::steady_clock::now() - t0, std::chrono::minutes(10)) << "the study stored too few runs";
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, WNOHANG), 0) << "the study ended before it was killed";
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the workers follow their parent
  const auto before = by_seed(out + "/study.h5");
  ASSERT_GE(before.size(), 8u);

  // 2. Resume: nothing finished is redone or lost.
  const auto r = run_cli("calibrate " + study + " --out " + out + " --resume --jobs 2 --threads 1 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto after = by_seed(out + "/study.h5");
  for (const auto& [seed, rec] : before) {
    ASSERT_EQ(after.count(seed), 1u) << "seed " << seed << " lost";
    EXPECT_EQ(after.at(seed).metrics, rec.metrics) << "seed " << seed << " changed";
  }
  const auto s = nlohmann::json::parse(read_text(out + "/summary.json"));
  EXPECT_EQ(s["evaluations_from_store"].get<std::size_t>(), before.size()) << s.dump(1);
  EXPECT_EQ(s["evaluations"].get<std::size_t>(), after.size());
  EXPECT_NE(read_text(out + "/calibrate.log").find("from the store"), std::string::npos);

  // 3. The same study on three MPI ranks: rank 0 plans, ranks 1 and 2 run (oversubscribed on a
  // two-core machine, Open MPI's idle rank yields its core).
  if (std::system("command -v mpirun > /dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun not installed";
  const std::string mpi_out = dir + "/mpi";
  const std::string cmd = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun --oversubscribe -n 3 " +
                          seedcal_binary() + " calibrate " + study + " --out " + mpi_out + " --threads 1 --quiet" +
                          " > " + dir + "/mpi.log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(dir + "/mpi.log");
  const auto m = nlohmann::json::parse(read_text(mpi_out + "/summary.json"));
  EXPECT_EQ(m["calibrated"], s["calibrated"]) << m.dump(1);
  EXPECT_EQ(m["evaluations"], s["evaluations"]);
  const auto mpi_runs = by_seed(mpi_out + "/study.h5");
  ASSERT_EQ(mpi_runs.size(), after.size());
  int from_rank1 = 0, from_rank2 = 0;
  for (const auto& [seed, rec] : mpi_runs) {
    ASSERT_EQ(after.count(seed), 1u);
    EXPECT_EQ(rec.metrics.value("shear_strength_pa", 0.0), after.at(seed).metrics.value("shear_strength_pa", 0.0));
    from_rank1 += rec.metrics.value("mpi_rank", 0) == 1;
    from_rank2 += rec.metrics.value("mpi_rank", 0) == 2;
  }
  EXPECT_EQ(from_rank1 + from_rank2, static_cast<int>(mpi_runs.size())) << "a run not from a worker rank";
  EXPECT_GT(from_rank1, 0);
  EXPECT_GT(from_rank2, 0);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace seedcal::testing
