#pragma once
// Shared by the fuzz harnesses (docs/stability.md, "Fuzzing"): a byte reader that turns a fuzz
// input into parameters with the extremes frequent, the violation type, and the entry-point macro.
//
// Encoding (tests/fuzz/make_corpus.py writes the same):
//   real():    one tag byte t; t < 32: kExtremeReals[t]; 32 <= t < 64: the next 8 bytes as an
//              IEEE double (little endian); t >= 64: lo + (hi - lo) * u / 65535 with u the next
//              two bytes (little endian), the harness's typical range.
//   integer(): one tag byte t; t < 16: kExtremeIntegers[t]; 16 <= t < 32: the next 8 bytes as a
//              two's-complement int64 (little endian); t >= 32: lo + u % (hi - lo + 1) with u the
//              next two bytes.
//   choice(n): one byte modulo n.
// An exhausted input reads as zero bytes (real() = 0, integer() = 0, choice() = 0).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>

namespace stickslip_fuzz {

/// A broken rule of the issue: Success with non-finite or wrong results, a hang caught by an
/// invariant (time not advancing), or an exception of the wrong type. Deliberately not derived
/// from std::invalid_argument or std::domain_error.
struct Violation : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline constexpr double kExtremeReals[32] = {
    0.0,      -0.0,     1.0,     -1.0,     0.5,      2.0,      1e-300,  -1e-300,
    1e300,    -1e300,   std::numeric_limits<double>::max(),     -std::numeric_limits<double>::max(),
    std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::denorm_min(),
    -std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::min(),
    1e-15,    1e15,     1e-9,    1e9,      1e-6,     1e6,      1e308,   1e-160,
    1e-310,   1e17,     4.611686018427387904e18 /* 2^62 */,      std::numeric_limits<double>::epsilon(),
    10.0,     100.0};

inline constexpr long long kExtremeIntegers[16] = {
    0, 1, -1, 2, std::numeric_limits<long long>::max(), std::numeric_limits<long long>::min(),
    4611686018427387904LL /* 2^62 */, 1000000000LL, 2147483648LL, -2147483648LL,
    1099511627776LL /* 2^40 */, 3, 64, 65, 1000, 1000000};

/// Reads parameters from a fuzz input (encoding in the file comment).
class Input {
 public:
  Input(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : std::uint8_t{0}; }
  bool empty() const { return pos_ >= size_; }

  /// One of n alternatives (n >= 1).
  unsigned choice(unsigned n) { return static_cast<unsigned>(byte()) % n; }
  bool flag() { return choice(2) == 1; }

  double real(double lo, double hi) {
    const std::uint8_t tag = byte();
    if (tag < 32) return kExtremeReals[tag];
    if (tag < 64) {
      double v;
      const std::uint64_t bits = raw64();
      std::memcpy(&v, &bits, sizeof v);
      return v;
    }
    return lo + (hi - lo) * static_cast<double>(raw16()) / 65535.0;
  }

  long long integer(long long lo, long long hi) {
    const std::uint8_t tag = byte();
    if (tag < 16) return kExtremeIntegers[tag];
    if (tag < 32) {
      long long v;
      const std::uint64_t bits = raw64();
      std::memcpy(&v, &bits, sizeof v);
      return v;
    }
    const auto span = static_cast<unsigned long long>(hi - lo) + 1ULL;
    return lo + static_cast<long long>(raw16() % span);
  }

 private:
  std::uint64_t raw64() {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(byte()) << (8 * i);
    return v;
  }
  unsigned raw16() {
    const unsigned a = byte();
    return a | (static_cast<unsigned>(byte()) << 8);
  }

  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

/// Throws Violation with `what` when `ok` is false.
inline void require(bool ok, const std::string& what) {
  if (!ok) throw Violation(what);
}

/// `v` formatted with all digits.
inline std::string str(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

/// Runs one harness on one input under the rule of the issue: std::invalid_argument and
/// std::domain_error (a named cause) are fine; a Violation or any other exception aborts, which
/// libFuzzer and the replay test both report as a failure.
template <class Harness>
int drive(const std::uint8_t* data, std::size_t size, Harness harness, const char* name) {
  try {
    Input in(data, size);
    harness(in);
  } catch (const std::invalid_argument&) {
  } catch (const std::domain_error&) {
  } catch (const Violation& v) {
    std::fprintf(stderr, "stickslip fuzz %s: VIOLATION: %s\n", name, v.what());
    std::abort();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stickslip fuzz %s: exception not derived from invalid_argument or "
                 "domain_error: %s\n", name, e.what());
    std::abort();
  }
  return 0;
}

}  // namespace stickslip_fuzz

// The entry point of a harness: LLVMFuzzerTestOneInput in a libFuzzer build (one binary per
// harness), stickslip_fuzz_<name> in the replay executable (all harnesses in one binary).
#ifdef STICKSLIP_LIBFUZZER
#define STICKSLIP_FUZZ_ENTRY(name, harness)                                              \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {   \
    return ::stickslip_fuzz::drive(data, size, harness, #name);                          \
  }
#else
#define STICKSLIP_FUZZ_ENTRY(name, harness)                                              \
  int stickslip_fuzz_##name(const std::uint8_t* data, std::size_t size) {               \
    return ::stickslip_fuzz::drive(data, size, harness, #name);                          \
  }
#endif
