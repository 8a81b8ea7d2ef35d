// The init of the QEMU guest in which the socketcan tests meet real kernel CAN (qemu_run.sh).
// It runs as PID 1 from the initramfs that guest_image.sh assembles:
//   1. loads the modules listed in /modules/order (dependencies first: virtio, 9p, can, vcan),
//   2. mounts the host's root (9p, tag "hostroot") and makes it the root, with the guest's own
//      proc, sys, dev and a tmpfs on /dev/shm and /run, so no shared memory or temporary file
//      the command leaves outlives the guest: its TMPDIR is /run/tmp (/tmp stays the host's,
//      since a build tree may be there, but without the host's iceoryx files: the guest's
//      RouDi keeps its own there, and a socket over 9p does not connect),
//   3. brings up lo and the vcan interfaces named by `mcnc.can=` (default vcan0),
//   4. runs `/bin/bash <mcnc.work>/command` on the console, writes its exit code to
//      <mcnc.work>/status, and powers the guest off.
// Every step says on the console what failed and why; a failed step powers off without a
// status, which the runner reports as "kernel CAN could not be had". Static, so that it needs
// nothing of the host's root before that root is mounted.
#include "roudi/iceoryx_tmp.hpp"

#include <fcntl.h>
#include <sys/mount.h>
#include <sys/reboot.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

constexpr const char* kNewRoot = "/newroot";

double uptime_s() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

void say(const std::string& line) {
  const std::string text = "mcnc-guest: " + line + "\n";
  (void)!write(STDOUT_FILENO, text.data(), text.size());
}

[[noreturn]] void power_off() {
  sync();
  reboot(RB_POWER_OFF);
  // Only reached when the kernel refused: PID 1 must not return.
  for (;;) {
    pause();
  }
}

[[noreturn]] void fail(const std::string& what) {
  say("FAILED: " + what);
  power_off();
}

std::string errno_text() {
  return std::strerror(errno);
}

void must_mount(const char* source, const std::string& target, const char* type,
                unsigned long flags, const char* data) {
  mkdir(target.c_str(), 0755);  // may exist already
  if (mount(source, target.c_str(), type, flags, data) != 0) {
    fail("mount " + std::string(type) + " on " + target + ": " + errno_text());
  }
}

// The value of `key=` on the kernel command line, or `fallback`.
std::string boot_parameter(const std::string& cmdline, const std::string& key,
                           const std::string& fallback) {
  std::istringstream words(cmdline);
  std::string word;
  while (words >> word) {
    if (word.rfind(key + "=", 0) == 0) {
      return word.substr(key.size() + 1);
    }
  }
  return fallback;
}

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, sep)) {
    if (!part.empty()) {
      parts.push_back(part);
    }
  }
  return parts;
}

int load_modules() {
  std::ifstream order("/modules/order");
  if (!order) {
    fail("no /modules/order in the initramfs");
  }
  int loaded = 0;
  std::string name;
  while (std::getline(order, name)) {
    if (name.empty()) {
      continue;
    }
    const std::string path = "/modules/" + name;
    const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
      fail("open " + path + ": " + errno_text());
    }
    // finit_module: the module comes from the file, with no parameters. EEXIST: built in or
    // already there.
    if (syscall(SYS_finit_module, fd, "", 0) != 0 && errno != EEXIST) {
      fail("load module " + name + ": " + errno_text());
    }
    close(fd);
    ++loaded;
  }
  return loaded;
}

// Runs argv to its end; its exit code, 128 + signal when a signal ended it. Orphans that PID 1
// inherits meanwhile are reaped as they end.
int run(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (const auto& a : args) {
    argv.push_back(const_cast<char*>(a.c_str()));
  }
  argv.push_back(nullptr);
  const pid_t child = fork();
  if (child < 0) {
    fail("fork: " + errno_text());
  }
  if (child == 0) {
    execvp(argv[0], argv.data());
    std::fprintf(stderr, "mcnc-guest: exec %s: %s\n", argv[0], std::strerror(errno));
    _exit(127);
  }
  for (;;) {
    int status = 0;
    const pid_t ended = waitpid(-1, &status, 0);
    if (ended < 0 && errno == EINTR) {
      continue;
    }
    if (ended < 0) {
      fail("wait: " + errno_text());
    }
    if (ended == child) {
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
  }
}

void must_run(const std::vector<std::string>& args) {
  const int code = run(args);
  if (code != 0) {
    std::string line;
    for (const auto& a : args) {
      line += a + " ";
    }
    fail(line + "exited with " + std::to_string(code));
  }
}

}  // namespace

