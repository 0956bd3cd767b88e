// int32 numpy arrays for the bindings: read-only views into C++ data, and new
// arrays that own a moved-in std::vector through a capsule.
#pragma once

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

#include <cstdint>
#include <vector>

namespace xroute {

using IntView = nanobind::ndarray<nanobind::numpy, const int32_t>;
using IntArray = nanobind::ndarray<nanobind::numpy, int32_t>;

// A read-only view of `count` rows of `cols` int32 each (1-D when cols == 1),
// starting at `data`. The caller binds it with rv_policy::reference_internal,
// so the view keeps its owner alive.
inline IntView int32View(const void* data, size_t count, size_t cols) {
  static const int32_t kEmpty[1] = {0};
  const int32_t* p = count ? static_cast<const int32_t*>(data) : kEmpty;
  if (cols == 1) {
    const size_t shape[1] = {count};
    return IntView(p, 1, shape, nanobind::handle());
  }
  const size_t shape[2] = {count, cols};
  return IntView(p, 2, shape, nanobind::handle());
}

// A new array owning `values`: rows x cols, or 1-D when cols == 1.
inline IntArray ownedInt32(std::vector<int32_t>&& values, size_t cols) {
  auto* heap = new std::vector<int32_t>(std::move(values));
  nanobind::capsule owner(heap, [](void* p) noexcept { delete static_cast<std::vector<int32_t>*>(p); });
  const size_t rows = cols ? heap->size() / cols : 0;
  if (heap->capacity() == 0) heap->reserve(1);  // a real (owned, unshared) address even when empty
  int32_t* data = heap->data();
  if (cols == 1) {
    const size_t shape[1] = {rows};
    return IntArray(data, 1, shape, owner);
  }
  const size_t shape[2] = {rows, cols};
  return IntArray(data, 2, shape, owner);
}

}  // namespace xroute
