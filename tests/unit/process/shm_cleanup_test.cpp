#include "common/process/shm_cleanup.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

namespace fs = std::filesystem;

namespace {
std::string shm(const std::string& name) {
  return "/dev/shm/" + name;
}
}  // namespace

TEST(ShmCleanup, RemovesSegmentsWhoseLockIsFreeAndKeepsLockedOnes) {
  const std::string tag = std::to_string(getpid());
  const std::string stale = "fastrtps_mcnctest_stale_" + tag;
  const std::string live = "fastrtps_mcnctest_live_" + tag;
  for (const auto& name : {stale, live}) {
    std::ofstream(shm(name)) << "segment";
    std::ofstream(shm(name + "_el"));
  }
  std::ofstream(shm("sem." + stale + "_mutex")) << "sem";
  // A live owner holds the lock file.
  const int fd = ::open(shm(live + "_el").c_str(), O_RDONLY);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX), 0);

  EXPECT_GE(mcnc::process::remove_stale_dds_shm_files(), 1U);
  EXPECT_FALSE(fs::exists(shm(stale)));
  EXPECT_FALSE(fs::exists(shm(stale + "_el")));
  EXPECT_FALSE(fs::exists(shm("sem." + stale + "_mutex")));
  EXPECT_TRUE(fs::exists(shm(live)));
  EXPECT_TRUE(fs::exists(shm(live + "_el")));

  ::close(fd);
  fs::remove(shm(live));
  fs::remove(shm(live + "_el"));
}

// After a run, its launcher removes what the run left, and nothing of another run's: files that
// were there before, ports of other domains, other participants' data-sharing files and files
// still in use stay.
TEST(ShmCleanup, ARunRemovesOnlyWhatItLeftAndNoLongerUses) {
  const fs::path dir = fs::temp_directory_path() / ("mcnc_shm_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string d = dir.string() + "/";
  const auto touch = [&](const std::string& name) { std::ofstream(d + name) << "x"; };
  touch("fastrtps_port57401");  // domain 200's, before the run
  touch("unrelated_file");
  mcnc::process::RunShmFootprint run(200, d);

  // During the run: domain 200's ports (one still in use), another domain's port, a run
  // process's data-sharing segment and another participant's.
  for (const char* name :
       {"fastrtps_port57410", "sem.fastrtps_port57410_mutex", "fastrtps_port57412",
        "fastrtps_port57650", "fast_datasharing_01.0f.aa_0.0.1.3",
        "fast_datasharing_01.0f.bb_0.0.1.3", "unrelated_new"}) {
    touch(name);
  }
  // The run's process maps its data-sharing segment (as /proc/<pid>/maps would say).
  const int fd = ::open((d + "fast_datasharing_01.0f.aa_0.0.1.3").c_str(), O_RDONLY);
  ASSERT_GE(fd, 0);
  run.note_process(getpid());
  ::close(fd);

  const std::set<std::string> in_use{d + "fastrtps_port57412"};
  EXPECT_EQ(run.remove_left_over(in_use), 3U);
  EXPECT_FALSE(fs::exists(d + "fastrtps_port57410"));
  EXPECT_FALSE(fs::exists(d + "sem.fastrtps_port57410_mutex"));
  EXPECT_FALSE(fs::exists(d + "fast_datasharing_01.0f.aa_0.0.1.3"));
  EXPECT_TRUE(fs::exists(d + "fastrtps_port57401")) << "there before the run";
  EXPECT_TRUE(fs::exists(d + "fastrtps_port57412")) << "in use";
  EXPECT_TRUE(fs::exists(d + "fastrtps_port57650")) << "domain 201's";
  EXPECT_TRUE(fs::exists(d + "fast_datasharing_01.0f.bb_0.0.1.3")) << "not the run's";
  EXPECT_TRUE(fs::exists(d + "unrelated_new"));
  fs::remove_all(dir);
}

// A launcher killed with `kill -9` removes nothing: the record of its run's footprint it kept
// lets the next run of the same domain remove what it left (its recorded files and the domain's
// ports that no process uses), and nothing of another run's.
TEST(ShmCleanup, TheNextRunOfTheDomainRemovesWhatAKilledRunLeft) {
  const fs::path dir = fs::temp_directory_path() / ("mcnc_shm_kill_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string d = dir.string() + "/";
  const auto touch = [&](const std::string& name) { std::ofstream(d + name) << "x"; };
  const std::string own = "fast_datasharing_01.0f.aa_0.0.1.3";
  const std::string others = "fast_datasharing_01.0f.bb_0.0.1.3";
  touch(own);
  touch(others);
  touch("fastrtps_port57410");  // domain 200's
  touch("fastrtps_port57650");  // domain 201's
  {
    // The killed run: its launcher noted its files, then was killed (its record stays and
    // names a launcher that is gone).
    mcnc::process::RunShmFootprint killed(200, d);
    const int fd = ::open((d + own).c_str(), O_RDONLY);
    ASSERT_GE(fd, 0);
    killed.note_process(getpid());
    ::close(fd);
  }
  const std::string record = d + "mcnc_run_domain200_" + std::to_string(getpid());
  ASSERT_TRUE(fs::exists(record));
  // The killed launcher's: a pid no process has (above the kernel's pid limit).
  const std::string killed_record = d + "mcnc_run_domain200_99999999";
  fs::rename(record, killed_record);
  // Another domain's next run touches nothing of it.
  { mcnc::process::RunShmFootprint other(201, d); }
  EXPECT_TRUE(fs::exists(d + own));
  mcnc::process::RunShmFootprint next(200, d);
  EXPECT_EQ(next.removed_at_start(), (std::set<std::string>{own, "fastrtps_port57410"}));
  EXPECT_FALSE(fs::exists(killed_record));
  EXPECT_TRUE(fs::exists(d + others)) << "not the killed run's";
  EXPECT_TRUE(fs::exists(d + "fastrtps_port57650")) << "domain 201's";
  fs::remove_all(dir);
}

// A record whose launcher still runs is another launcher's run in progress: left alone.
TEST(ShmCleanup, ARecordOfALauncherThatStillRunsIsLeftAlone) {
  const fs::path dir = fs::temp_directory_path() / ("mcnc_shm_live_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string d = dir.string() + "/";
  std::ofstream(d + "fastrtps_port57410") << "x";
  std::ofstream(d + "mcnc_run_domain200_" + std::to_string(getpid())) << "fastrtps_port57410\n";
  mcnc::process::RunShmFootprint next(200, d);
  EXPECT_TRUE(next.removed_at_start().empty());
  EXPECT_TRUE(fs::exists(d + "fastrtps_port57410"));
  fs::remove_all(dir);
}
