// A launcher's child inherits its standard streams and nothing else: not the sockets of the
// launcher's own DDS participant, which a child outliving the launcher would keep bound.
#include "launch/child_process.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

namespace {

std::string run_shell(const std::string& script, const std::string& output) {
  mcnc::launch::ChildProcess child("sh", {"/bin/sh", "-c", script});
  child.set_output(output);
  child.start({});
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!child.poll_exited() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_EQ(child.exit_code(), 0);
  std::ifstream in(output);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ChildProcess, InheritsOnlyTheStandardStreams) {
  // Opened without close-on-exec, as DDS implementations open their sockets.
  const int fd = ::open("/dev/null", O_RDONLY);
  ASSERT_GE(fd, 3);
  char dir[] = "/tmp/mcnc_child_fd_XXXXXX";
  ASSERT_NE(::mkdtemp(dir), nullptr);
  const std::string out = std::string(dir) + "/out";
  const std::string n = std::to_string(fd);
  // `test` is the shell's own: /proc/self is the child itself.
  EXPECT_EQ(
      run_shell("if test -e /proc/self/fd/" + n + "; then echo open; else echo closed; fi", out),
      "closed\n");
  // Its standard output is the file it was given, and standard error goes there too.
  EXPECT_EQ(run_shell("echo to-out; echo to-err >&2", out), "to-out\nto-err\n");
  ::close(fd);
  std::remove(out.c_str());
  ::rmdir(dir);
}

}  // namespace
