// A study's fingerprint (the key `--resume` checks a study directory against) depends on what the
// study reads, not on how its path was spelt: relative or absolute, through "..", through a
// symbolic link, or from another working directory.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "calibrate/pipeline/study_config.hpp"
#include "tests/support/cli.hpp"

namespace seedcal {
namespace {

namespace fs = std::filesystem;

// Restores the working directory when a test changes it.
class InDirectory {
 public:
  explicit InDirectory(const fs::path& dir) : saved_(fs::current_path()) { fs::current_path(dir); }
  ~InDirectory() { fs::current_path(saved_); }
  InDirectory(const InDirectory&) = delete;
  InDirectory& operator=(const InDirectory&) = delete;

 private:
  fs::path saved_;
};

std::string fingerprint_of(const std::string& study_file) { return study_fingerprint(read_study(study_file)); }

const fs::path kStudy = fs::path("data") / "studies" / "jinong1-paper.toml";  // scenes and clumps by "../"

TEST(StudyFingerprint, DoesNotDependOnHowTheStudyPathIsSpelt) {
  const fs::path root = fs::weakly_canonical(testing::source_dir());
  const std::string absolute = fingerprint_of((root / kStudy).string());
  EXPECT_EQ(absolute.size(), 16u);
  EXPECT_EQ(fingerprint_of((root / "data" / "scenes" / ".." / "studies" / kStudy.filename()).string()), absolute);
  {
    InDirectory here(root);
    EXPECT_EQ(fingerprint_of(kStudy.string()), absolute);
  }
  {
    InDirectory here(root / "data" / "scenes");
    EXPECT_EQ(fingerprint_of((fs::path("..") / "studies" / kStudy.filename()).string()), absolute);
  }
  const fs::path link = fs::temp_directory_path() / ("seedcal-fingerprint-" + std::to_string(::getpid()));
  fs::remove(link);
  fs::create_directory_symlink(root / "data", link);
  EXPECT_EQ(fingerprint_of((link / "studies" / kStudy.filename()).string()), absolute);
  fs::remove(link);
}

// The older rule (kept to accept the stores it fingerprinted on resume): the files named as the
// paths were spelt, so a relative and an absolute spelling differ there and agree here.
TEST(StudyFingerprint, EarlierBuildsRuleDependsOnTheSpelling) {
  const fs::path root = fs::weakly_canonical(testing::source_dir());
  const StudyConfig absolute = read_study((root / kStudy).string());
  InDirectory here(root);
  const StudyConfig relative = read_study(kStudy.string());
  EXPECT_NE(study_fingerprint_as_spelt(relative), study_fingerprint_as_spelt(absolute));
  EXPECT_EQ(study_fingerprint(relative), study_fingerprint(absolute));
  EXPECT_NE(study_fingerprint_as_spelt(relative), study_fingerprint(relative));
}

TEST(StudyFingerprint, ChangesWithAClumpFileTheStudyReads) {
  const fs::path root = fs::weakly_canonical(testing::source_dir());
  const fs::path dir = fs::temp_directory_path() / ("seedcal-fingerprint-copy-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy(root / "data", dir / "data", fs::copy_options::recursive);
  const std::string before = fingerprint_of((dir / kStudy).string());
  EXPECT_EQ(before, fingerprint_of((root / kStudy).string())) << "a copy of the same files is the same study";
  {
    std::ofstream clump(dir / "data" / "clumps" / "jinong1-manual-7.toml", std::ios::app);
    clump << "\n# edited\n";
  }
  EXPECT_NE(fingerprint_of((dir / kStudy).string()), before);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace seedcal
