// SHA-256 (FIPS 180-4), the hash a demonstration file names its body by: the same digest
// `sha256sum my_body.xml` prints, so a user can check which MJCF file a recording came from.
#pragma once

#include <string>

namespace vaegail {

// 64 lowercase hex digits.
std::string sha256_hex(const std::string& bytes);

}  // namespace vaegail
