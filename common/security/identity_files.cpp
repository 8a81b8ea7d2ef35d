#include "common/security/identity_files.hpp"

namespace mcnc::security {

IdentityFiles identity_files(const std::string& dir, const std::string& identity) {
  IdentityFiles files;
  files.identity = identity;
  files.ca_certificate = dir + "/ca.pem";
  files.permissions_ca = files.ca_certificate;
  files.certificate = dir + "/identities/" + identity + ".pem";
  files.private_key = dir + "/identities/" + identity + ".key";
  files.governance = dir + "/governance.p7s";
  files.permissions = dir + "/permissions.p7s";
  return files;
}

std::string ca_key_file(const std::string& dir) {
  return dir + "/ca.key";
}

std::string governance_source_file(const std::string& dir) {
  return dir + "/governance.xml";
}

std::string permissions_source_file(const std::string& dir) {
  return dir + "/permissions.xml";
}

}  // namespace mcnc::security
