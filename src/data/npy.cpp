#include "data/npy.h"

#include <cstring>
#include <limits>

#include "data/demos.h"

namespace vaegail {

namespace {

// The value of 'key' in numpy's header dict, e.g. "'<f4'", "False" or "(3, 4)".
std::string header_value(const std::string& header, const std::string& key, const std::string& where) {
  const size_t k = header.find("'" + key + "'");
  if (k == std::string::npos) throw DataError(where + ": .npy header has no '" + key + "'");
  size_t begin = header.find(':', k);
  if (begin == std::string::npos) throw DataError(where + ": malformed .npy header");
  begin = header.find_first_not_of(' ', begin + 1);
  const bool tuple = begin != std::string::npos && header[begin] == '(';
  const size_t end = tuple ? header.find(')', begin) + 1 : header.find_first_of(",}", begin);
  if (begin == std::string::npos || end == std::string::npos || end == 0)
    throw DataError(where + ": malformed .npy header");
  return header.substr(begin, end - begin);
}

std::vector<std::uint64_t> parse_shape(const std::string& text, const std::string& where) {
  std::vector<std::uint64_t> shape;
  for (size_t i = 1; i + 1 < text.size();) {
    const size_t next = text.find_first_of(",)", i);
    const std::string field = text.substr(i, next - i);
    if (field.find_first_not_of(' ') != std::string::npos) {
      try {
        shape.push_back(std::stoull(field));
      } catch (const std::exception&) {
        throw DataError(where + ": .npy shape " + text + " is not a tuple of sizes");
      }
    }
    i = next + 1;
  }
  return shape;
}

template <typename T>
void convert(const char* data, std::uint64_t n, std::vector<double>& out) {
  out.resize(n);
  for (std::uint64_t i = 0; i < n; ++i) {
    T v;
    std::memcpy(&v, data + i * sizeof(T), sizeof(T));
    out[i] = static_cast<double>(v);
  }
}

// Converts n little-endian elements of `kind`+`size` ("f4", "i8", "b1"...); false when unknown.
bool convert_any(char kind, int size, const char* data, std::uint64_t n, std::vector<double>& out) {
  if (kind == 'f' && size == 4) return convert<float>(data, n, out), true;
  if (kind == 'f' && size == 8) return convert<double>(data, n, out), true;
  if ((kind == 'b' || kind == 'u') && size == 1) return convert<std::uint8_t>(data, n, out), true;
  if (kind == 'u' && size == 2) return convert<std::uint16_t>(data, n, out), true;
  if (kind == 'u' && size == 4) return convert<std::uint32_t>(data, n, out), true;
  if (kind == 'u' && size == 8) return convert<std::uint64_t>(data, n, out), true;
  if (kind == 'i' && size == 1) return convert<std::int8_t>(data, n, out), true;
  if (kind == 'i' && size == 2) return convert<std::int16_t>(data, n, out), true;
  if (kind == 'i' && size == 4) return convert<std::int32_t>(data, n, out), true;
  if (kind == 'i' && size == 8) return convert<std::int64_t>(data, n, out), true;
  return false;
}

}  // namespace

std::uint64_t NpyArray::row_width() const {
  std::uint64_t w = 1;
  for (size_t i = 1; i < shape.size(); ++i) w *= shape[i];
  return w;
}

NpyArray parse_npy(const std::string& bytes, const std::string& where) {
  if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0) throw DataError(where + ": not a .npy array");
  const int major = static_cast<unsigned char>(bytes[6]);
  const auto byte = [&](size_t i) { return static_cast<std::uint64_t>(static_cast<unsigned char>(bytes[i])); };
  const bool wide = major >= 2;  // versions 2 and 3 have a 4-byte header length
  if (wide && bytes.size() < 12) throw DataError(where + ": truncated .npy header");
  const std::uint64_t header_length = wide ? byte(8) | byte(9) << 8 | byte(10) << 16 | byte(11) << 24 : byte(8) | byte(9) << 8;
  const std::uint64_t data_start = (wide ? 12 : 10) + header_length;
  if (data_start > bytes.size()) throw DataError(where + ": truncated .npy header");
  const std::string header = bytes.substr(wide ? 12 : 10, header_length);
  NpyArray a;
  const std::string descr = header_value(header, "descr", where);
  if (descr.size() < 4 || (descr.front() != '\'' && descr.front() != '"'))
    throw DataError(where + ": .npy dtype " + descr + " is a structured dtype: not read");
  a.dtype = descr.substr(1, descr.size() - 2);
  if (header_value(header, "fortran_order", where) != "False")
    throw DataError(where + ": Fortran-ordered .npy array: not read (save it in C order)");
  a.shape = parse_shape(header_value(header, "shape", where), where);
  std::uint64_t n = 1;
  for (std::uint64_t d : a.shape) {
    if (d != 0 && n > std::numeric_limits<std::uint64_t>::max() / d) throw DataError(where + ": .npy shape overflows");
    n *= d;
  }
  const char order = a.dtype[0], kind = a.dtype[1];
  int size = 0;
  try {
    size = std::stoi(a.dtype.substr(2));
  } catch (const std::exception&) {
  }
  if (kind == 'O') throw DataError(where + ": an object array (pickled Python objects): not read");
  if (order == '>' && size > 1) throw DataError(where + ": big-endian dtype " + a.dtype + ": not read");
  if (size <= 0 || n > (bytes.size() - data_start) / size || n * size != bytes.size() - data_start)
    throw DataError(where + ": " + std::to_string(bytes.size() - data_start) + " bytes of data for shape " +
                    header_value(header, "shape", where) + " of " + a.dtype);
  if (!convert_any(kind, size, bytes.data() + data_start, n, a.values))
    throw DataError(where + ": dtype " + a.dtype + ": not read (numbers and booleans only)");
  return a;
}

}  // namespace vaegail
