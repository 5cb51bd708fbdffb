// core/base/content_hash.h — a content hash for provenance: SHA-256 (FIPS 180-4) through OpenSSL's
// libcrypto, so that an output can name the exact bytes of an input file it read.
#pragma once

#include <string>

namespace sl {

// The SHA-256 of `bytes` as 64 lowercase hex digits.
std::string sha256Hex(const std::string& bytes);
// The SHA-256 of the file at `path`; InputError naming it when it cannot be read.
std::string sha256OfFile(const std::string& path);

}  // namespace sl
