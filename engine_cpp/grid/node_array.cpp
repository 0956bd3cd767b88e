#include "grid/node_array.hpp"

#include <sys/mman.h>

#include <mutex>
#include <unordered_map>
#include <utility>
#include <vector>

namespace xroute {

namespace {

constexpr size_t kPage = 4096;
// Bytes of freed blocks kept for reuse at most; beyond it the oldest go back to the kernel.
constexpr size_t kMaxKeptBytes = size_t(128) << 20;

size_t pageRound(size_t bytes) { return (bytes + kPage - 1) & ~(kPage - 1); }

// The blocks freed inside a BlockReuse scope, kept for the next request of about their size.
struct Kept {
  std::mutex mutex;
  int scopes = 0;
  std::vector<std::pair<void*, size_t>> free;  // address, mapped bytes; oldest first
  size_t freeBytes = 0;
  std::unordered_map<void*, size_t> mapped;    // blocks handed out from `free`: their mapped bytes
};

Kept& kept() {
  static Kept k;
  return k;
}

void unmapAll(Kept& k) noexcept {
  for (const auto& [p, bytes] : k.free) munmap(p, bytes);
  k.free.clear();
  k.freeBytes = 0;
}

}  // namespace

void* mapBlock(size_t bytes) {
  const size_t want = pageRound(bytes);
  Kept& k = kept();
  {
    std::lock_guard<std::mutex> lock(k.mutex);
    // The smallest kept block that holds the request, its pages past the request given back to the
    // kernel (they stay mapped and cost nothing until touched); else the largest, grown to the
    // request (its pages kept, the new ones faulted in when first touched).
    size_t best = k.free.size(), largest = k.free.size();
    for (size_t i = 0; i < k.free.size(); ++i) {
      const size_t have = k.free[i].second;
      if (have >= want && (best == k.free.size() || have < k.free[best].second)) best = i;
      if (largest == k.free.size() || have > k.free[largest].second) largest = i;
    }
    const size_t pick = best < k.free.size() ? best : largest;
    if (pick < k.free.size()) {
      auto [p, have] = k.free[pick];
      k.free.erase(k.free.begin() + static_cast<std::ptrdiff_t>(pick));
      k.freeBytes -= have;
      if (have < want) {
        void* q = mremap(p, have, want, MREMAP_MAYMOVE);
        if (q == MAP_FAILED) {
          munmap(p, have);
          p = nullptr;
        } else {
          p = q;
          have = want;
        }
      } else if (have > want) {
        madvise(static_cast<char*>(p) + want, have - want, MADV_DONTNEED);
      }
      if (p) {
        k.mapped.emplace(p, have);
        return p;
      }
    }
  }
  void* p = mmap(nullptr, want, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) throw std::bad_alloc();
  return p;
}

void unmapBlock(void* p, size_t bytes) noexcept {
  size_t have = pageRound(bytes);
  Kept& k = kept();
  std::lock_guard<std::mutex> lock(k.mutex);
  const auto it = k.mapped.find(p);
  if (it != k.mapped.end()) {
    have = it->second;
    k.mapped.erase(it);
  }
  if (k.scopes == 0) {
    munmap(p, have);
    return;
  }
  try {
    k.free.emplace_back(p, have);
  } catch (...) {
    munmap(p, have);
    return;
  }
  k.freeBytes += have;
  while (k.freeBytes > kMaxKeptBytes && !k.free.empty()) {
    munmap(k.free.front().first, k.free.front().second);
    k.freeBytes -= k.free.front().second;
    k.free.erase(k.free.begin());
  }
}

BlockReuse::BlockReuse() {
  std::lock_guard<std::mutex> lock(kept().mutex);
  ++kept().scopes;
}

BlockReuse::~BlockReuse() {
  Kept& k = kept();
  std::lock_guard<std::mutex> lock(k.mutex);
  if (--k.scopes == 0) unmapAll(k);
}

}  // namespace xroute
