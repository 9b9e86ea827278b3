// What the fuzz targets share: reading bounded values out of the fuzzer's bytes, and failing
// loudly. Plain C++ (no libFuzzer header), so the same targets build with g++ for the replay
// ctests and with clang -fsanitize=fuzzer for `make fuzz`.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

namespace virtual_origami::fuzz
{
/// Consumes the input front to back; past its end every read gives zero, so any byte string
/// decodes to some sequence (libFuzzer's mutations then stay meaningful).
class ByteReader
{
public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  bool empty() const { return pos_ >= size_; }
  size_t remaining() const { return pos_ < size_ ? size_ - pos_ : 0; }

  uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  uint16_t u16() { return static_cast<uint16_t>(byte() | (byte() << 8)); }
  bool flag() { return byte() & 1; }
  /// In [0, 1].
  double unit() { return u16() / 65535.0; }
  double range(double lo, double hi) { return lo + (hi - lo) * unit(); }
  /// An index in [0, n) (0 when n is 0).
  int index(int n) { return n > 0 ? static_cast<int>(u16() % static_cast<unsigned>(n)) : 0; }
  /// Eight raw bytes as a double: every bit pattern, NaNs and denormals included.
  double rawDouble()
  {
    uint64_t bits = 0;
    for (int i = 0; i < 8; ++i)
      bits |= static_cast<uint64_t>(byte()) << (8 * i);
    double d;
    std::memcpy(&d, &bits, sizeof d);
    return d;
  }

  /// The values user input breaks code with: non-finite, huge, tiny, signed zero.
  double special()
  {
    switch (byte() % 10)
    {
      case 0:
        return std::numeric_limits<double>::quiet_NaN();
      case 1:
        return std::numeric_limits<double>::infinity();
      case 2:
        return -std::numeric_limits<double>::infinity();
      case 3:
        return 1e300;
      case 4:
        return -1e300;
      case 5:
        return 1e-300;
      case 6:
        return -0.0;
      case 7:
        return std::numeric_limits<double>::denorm_min();
      case 8:
        return std::numeric_limits<double>::max();
      default:
        return rawDouble();
    }
  }

private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

/// Reports an invariant violation the way a crash is reported (libFuzzer saves the input),
/// with what was checked and the steps that led there.
[[noreturn]] inline void fail(const std::string& what, const std::string& trace)
{
  std::fprintf(stderr, "\n==== fuzz invariant violated: %s\n---- steps:\n%s\n", what.c_str(), trace.c_str());
  std::fflush(stderr);
  std::abort();
}

}  // namespace virtual_origami::fuzz
