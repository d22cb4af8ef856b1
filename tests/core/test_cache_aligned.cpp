// CacheAlignedVector: storage starts on a 64-byte boundary for any element type and size,
// including after growth (kernels carve their arrays from it at cache-line offsets).
#include <catch2/catch.hpp>

#include <cstdint>

#include "harness/core/cache_aligned.hpp"

namespace DABENCH_TEST_FILE {

using dabench::CacheAlignedVector;

TEST_CASE("cache_aligned: storage starts on a cache line before and after growth", "[harness]") {
  for (std::size_t size : {1u, 3u, 8u, 100u, 4097u}) {
    CacheAlignedVector<double> doubles(size, 1.0);
    CacheAlignedVector<char> chars(size, 'x');
    CHECK(reinterpret_cast<std::uintptr_t>(doubles.data()) % 64 == 0);
    CHECK(reinterpret_cast<std::uintptr_t>(chars.data()) % 64 == 0);
    doubles.resize(3 * size + 5, 2.0);
    CHECK(reinterpret_cast<std::uintptr_t>(doubles.data()) % 64 == 0);
    CHECK(doubles.front() == 1.0);
    CHECK(doubles.back() == 2.0);
  }
}

}  // namespace DABENCH_TEST_FILE
