// The gateway's TLS: a certificate and key given by the user (PEM files), or a self-signed pair
// made for the addresses it serves (OpenSSL), kept in a directory so that it, and its
// fingerprint, stay the same from one start to the next. People check the printed SHA-256
// fingerprint against what their browser shows before they trust it.
#pragma once

#include <boost/asio/ssl/context.hpp>
#include <memory>
#include <string>
#include <vector>

namespace flagsim::gateway {

struct TlsSetup {
  std::shared_ptr<boost::asio::ssl::context> context;  ///< a TLS 1.2+ server context holding the pair
  std::string certificate_path;
  std::string fingerprint;  ///< SHA-256 of the certificate, "AB:CD:..."
  bool self_signed = false;
};

/// Loads `certificate` (PEM, with its chain) and `key` (PEM). Throws std::runtime_error naming the
/// file and what is wrong: unreadable, not PEM, or a key that does not match the certificate.
TlsSetup LoadTls(const std::string& certificate, const std::string& key);

/// The self-signed pair in `directory` (gateway.crt, gateway.key: the key readable by its owner
/// only), made first if absent or not naming every one of `hosts` (IP addresses, or names).
/// Throws std::runtime_error naming what could not be made or written.
TlsSetup SelfSignedTls(const std::string& directory, const std::vector<std::string>& hosts);

}  // namespace flagsim::gateway
