// A study's fingerprint (the key `--resume` checks a study directory against) depends on what the
// study reads, not on how its path was spelt: relative or absolute, through "..", through a
// symbolic link, or from another working directory.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
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
  const std::string clump_edited = fingerprint_of((dir / kStudy).string());
  EXPECT_NE(clump_edited, before);
  {  // the variety the scenes name (their seed's values and clump models)
    std::ofstream variety(dir / "data" / "varieties" / "jinong1.toml", std::ios::app);
    variety << "\n# edited\n";
  }
  EXPECT_NE(fingerprint_of((dir / kStudy).string()), clump_edited);
  fs::remove_all(dir);
}

// A study-wide `variety` reaches every scene under every model (a variety=FILE override first), and
// the seed it names is part of the fingerprint.
TEST(StudyFingerprint, AStudyWideVarietyGoesToEveryScene) {
  const fs::path root = fs::weakly_canonical(testing::source_dir());
  const fs::path dir = fs::temp_directory_path() / ("seedcal-fingerprint-variety-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy(root / "data", dir / "data", fs::copy_options::recursive);
  const fs::path study = dir / "data" / "studies" / "jinong1-quick.toml";
  const std::string before = fingerprint_of(study.string());
  std::string text;
  {
    std::ifstream in(study);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  {
    std::ofstream out(study);
    out << "variety = \"../varieties/jinong3.toml\"\n" << text;
  }
  const StudyConfig s = read_study(study.string());
  EXPECT_EQ(s.variety_file, (dir / "data" / "varieties" / "jinong3.toml").lexically_normal().string());
  for (const StudyModel& m : s.models) {
    ASSERT_FALSE(m.sets.empty());
    EXPECT_EQ(m.sets.front(), "variety=" + s.variety_file);
  }
  EXPECT_NE(study_fingerprint(s), before);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace seedcal
