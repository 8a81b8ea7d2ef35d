#include "common/process/shm_cleanup.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

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
