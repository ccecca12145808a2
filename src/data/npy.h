// numpy's .npy arrays (format versions 1-3), as an .npz archive holds them: what the
// `imitation` library's trajectory files are made of. Numbers only; object arrays (pickled
// Python) are refused rather than unpickled.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace vaegail {

struct NpyArray {
  std::vector<std::uint64_t> shape;  // () for a scalar
  std::vector<double> values;        // row-major (C order), converted from the stored dtype
  std::string dtype;                 // numpy's descr, e.g. "<f4", "|b1"
  std::uint64_t rows() const { return shape.empty() ? 1 : shape[0]; }
  // Elements per row: the product of every dimension after the first.
  std::uint64_t row_width() const;
};

// Throws DataError "`where`: problem" on a malformed header, an unsupported dtype (object,
// big-endian, complex, strings), Fortran order, or a size that disagrees with the shape.
NpyArray parse_npy(const std::string& bytes, const std::string& where);

}  // namespace vaegail
