#include "common/security/pki/pki.hpp"

#include <openssl/bio.h>
#include <openssl/bn.h>
#include <openssl/err.h>
#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/pkcs7.h>
#include <openssl/rand.h>
#include <openssl/x509.h>
#include <openssl/x509v3.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace mcnc::security {

namespace {

template <auto Free>
struct Freer {
  template <class T>
  void operator()(T* p) const noexcept {
    Free(p);
  }
};
using Bio = std::unique_ptr<BIO, Freer<BIO_free_all>>;
using Key = std::unique_ptr<EVP_PKEY, Freer<EVP_PKEY_free>>;
using Cert = std::unique_ptr<X509, Freer<X509_free>>;
using Store = std::unique_ptr<X509_STORE, Freer<X509_STORE_free>>;
using StoreContext = std::unique_ptr<X509_STORE_CTX, Freer<X509_STORE_CTX_free>>;
using Pkcs7 = std::unique_ptr<PKCS7, Freer<PKCS7_free>>;

// OpenSSL's last error as text (its queue emptied), or `fallback` when it has none.
std::string ssl_reason(const char* fallback) {
  const unsigned long code = ERR_peek_last_error();
  ERR_clear_error();
  if (code == 0) {
    return fallback;
  }
  char text[256];
  ERR_error_string_n(code, text, sizeof(text));
  return text;
}

[[noreturn]] void fail(const std::string& what) {
  throw std::runtime_error(what + ": " + ssl_reason("OpenSSL failed"));
}

Bio memory_of(const std::string& text) {
  Bio bio(BIO_new_mem_buf(text.data(), static_cast<int>(text.size())));
  if (!bio) {
    fail("cannot make a memory buffer");
  }
  return bio;
}

Bio new_memory() {
  Bio bio(BIO_new(BIO_s_mem()));
  if (!bio) {
    fail("cannot make a memory buffer");
  }
  return bio;
}

std::string text_of(BIO* bio) {
  char* data = nullptr;
  const long size = BIO_get_mem_data(bio, &data);
  return std::string(data, static_cast<std::size_t>(size));
}

Key read_key(const std::string& pem) {
  Bio bio = memory_of(pem);
  return Key(PEM_read_bio_PrivateKey(bio.get(), nullptr, nullptr, nullptr));
}

Cert read_certificate(const std::string& pem) {
  Bio bio = memory_of(pem);
  return Cert(PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr));
}

void add_extension(X509* cert, X509* issuer, int nid, const char* value) {
  X509V3_CTX ctx;
  X509V3_set_ctx_nodb(&ctx);
  X509V3_set_ctx(&ctx, issuer, cert, nullptr, nullptr, 0);
  X509_EXTENSION* extension = X509V3_EXT_conf_nid(nullptr, &ctx, nid, value);
  const bool added = extension != nullptr && X509_add_ext(cert, extension, -1) == 1;
  X509_EXTENSION_free(extension);
  if (!added) {
    fail(std::string("cannot add the extension ") + value);
  }
}

void set_time(ASN1_TIME* field, TimePoint time) {
  if (ASN1_TIME_set(field, std::chrono::system_clock::to_time_t(time)) == nullptr) {
    fail("cannot set a validity time");
  }
}

