#include "client/gateway/tls_certificate.hpp"

#include <fcntl.h>
#include <openssl/err.h>
#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/rand.h>
#include <openssl/ssl.h>
#include <openssl/x509.h>
#include <openssl/x509v3.h>
#include <unistd.h>

#include <arpa/inet.h>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace flagsim::gateway {
namespace {

namespace ssl = boost::asio::ssl;

constexpr long kValidDays = 397;  ///< the longest browsers accept for a server certificate

template <class T, void (*Free)(T*)>
struct Deleter {
  void operator()(T* p) const { Free(p); }
};
using X509Ptr = std::unique_ptr<X509, Deleter<X509, X509_free>>;
using KeyPtr = std::unique_ptr<EVP_PKEY, Deleter<EVP_PKEY, EVP_PKEY_free>>;
using ExtensionPtr = std::unique_ptr<X509_EXTENSION, Deleter<X509_EXTENSION, X509_EXTENSION_free>>;

/// OpenSSL's last error, in words; "" if none.
std::string OpenSslError() {
  const unsigned long code = ERR_get_error();
  if (code == 0) return "";
  char text[256];
  ERR_error_string_n(code, text, sizeof(text));
  ERR_clear_error();
  return text;
}

X509Ptr ReadCertificate(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "r");
  if (file == nullptr) return nullptr;
  X509Ptr certificate(PEM_read_X509(file, nullptr, nullptr, nullptr));
  std::fclose(file);
  return certificate;
}

/// SHA-256 of the certificate's DER bytes, as "AB:CD:...".
std::string Fingerprint(X509* certificate) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  X509_digest(certificate, EVP_sha256(), digest, &size);
  std::string text;
  char byte[4];
  for (unsigned int i = 0; i < size; ++i) {
    std::snprintf(byte, sizeof(byte), i + 1 < size ? "%02X:" : "%02X", digest[i]);
    text += byte;
  }
  return text;
}

bool IsIpAddress(const std::string& host) {
  unsigned char bytes[16];
  return inet_pton(AF_INET, host.c_str(), bytes) == 1 || inet_pton(AF_INET6, host.c_str(), bytes) == 1;
}

/// Whether `certificate` names every one of `hosts`.
bool Names(X509* certificate, const std::vector<std::string>& hosts) {
  for (const std::string& host : hosts) {
    const int named = IsIpAddress(host) ? X509_check_ip_asc(certificate, host.c_str(), 0)
                                        : X509_check_host(certificate, host.c_str(), host.size(), 0, nullptr);
    if (named != 1) return false;
  }
  return true;
}

void AddExtension(X509* certificate, int nid, const std::string& value) {
  X509V3_CTX context;
  X509V3_set_ctx_nodb(&context);
  X509V3_set_ctx(&context, certificate, certificate, nullptr, nullptr, 0);
  ExtensionPtr extension(X509V3_EXT_conf_nid(nullptr, &context, nid, value.c_str()));
  if (!extension || X509_add_ext(certificate, extension.get(), -1) != 1)
    throw std::runtime_error("cannot add " + value + " to a certificate: " + OpenSslError());
}

/// A P-256 key and a certificate signed by it, naming `hosts` (and localhost, 127.0.0.1).
std::pair<KeyPtr, X509Ptr> MakeSelfSigned(const std::vector<std::string>& hosts) {
  KeyPtr key(EVP_EC_gen("P-256"));
  X509Ptr certificate(X509_new());
  if (!key || !certificate) throw std::runtime_error("cannot make a key: " + OpenSslError());
  X509_set_version(certificate.get(), 2);
  unsigned char serial[16];
  RAND_bytes(serial, sizeof(serial));
  serial[0] &= 0x7F;  // positive
  BIGNUM* number = BN_bin2bn(serial, sizeof(serial), nullptr);
  BN_to_ASN1_INTEGER(number, X509_get_serialNumber(certificate.get()));
  BN_free(number);
  X509_gmtime_adj(X509_getm_notBefore(certificate.get()), -3600);
  X509_gmtime_adj(X509_getm_notAfter(certificate.get()), kValidDays * 24 * 3600);
  X509_set_pubkey(certificate.get(), key.get());
  X509_NAME* name = X509_get_subject_name(certificate.get());
  X509_NAME_add_entry_by_txt(name, "CN", MBSTRING_ASC, reinterpret_cast<const unsigned char*>("flagsim gateway"),
                             -1, -1, 0);
  X509_set_issuer_name(certificate.get(), name);
  std::string names = "DNS:localhost,IP:127.0.0.1";
  for (const std::string& host : hosts) {
    if (host != "localhost" && host != "127.0.0.1") names += (IsIpAddress(host) ? ",IP:" : ",DNS:") + host;
  }
  AddExtension(certificate.get(), NID_subject_alt_name, names);
  AddExtension(certificate.get(), NID_ext_key_usage, "serverAuth");
  if (X509_sign(certificate.get(), key.get(), EVP_sha256()) == 0)
    throw std::runtime_error("cannot sign a certificate: " + OpenSslError());
  return {std::move(key), std::move(certificate)};
}

