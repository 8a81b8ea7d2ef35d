#include "tools/certs/certs_command.hpp"

#include "common/config/machine_config.hpp"
#include "common/security/identity_files.hpp"
#include "common/security/machine_permissions.hpp"
#include "common/security/pki/pki.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace mcnc::tools {

namespace {

// Private keys are readable by their owner only; the rest by anyone on the host.
constexpr mode_t kPublicFile = 0644;
constexpr mode_t kPrivateFile = 0600;
// Hosts whose clocks differ a little still accept a certificate made just now.
constexpr auto kClockSkew = std::chrono::hours(1);
constexpr auto kCaLifetime = std::chrono::days(3650);

void write_file(const std::string& path, const std::string& text, mode_t mode) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, mode);
  if (fd < 0) {
    throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
  }
  const bool written = ::fchmod(fd, mode) == 0 &&
                       ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  const int saved = errno;
  ::close(fd);
  if (!written) {
    throw std::runtime_error(path + ": cannot write: " + std::strerror(saved));
  }
}

std::optional<security::Protection> parse_protection(const std::string& name) {
  for (security::Protection p : {security::Protection::access_control, security::Protection::sign,
                                 security::Protection::encrypt}) {
    if (name == security::protection_name(p)) {
      return p;
    }
  }
  return std::nullopt;
}

}  // namespace

void add_certs_options(CLI::App& app, CertsArguments& args) {
  app.add_option("machine", args.machine_path, "machine file (YAML)")->required();
  app.add_option("dir", args.dir, "directory to make the CA, identities and documents in")
      ->required();
  app.add_option("--days", args.days, "how long the identities and grants hold (default 730)")
      ->check(CLI::Range(1, 36500));
  app.add_option("--protection", args.protection,
                 "access (authentication and access control), sign (default: also every "
                 "submessage signed) or encrypt (also encrypted)");
}

int execute_certs(const CertsArguments& args) {
  config::MachineConfig machine;
  try {
    machine = config::load_machine_file(args.machine_path);
  } catch (const config::ConfigError& error) {
    std::fprintf(stderr, "%s: %s\n", args.machine_path.c_str(), error.what());
    return 2;
  }
  const std::optional<security::Protection> protection = parse_protection(args.protection);
  if (!protection) {
    std::fprintf(stderr, "--protection must be access, sign or encrypt, not '%s'\n",
                 args.protection.c_str());
    return 2;
  }
  namespace fs = std::filesystem;
  const std::string dir = fs::absolute(args.dir).lexically_normal().string();
  std::error_code ec;
  if (fs::exists(security::ca_key_file(dir), ec) ||
      fs::exists(security::identity_files(dir, "").ca_certificate, ec)) {
    std::fprintf(stderr,
                 "%s already holds a machine's CA: remove it or name another directory (a new CA "
                 "would lock out every process still holding the old one's certificates)\n",
                 dir.c_str());
    return 2;
  }
  try {
    fs::create_directories(dir + "/identities");
    const auto now = std::chrono::system_clock::now();
    const auto not_before = now - kClockSkew;
    const auto not_after = now + std::chrono::days(args.days);
    const security::KeyAndCertificate ca =
        security::make_ca("CA." + machine.name, not_before, now + kCaLifetime);
    write_file(security::ca_key_file(dir), ca.key_pem, kPrivateFile);
    write_file(security::identity_files(dir, "").ca_certificate, ca.certificate_pem, kPublicFile);
    const std::vector<security::Identity> identities = security::machine_identities(machine);
    for (const security::Identity& identity : identities) {
      const security::KeyAndCertificate made = security::make_identity(
          ca, security::common_name(machine.name, identity.name), not_before, not_after);
      const security::IdentityFiles files = security::identity_files(dir, identity.name);
      write_file(files.private_key, made.key_pem, kPrivateFile);
      write_file(files.certificate, made.certificate_pem, kPublicFile);
    }
    const std::string governance = security::governance_xml(*protection);
    const std::string permissions = security::permissions_xml(
        machine.name, identities,
        security::Validity{security::xml_date(not_before), security::xml_date(not_after)});
    const security::IdentityFiles shared = security::identity_files(dir, "");
    write_file(security::governance_source_file(dir), governance, kPublicFile);
    write_file(shared.governance, security::sign_document(ca, governance), kPublicFile);
    write_file(security::permissions_source_file(dir), permissions, kPublicFile);
    write_file(shared.permissions, security::sign_document(ca, permissions), kPublicFile);
    std::printf(
        "mcnc certs: machine %s, %zu identities, protection %s, valid until %s UTC, in %s\n"
        "Keep %s off the machine: it signs new identities and permissions.\n",
        machine.name.c_str(), identities.size(), security::protection_name(*protection),
        security::xml_date(not_after).c_str(), dir.c_str(), security::ca_key_file(dir).c_str());
    if (machine.security_dir.empty()) {
      std::printf("%s names no security_dir: the machine runs unsecured until it names %s\n",
                  args.machine_path.c_str(), dir.c_str());
    } else if (fs::path(machine.security_dir).lexically_normal() != fs::path(dir)) {
      std::printf("%s names security_dir %s, not %s\n", args.machine_path.c_str(),
                  machine.security_dir.c_str(), dir.c_str());
    }
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "mcnc certs: %s\n", error.what());
    return 1;
  }
}

}  // namespace mcnc::tools