// A certificate of `key` for CN=`common_name`, issued by `issuer` (itself when null) and signed
// with `issuer_key`.
KeyAndCertificate make_certificate(Key key, const std::string& common_name, X509* issuer,
                                   EVP_PKEY* issuer_key, TimePoint not_before,
                                   TimePoint not_after) {
  if (!key) {
    fail("cannot make an EC P-256 key");
  }
  Cert cert(X509_new());
  if (!cert || X509_set_version(cert.get(), 2) != 1) {
    fail("cannot make a certificate");
  }
  unsigned char serial[16];
  if (RAND_bytes(serial, sizeof(serial)) != 1) {
    fail("no random serial number");
  }
  serial[0] &= 0x7f;  // a positive INTEGER
  BIGNUM* number = BN_bin2bn(serial, sizeof(serial), nullptr);
  const bool serial_set =
      number != nullptr && BN_to_ASN1_INTEGER(number, X509_get_serialNumber(cert.get())) != nullptr;
  BN_free(number);
  if (!serial_set) {
    fail("cannot set the serial number");
  }
  if (X509_NAME_add_entry_by_txt(X509_get_subject_name(cert.get()), "CN", MBSTRING_UTF8,
                                 reinterpret_cast<const unsigned char*>(common_name.c_str()), -1,
                                 -1, 0) != 1) {
    fail("cannot set the subject CN=" + common_name);
  }
  const bool ca = issuer == nullptr;
  X509* signer = ca ? cert.get() : issuer;
  if (X509_set_issuer_name(cert.get(), X509_get_subject_name(signer)) != 1 ||
      X509_set_pubkey(cert.get(), key.get()) != 1) {
    fail("cannot set the issuer or the key");
  }
  set_time(X509_getm_notBefore(cert.get()), not_before);
  set_time(X509_getm_notAfter(cert.get()), not_after);
  add_extension(cert.get(), signer, NID_basic_constraints, ca ? "critical,CA:TRUE" : "CA:FALSE");
  add_extension(cert.get(), signer, NID_key_usage,
                ca ? "critical,keyCertSign,cRLSign,digitalSignature" : "critical,digitalSignature");
  add_extension(cert.get(), signer, NID_subject_key_identifier, "hash");
  if (X509_sign(cert.get(), ca ? key.get() : issuer_key, EVP_sha256()) == 0) {
    fail("cannot sign the certificate of CN=" + common_name);
  }
  Bio key_out = new_memory();
  Bio cert_out = new_memory();
  if (PEM_write_bio_PrivateKey(key_out.get(), key.get(), nullptr, nullptr, 0, nullptr, nullptr) !=
          1 ||
      PEM_write_bio_X509(cert_out.get(), cert.get()) != 1) {
    fail("cannot write the key or certificate of CN=" + common_name);
  }
  return KeyAndCertificate{text_of(key_out.get()), text_of(cert_out.get())};
}

// The whole file, or the reason it cannot be read (path first).
std::optional<std::string> read_file(const std::string& path, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = path + ": cannot read: " + std::strerror(errno);
    return std::nullopt;
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) {
    error = path + ": cannot read";
    return std::nullopt;
  }
  return text.str();
}

// The certificate in the file at `path`; null, and the reason in `error`, when there is none.
Cert load_certificate(const std::string& path, std::string& error) {
  const auto text = read_file(path, error);
  if (!text) {
    return nullptr;
  }
  Cert cert = read_certificate(*text);
  if (!cert) {
    error = path + ": not a PEM certificate";
  }
  return cert;
}

// A signed document's content when `ca` signed it; else nullopt and the reason.
std::optional<std::string> verified_document(const std::string& signed_text, X509* ca,
                                             std::string& reason) {
  Bio in = memory_of(signed_text);
  BIO* content_raw = nullptr;
  Pkcs7 p7(SMIME_read_PKCS7(in.get(), &content_raw));
  Bio content(content_raw);
  if (!p7) {
    reason = "not an S/MIME signed document (" + ssl_reason("no signature") + ")";
    return std::nullopt;
  }
  Store store(X509_STORE_new());
  if (!store || X509_STORE_add_cert(store.get(), ca) != 1) {
    fail("cannot make a certificate store");
  }
  Bio out = new_memory();
  if (PKCS7_verify(p7.get(), nullptr, store.get(), content.get(), out.get(), PKCS7_TEXT) != 1) {
    reason = "not signed by the machine's CA (" + ssl_reason("bad signature") + ")";
    return std::nullopt;
  }
  return text_of(out.get());
}

}  // namespace

KeyAndCertificate make_ca(const std::string& common_name, TimePoint not_before,
                          TimePoint not_after) {
  return make_certificate(Key(EVP_EC_gen("P-256")), common_name, nullptr, nullptr, not_before,
                          not_after);
}

KeyAndCertificate make_identity(const KeyAndCertificate& ca, const std::string& common_name,
                                TimePoint not_before, TimePoint not_after) {
  Cert ca_cert = read_certificate(ca.certificate_pem);
  Key ca_key = read_key(ca.key_pem);
  if (!ca_cert || !ca_key) {
    fail("cannot read the CA");
  }
  return make_certificate(Key(EVP_EC_gen("P-256")), common_name, ca_cert.get(), ca_key.get(),
                          not_before, not_after);
}

