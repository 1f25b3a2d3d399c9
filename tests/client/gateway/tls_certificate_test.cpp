// The gateway's TLS pair: a self-signed certificate made once for the addresses served and kept
// (the same fingerprint at the next start), made again when an address is new; a key readable by
// its owner only; a key that does not match its certificate named as such.
#include "client/gateway/tls_certificate.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <regex>
#include <stdexcept>

namespace flagsim::gateway {
namespace {

namespace fs = std::filesystem;

fs::path Scratch(const std::string& name) {
  const fs::path path = fs::path(::testing::TempDir()) / (name + "_" + std::to_string(getpid()));
  fs::remove_all(path);
  return path;
}

TEST(TlsCertificate, ASelfSignedPairIsMadeOnceForItsAddresses) {
  const fs::path directory = Scratch("tls");
  const TlsSetup first = SelfSignedTls(directory.string(), {"127.0.0.1", "10.1.2.3"});
  EXPECT_TRUE(first.self_signed);
  EXPECT_TRUE(std::regex_match(first.fingerprint, std::regex("([0-9A-F]{2}:){31}[0-9A-F]{2}")))
      << first.fingerprint;
  struct stat info {};
  ASSERT_EQ(::stat((directory / "gateway.key").c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0600u) << "the key is its owner's alone";
  EXPECT_EQ(SelfSignedTls(directory.string(), {"10.1.2.3"}).fingerprint, first.fingerprint) << "kept";
  EXPECT_NE(SelfSignedTls(directory.string(), {"10.9.9.9"}).fingerprint, first.fingerprint)
      << "a new address";
  fs::remove_all(directory);
}

TEST(TlsCertificate, WhatIsWrongWithAGivenPairIsNamed) {
  const fs::path one = Scratch("tls_one"), two = Scratch("tls_two");
  SelfSignedTls(one.string(), {"127.0.0.1"});
  SelfSignedTls(two.string(), {"127.0.0.1"});
  const std::string cert = (one / "gateway.crt").string(), key = (one / "gateway.key").string();
  EXPECT_FALSE(LoadTls(cert, key).fingerprint.empty());
  const auto refusal = [](const std::string& certificate, const std::string& private_key) {
    try {
      LoadTls(certificate, private_key);
    } catch (const std::runtime_error& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refusal(cert, (two / "gateway.key").string()),
            "--tls-key " + (two / "gateway.key").string() + " does not match the certificate in --tls-cert " +
                cert);
  EXPECT_EQ(refusal(key, key), "--tls-cert " + key + ": not a PEM certificate that can be read");
  EXPECT_EQ(refusal(cert, cert), "--tls-key " + cert + ": not a PEM private key that can be read");
  fs::remove_all(one);
  fs::remove_all(two);
}

}  // namespace
}  // namespace flagsim::gateway