int main() {
  // The built-in initramfs has /dev/console; a devtmpfs gives the rest.
  must_mount("devtmpfs", "/dev", "devtmpfs", 0, nullptr);
  const int console = open("/dev/console", O_RDWR);
  if (console >= 0) {
    dup2(console, STDIN_FILENO);
    dup2(console, STDOUT_FILENO);
    dup2(console, STDERR_FILENO);
    if (console > STDERR_FILENO) {
      close(console);
    }
  }
  must_mount("proc", "/proc", "proc", 0, nullptr);
  std::string cmdline;
  std::getline(std::ifstream("/proc/cmdline"), cmdline);
  const std::string work = boot_parameter(cmdline, "mcnc.work", "");
  const std::vector<std::string> buses = split(boot_parameter(cmdline, "mcnc.can", "vcan0"), ',');
  if (work.empty()) {
    fail("no mcnc.work= on the kernel command line");
  }

  const int modules = load_modules();

  must_mount("hostroot", kNewRoot, "9p", 0,
             "trans=virtio,version=9p2000.L,msize=262144,cache=loose");
  const std::string root = kNewRoot;
  must_mount("proc", root + "/proc", "proc", 0, nullptr);
  must_mount("sysfs", root + "/sys", "sysfs", 0, nullptr);
  must_mount("devtmpfs", root + "/dev", "devtmpfs", 0, nullptr);
  must_mount("devpts", root + "/dev/pts", "devpts", 0, nullptr);
  // The guest's own: what the command leaves in shared memory goes with the guest.
  must_mount("tmpfs", root + "/dev/shm", "tmpfs", 0, "mode=1777");
  must_mount("tmpfs", root + "/run", "tmpfs", 0, "mode=0755");
  // Temporary files in the guest's memory: a candump record written over 9p lost frames.
  mkdir((root + "/run/tmp").c_str(), 01777);
  chmod((root + "/run/tmp").c_str(), 01777);  // past the umask
  if (const std::string why = mcnc::test::cover_iceoryx_files(root + "/tmp"); !why.empty()) {
    fail(why);
  }
  if (chroot(kNewRoot) != 0 || chdir("/") != 0) {
    fail("chroot to the host's root: " + errno_text());
  }
  setenv("PATH", "/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin", 1);
  setenv("HOME", "/root", 1);
  setenv("TMPDIR", "/run/tmp", 1);

  must_run({"ip", "link", "set", "lo", "up"});
  for (const auto& bus : buses) {
    must_run({"ip", "link", "add", "dev", bus, "type", "vcan"});
    must_run({"ip", "link", "set", bus, "up"});
  }
  std::string names;
  for (const auto& bus : buses) {
    names += " " + bus;
  }
  char up[64];
  std::snprintf(up, sizeof up, "%.2f", uptime_s());
  say("up at " + std::string(up) + " s: " + std::to_string(modules) + " modules, the host's root," +
      names + "; the command starts");

  const double started = uptime_s();
  const int code = run({"/bin/bash", work + "/command"});
  char took[64];
  std::snprintf(took, sizeof took, "%.2f", uptime_s() - started);
  // The runner made the file; writing into it needs no change of owner over 9p.
  const std::string status_path = work + "/status";
  const std::string status = std::to_string(code) + "\n";
  const int fd = open(status_path.c_str(), O_WRONLY | O_TRUNC | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0 || write(fd, status.data(), status.size()) != static_cast<ssize_t>(status.size()) ||
      close(fd) != 0) {
    fail("write " + status_path + ": " + errno_text());
  }
  say("the command ended with exit code " + std::to_string(code) + " after " + took +
      " s; powering off");
  power_off();
}