std::string sign_document(const KeyAndCertificate& ca, const std::string& document) {
  Cert ca_cert = read_certificate(ca.certificate_pem);
  Key ca_key = read_key(ca.key_pem);
  if (!ca_cert || !ca_key) {
    fail("cannot read the CA");
  }
  const int flags = PKCS7_DETACHED | PKCS7_TEXT | PKCS7_STREAM;
  Bio in = memory_of(document);
  Pkcs7 p7(PKCS7_sign(ca_cert.get(), ca_key.get(), nullptr, in.get(), flags));
  if (!p7) {
    fail("cannot sign a document");
  }
  Bio content = memory_of(document);  // PKCS7_STREAM reads the content again while writing
  Bio out = new_memory();
  if (SMIME_write_PKCS7(out.get(), p7.get(), content.get(), flags) != 1) {
    fail("cannot write a signed document");
  }
  return text_of(out.get());
}

std::optional<std::string> check_identity(const IdentityFiles& files, TimePoint now) {
  std::string error;
  Cert ca = load_certificate(files.ca_certificate, error);
  if (!ca) {
    return error;
  }
  Cert cert = load_certificate(files.certificate, error);
  if (!cert) {
    return error;
  }
  Store store(X509_STORE_new());
  StoreContext context(X509_STORE_CTX_new());
  if (!store || !context || X509_STORE_add_cert(store.get(), ca.get()) != 1 ||
      X509_STORE_CTX_init(context.get(), store.get(), cert.get(), nullptr) != 1) {
    fail("cannot make a certificate store");
  }
  X509_STORE_CTX_set_time(context.get(), 0, std::chrono::system_clock::to_time_t(now));
  if (X509_verify_cert(context.get()) != 1) {
    const int code = X509_STORE_CTX_get_error(context.get());
    return files.certificate + ": " + X509_verify_cert_error_string(code) +
           (code == X509_V_ERR_UNABLE_TO_GET_ISSUER_CERT_LOCALLY ||
                    code == X509_V_ERR_CERT_SIGNATURE_FAILURE
                ? " (not signed by the CA in " + files.ca_certificate + ")"
                : std::string());
  }
  const auto key_text = read_file(files.private_key, error);
  if (!key_text) {
    return error;
  }
  Key key = read_key(*key_text);
  ERR_clear_error();
  if (!key) {
    return files.private_key + ": not an unencrypted PEM private key";
  }
  if (X509_check_private_key(cert.get(), key.get()) != 1) {
    ERR_clear_error();
    return files.private_key + ": not the key of " + files.certificate;
  }
  Cert permissions_ca;
  if (files.permissions_ca != files.ca_certificate) {
    permissions_ca = load_certificate(files.permissions_ca, error);
    if (!permissions_ca) {
      return error;
    }
  }
  X509* signer = permissions_ca ? permissions_ca.get() : ca.get();
  for (const std::string* path : {&files.governance, &files.permissions}) {
    const auto signed_text = read_file(*path, error);
    if (!signed_text) {
      return error;
    }
    std::string reason;
    const auto document = verified_document(*signed_text, signer, reason);
    if (!document) {
      return *path + ": " + reason;
    }
    if (path == &files.permissions) {
      char subject[256];
      X509_NAME_oneline(X509_get_subject_name(cert.get()), subject, sizeof(subject));
      const std::string subject_name = subject[0] == '/' ? subject + 1 : subject;
      if (document->find("<subject_name>" + subject_name + "</subject_name>") ==
          std::string::npos) {
        return *path + ": grants nothing to " + subject_name + " (the subject of " +
               files.certificate + ")";
      }
    }
  }
  return std::nullopt;
}

std::string xml_date(TimePoint time) {
  const std::time_t t = std::chrono::system_clock::to_time_t(time);
  std::tm utc{};
  gmtime_r(&t, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%S", &utc);
  return text;
}

}  // namespace mcnc::security