/// Writes `path` readable by its owner only (`private_file`) or by all, with `write(file)`.
template <class Write>
void WritePem(const std::string& path, bool private_file, const Write& write) {
  const int descriptor = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, private_file ? 0600 : 0644);
  std::FILE* file = descriptor < 0 ? nullptr : fdopen(descriptor, "w");
  if (file == nullptr) throw std::runtime_error(path + ": cannot be written");
  const bool written = write(file) == 1;
  if (std::fclose(file) != 0 || !written) throw std::runtime_error(path + ": cannot be written");
}

}  // namespace

// certificate and key read and matched first, so that what is wrong is named; then the context
TlsSetup LoadTls(const std::string& certificate, const std::string& key) {
  const X509Ptr read = ReadCertificate(certificate);
  if (!read) throw std::runtime_error("--tls-cert " + certificate + ": not a PEM certificate that can be read");
  std::FILE* key_file = std::fopen(key.c_str(), "r");
  const KeyPtr read_key(key_file ? PEM_read_PrivateKey(key_file, nullptr, nullptr, nullptr) : nullptr);
  if (key_file) std::fclose(key_file);
  ERR_clear_error();
  if (!read_key) throw std::runtime_error("--tls-key " + key + ": not a PEM private key that can be read");
  if (X509_check_private_key(read.get(), read_key.get()) != 1) {
    ERR_clear_error();
    throw std::runtime_error("--tls-key " + key + " does not match the certificate in --tls-cert " + certificate);
  }
  auto context = std::make_shared<ssl::context>(ssl::context::tls_server);
  context->set_options(ssl::context::default_workarounds | ssl::context::no_sslv2 | ssl::context::no_sslv3 |
                       ssl::context::no_tlsv1 | ssl::context::no_tlsv1_1);
  boost::system::error_code error;
  context->use_certificate_chain_file(certificate, error);
  if (!error) context->use_private_key_file(key, ssl::context::pem, error);
  if (error) throw std::runtime_error("--tls-cert " + certificate + ", --tls-key " + key + ": " + error.message());
  return {context, certificate, Fingerprint(read.get()), false};
}

TlsSetup SelfSignedTls(const std::string& directory, const std::vector<std::string>& hosts) {
  const std::string certificate = directory + "/gateway.crt", key = directory + "/gateway.key";
  const X509Ptr existing = ReadCertificate(certificate);
  if (!existing || !Names(existing.get(), hosts) || X509_cmp_current_time(X509_get0_notAfter(existing.get())) <= 0 ||
      !std::filesystem::exists(key)) {
    std::error_code made;
    std::filesystem::create_directories(directory, made);
    if (made) throw std::runtime_error("cannot make the directory " + directory + ": " + made.message());
    const std::pair<KeyPtr, X509Ptr> pair = MakeSelfSigned(hosts);
    EVP_PKEY* new_key = pair.first.get();
    X509* new_certificate = pair.second.get();
    WritePem(key, true, [new_key](std::FILE* file) {
      return PEM_write_PrivateKey(file, new_key, nullptr, nullptr, 0, nullptr, nullptr);
    });
    WritePem(certificate, false, [new_certificate](std::FILE* file) { return PEM_write_X509(file, new_certificate); });
  }
  TlsSetup setup = LoadTls(certificate, key);
  setup.self_signed = true;
  return setup;
}

}  // namespace flagsim::gateway
