#pragma once
// Memory for the grid's arrays: zeroed by the kernel (a fresh anonymous mapping), 64-byte aligned,
// huge pages where the kernel's transparent-huge-page setting allows them (madvise).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace bhnsid::grid {

/// Unmaps a block from allocate_zeroed.
void release_block(void* p);
/// Releases a block from allocate_zeroed; leaves one that a BlockArena owns (owned = false) to it.
struct FreeDeleter {
  bool owned = true;
  void operator()(void* p) const {
    if (owned) release_block(p);
  }
};
using DoubleArray = std::unique_ptr<double[], FreeDeleter>;
using ByteArray = std::unique_ptr<std::uint8_t[], FreeDeleter>;

/// A zeroed block of `bytes` bytes (never null) in a mapping of its own, 2 MiB aligned: for blocks of
/// 2 MiB and more (BlockArena::allocate carves the smaller ones from shared slabs).
void* allocate_zeroed(std::size_t bytes);

/// Blocks of 2 MiB and more get mappings of their own (allocate_zeroed); smaller ones (the coarse
/// levels' arrays, the masks) are carved one after the other from 32 MiB slabs of huge pages, which
/// live as long as the arena. The arena writes nothing into a slab (no header: the deleter says
/// who owns a block), so each page is zeroed by the kernel at its first touch, which falls in the
/// solver's parallel loops: a serial memset of every coarse array (40 MiB at n = 128) had been a
/// third of the multigrid's set-up, and 4 KiB pages a fault per page.
class BlockArena {
 public:
  BlockArena() = default;
  ~BlockArena();
  BlockArena(const BlockArena&) = delete;
  BlockArena& operator=(const BlockArena&) = delete;

  /// A zeroed, 64-byte aligned block, with the deleter that releases it (nothing for a slab's).
  template <class T>
  std::unique_ptr<T[], FreeDeleter> allocate(std::size_t count) {
    bool owned = false;
    void* p = allocate_bytes(count * sizeof(T), owned);
    return std::unique_ptr<T[], FreeDeleter>(static_cast<T*>(p), FreeDeleter{owned});
  }

 private:
  void* allocate_bytes(std::size_t bytes, bool& owned);

  std::vector<std::pair<void*, std::size_t>> slabs_;  // mapping, length
  char* next_ = nullptr;                              // the current slab's first free byte
  std::size_t left_ = 0;                              // bytes free in the current slab
};

}  // namespace bhnsid::grid
