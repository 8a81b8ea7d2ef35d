#pragma once
// The machine's certificates and signed documents, by OpenSSL's library: what `mcnc certs`
// makes and what every process checks before it joins the machine's domain.
#include "common/security/identity_files.hpp"

#include <chrono>
#include <optional>
#include <string>

namespace mcnc::security {

// A key pair and its certificate, both PEM.
struct KeyAndCertificate {
  std::string key_pem;
  std::string certificate_pem;
};

using TimePoint = std::chrono::system_clock::time_point;

// A self-signed CA (EC P-256, ECDSA with SHA-256) whose subject is CN=`common_name`.
// Throws std::runtime_error with OpenSSL's reason.
KeyAndCertificate make_ca(const std::string& common_name, TimePoint not_before,
                          TimePoint not_after);
// A certificate of a new key, CN=`common_name`, signed by `ca`.
KeyAndCertificate make_identity(const KeyAndCertificate& ca, const std::string& common_name,
                                TimePoint not_before, TimePoint not_after);
// `document` signed by `ca` as S/MIME (detached, text), as DDS Security's governance and
// permissions are.
std::string sign_document(const KeyAndCertificate& ca, const std::string& document);

// Whether the files of an identity let it join the machine at `now`: each file readable, the
// certificate signed by the CA and within its validity, the key the certificate's, the
// governance and permissions signed by the CA and the permissions granting the certificate's
// subject. nullopt when they do; else the reason, starting with the file's path.
std::optional<std::string> check_identity(const IdentityFiles& files, TimePoint now);

// "YYYY-MM-DDTHH:MM:SS" in UTC, as the permissions' validity writes a time.
std::string xml_date(TimePoint time);

}  // namespace mcnc::security
