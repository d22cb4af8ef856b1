// Tests of grow_buffer (harness/core/grow_buffer.hpp): it grows to the requested size, never
// shrinks, and keeps the storage (and its contents) when the request fits.
#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include "harness/core/cache_aligned.hpp"
#include "harness/core/grow_buffer.hpp"

namespace DABENCH_TEST_FILE {

TEST_CASE("grow_buffer: grows to the request, never shrinks, keeps storage that fits", "[grow_buffer]") {
  std::vector<int> buffer;
  dabench::grow_buffer(buffer, 5);
  CHECK(buffer.size() == 5);
  buffer[4] = 7;
  const int* storage = buffer.data();
  dabench::grow_buffer(buffer, 3);
  CHECK(buffer.size() == 5);
  CHECK(buffer.data() == storage);
  CHECK(buffer[4] == 7);
  dabench::grow_buffer(buffer, 5);
  CHECK(buffer.data() == storage);
  dabench::grow_buffer(buffer, 12);
  CHECK(buffer.size() == 12);
  CHECK(buffer[4] == 7);  // resize keeps the prefix
}

TEST_CASE("grow_buffer: cache-aligned vectors stay aligned as they grow", "[grow_buffer]") {
  dabench::CacheAlignedVector<double> buffer;
  for (std::size_t size : {1, 9, 100, 3}) {
    dabench::grow_buffer(buffer, size);
    CHECK(buffer.size() >= size);
    CHECK(reinterpret_cast<std::uintptr_t>(buffer.data()) % 64 == 0);
  }
  CHECK(buffer.size() == 100);
}

}  // namespace DABENCH_TEST_FILE
