// Per-node arrays of a region grid and of the maze's search (NodeArray<T>):
// std::vector with an allocator that maps a block of 1 MiB or more straight
// from the kernel and gives it back when freed (inside a BlockReuse scope:
// when the scope ends).
//
// Why: a region's arrays are tens of MB and live for one region. Through
// malloc, glibc raises its mmap threshold after the first such block is
// freed, so later ones come from the per-thread arenas and stay in the
// process after the region. ispd19_test3's iteration 0, 2 threads, measured
// 2026-11-27: peak RSS 383 MB through malloc, 300 MB with glibc's threshold
// held at 1 MiB (MALLOC_MMAP_THRESHOLD_), 249 MB with these arrays and the
// smaller nodes of region_grid.hpp and route/maze.hpp.
#pragma once

#include <cstddef>
#include <new>
#include <vector>

namespace xroute {

inline constexpr size_t kMappedBlockBytes = size_t(1) << 20;  // bytes: a block this big or bigger is mapped

void* mapBlock(size_t bytes);              // throws std::bad_alloc when the kernel refuses
void unmapBlock(void* p, size_t bytes) noexcept;

// While one of these lives, a freed block is kept (128 MiB of them at most) and handed to the next
// request, cut or grown to its size, instead of going back to the kernel: the regions of a batch
// reuse each other's pages instead of faulting fresh ones in and having the kernel clear them. The
// last one to go gives every kept block back.
class BlockReuse {
 public:
  BlockReuse();
  ~BlockReuse();
  BlockReuse(const BlockReuse&) = delete;
  BlockReuse& operator=(const BlockReuse&) = delete;
};

template <class T>
struct NodeAllocator {
  using value_type = T;
  NodeAllocator() noexcept = default;
  template <class U>
  NodeAllocator(const NodeAllocator<U>&) noexcept {}

  T* allocate(size_t n) {
    const size_t bytes = n * sizeof(T);
    if (bytes >= kMappedBlockBytes) return static_cast<T*>(mapBlock(bytes));
    return static_cast<T*>(::operator new(bytes));
  }
  void deallocate(T* p, size_t n) noexcept {
    const size_t bytes = n * sizeof(T);
    if (bytes >= kMappedBlockBytes) unmapBlock(p, bytes);
    else ::operator delete(p);
  }
  template <class U>
  bool operator==(const NodeAllocator<U>&) const noexcept { return true; }
};

template <class T>
using NodeArray = std::vector<T, NodeAllocator<T>>;

// Bytes a node takes in the given per-node arrays (for the static_asserts that hold a struct's
// per-node size).
template <class... Arrays>
constexpr size_t bytesPerNode() {
  return (sizeof(typename Arrays::value_type) + ...);
}

}  // namespace xroute
