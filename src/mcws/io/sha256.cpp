#include "mcws/io/sha256.h"

#include <openssl/evp.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <utility>
#include <vector>

#include "mcws/core/error.h"

namespace mcws::io {

Sha256::Sha256(std::string what)
    : what_(std::move(what)), context_(EVP_MD_CTX_new(), EVP_MD_CTX_free) {
  if (!context_ || EVP_DigestInit_ex(context_.get(), EVP_sha256(), nullptr) != 1) {
    throw Error(what_ + ": OpenSSL's SHA-256 failed to start");
  }
}

Sha256::~Sha256() = default;

void Sha256::add(const void* data, std::size_t size) {
  if (size > 0 && EVP_DigestUpdate(context_.get(), data, size) != 1) {
    throw Error(what_ + ": OpenSSL's SHA-256 failed");
  }
}

std::string Sha256::hex() {
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int length = 0;
  if (EVP_DigestFinal_ex(context_.get(), digest.data(), &length) != 1 || length != 32) {
    throw Error(what_ + ": OpenSSL's SHA-256 failed");
  }
  std::string text;
  for (unsigned int k = 0; k < length; ++k) {
    char byte[3];
    std::snprintf(byte, sizeof byte, "%02x", digest[k]);
    text += byte;
  }
  return text;
}

std::string sha256OfFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot read the file to hash it");
  Sha256 digest(path);
  std::vector<char> buffer(1u << 16);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    digest.add(buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw Error(path + ": cannot read the file to hash it");
  return digest.hex();
}

}  // namespace mcws::io
