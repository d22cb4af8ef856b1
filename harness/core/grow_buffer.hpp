#pragma once
// Scratch buffers that only grow: a solver reused across trials resizes its working arrays to
// at least the current problem's size and never shrinks them, so once they have reached the
// largest size seen, a solve allocates nothing. Contents are unspecified after a call (callers
// overwrite what they use).
#include <cstddef>
#include <vector>

namespace dabench {

template <class T, class Allocator>
void grow_buffer(std::vector<T, Allocator>& buffer, std::size_t size) {
  if (buffer.size() < size) buffer.resize(size);
}

}  // namespace dabench
