#pragma once
/// \file
/// \brief SHA-256 digests (OpenSSL's EVP interface): of bytes fed in pieces, and of a file.

#include <cstddef>
#include <memory>
#include <string>

struct evp_md_ctx_st;

namespace mcws::io {

/// \brief A SHA-256 digest of bytes fed in pieces.
class Sha256 {
 public:
  /// \param what names what is hashed in the messages ("map cache", a file name).
  /// \throws mcws::Error "WHAT: OpenSSL's SHA-256 failed to start".
  explicit Sha256(std::string what);
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;

  /// \brief Feeds `size` bytes. \throws mcws::Error "WHAT: OpenSSL's SHA-256 failed".
  void add(const void* data, std::size_t size);
  /// \brief The digest of the bytes fed, as 64 lowercase hex digits (the digest is then spent).
  /// \throws mcws::Error as add().
  std::string hex();

 private:
  std::string what_;
  std::unique_ptr<evp_md_ctx_st, void (*)(evp_md_ctx_st*)> context_;
};

/// \brief The SHA-256 of a file's bytes, as 64 lowercase hex digits.
/// \throws mcws::Error "PATH: cannot read the file to hash it" or as Sha256.
std::string sha256OfFile(const std::string& path);

}  // namespace mcws::io
