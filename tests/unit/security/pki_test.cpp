#include "common/security/pki/pki.hpp"

#include "common/security/identity_files.hpp"
#include "common/security/machine_permissions.hpp"
#include "tools/certs/certs_command.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace mcnc;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;
namespace fs = std::filesystem;

namespace {

const std::string kSourceDir = MCNC_SOURCE_DIR;
const auto kNow = std::chrono::system_clock::now();
const auto kDay = std::chrono::hours(24);

class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "mcnc-pki-XXXXXX").string();
    path_ = ::mkdtemp(pattern.data());
  }
  ~TempDir() { fs::remove_all(path_); }
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
};

void write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The files of one identity, made by hand as `mcnc certs` would, for the cases it never makes.
struct Pki {
  TempDir dir;
  security::KeyAndCertificate ca = security::make_ca("CA.m", kNow - 10 * kDay, kNow + 10 * kDay);
  security::IdentityFiles files = security::identity_files(dir.path(), "CH1");

  Pki() {
    fs::create_directories(dir.path() + "/identities");
    write(files.ca_certificate, ca.certificate_pem);
    set_identity(security::make_identity(ca, "CH1.m", kNow - kDay, kNow + kDay));
    write(files.governance,
          security::sign_document(ca, security::governance_xml(security::Protection::sign)));
    write(files.permissions,
          security::sign_document(ca,
                                  security::permissions_xml(
                                      "m", {security::Identity{"CH1", security::Role::channel, {}}},
                                      {"2026-01-01T00:00:00", "2036-01-01T00:00:00"})));
  }
  void set_identity(const security::KeyAndCertificate& identity) const {
    write(files.certificate, identity.certificate_pem);
    write(files.private_key, identity.key_pem);
  }
};

// Why check_identity refuses the files at kNow ("accepted" when it does not).
std::string refusal(const Pki& pki) {
  return security::check_identity(pki.files, kNow).value_or("accepted");
}

}  // namespace

TEST(Pki, AnIdentityMadeByTheCaChecksGood) {
  Pki pki;
  EXPECT_EQ(security::check_identity(pki.files, kNow), std::nullopt);
}

TEST(Pki, AnExpiredCertificateIsRefusedNamingIt) {
  Pki pki;
  pki.set_identity(security::make_identity(pki.ca, "CH1.m", kNow - 3 * kDay, kNow - kDay));
  EXPECT_THAT(refusal(pki), AllOf(StartsWith(pki.files.certificate + ": "), HasSubstr("expired")));
  // The same files hold at a time within the validity.
  EXPECT_EQ(security::check_identity(pki.files, kNow - 2 * kDay), std::nullopt);
}

TEST(Pki, ACertificateOfAnotherCaIsRefusedNamingItAndTheCa) {
  Pki pki;
  const auto other_ca = security::make_ca("CA.other", kNow - kDay, kNow + kDay);
  pki.set_identity(security::make_identity(other_ca, "CH1.m", kNow - kDay, kNow + kDay));
  EXPECT_THAT(refusal(pki),
              AllOf(StartsWith(pki.files.certificate + ": "), HasSubstr(pki.files.ca_certificate)));
}

TEST(Pki, AMissingOrForeignOrUnreadableKeyIsRefusedNamingIt) {
  Pki pki;
  fs::remove(pki.files.private_key);
  EXPECT_THAT(refusal(pki), StartsWith(pki.files.private_key + ": cannot read"));

  write(pki.files.private_key, "not a key\n");
  EXPECT_THAT(refusal(pki),
              StartsWith(pki.files.private_key + ": not an unencrypted PEM private key"));

  write(pki.files.private_key,
        security::make_identity(pki.ca, "CH1.m", kNow - kDay, kNow + kDay).key_pem);
  EXPECT_THAT(refusal(pki), StartsWith(pki.files.private_key + ": not the key of"));
}

TEST(Pki, DocumentsNotSignedByTheCaOrGrantingNothingAreRefusedNamingThem) {
  Pki pki;
  const auto other_ca = security::make_ca("CA.other", kNow - kDay, kNow + kDay);
  write(pki.files.governance,
        security::sign_document(other_ca, security::governance_xml(security::Protection::sign)));
  EXPECT_THAT(refusal(pki), StartsWith(pki.files.governance + ": not signed by the machine's CA"));

  write(pki.files.governance,
        security::sign_document(pki.ca, security::governance_xml(security::Protection::sign)));
  write(pki.files.permissions,
        security::sign_document(
            pki.ca,
            security::permissions_xml("m", {security::Identity{"CH2", security::Role::channel, {}}},
                                      {"2026-01-01T00:00:00", "2036-01-01T00:00:00"})));
  EXPECT_THAT(refusal(pki), StartsWith(pki.files.permissions + ": grants nothing to CN=CH1.m"));

  write(pki.files.permissions, "<dds/>\n");
  EXPECT_THAT(refusal(pki), StartsWith(pki.files.permissions + ": not an S/MIME signed document"));
}

TEST(CertsCommand, MakesACheckedIdentityPerProcessWithPrivateKeysAndRefusesToOverwrite) {
  TempDir dir;
  tools::CertsArguments args;
  args.machine_path = kSourceDir + "/launch/machines/twin_turret.yaml";
  args.dir = dir.path() + "/certs";
  ASSERT_EQ(tools::execute_certs(args), 0);
  const auto machine = config::load_machine_file(args.machine_path);
  for (const security::Identity& identity : security::machine_identities(machine)) {
    const auto files = security::identity_files(args.dir, identity.name);
    EXPECT_EQ(security::check_identity(files, std::chrono::system_clock::now()), std::nullopt)
        << identity.name;
    struct stat st {};
    ASSERT_EQ(::stat(files.private_key.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0600u) << files.private_key;
  }
  struct stat st {};
  ASSERT_EQ(::stat(security::ca_key_file(args.dir).c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  // The identities last --days, the CA longer.
  EXPECT_THAT(security::check_identity(security::identity_files(args.dir, "CH1"),
                                       std::chrono::system_clock::now() + 731 * kDay)
                  .value_or(""),
              HasSubstr("expired"));
  // A second run would make a new CA and lock the machine's processes out: refused.
  EXPECT_EQ(tools::execute_certs(args), 2);
  args.protection = "scramble";
  args.dir = dir.path() + "/other";
  EXPECT_EQ(tools::execute_certs(args), 2);
  EXPECT_FALSE(fs::exists(args.dir));
}
