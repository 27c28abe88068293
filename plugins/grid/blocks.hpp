#pragma once
// Memory for the grid's arrays: zeroed by the kernel (a fresh anonymous mapping), 64-byte aligned,
// huge pages where the kernel's transparent-huge-page setting allows them (madvise).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace bhnsid::grid {

/// Returns a block to where it came from: a block of its own is unmapped, a block carved from a
/// BlockArena is left to the arena.
void release_block(void* p);
struct FreeDeleter {
  void operator()(void* p) const { release_block(p); }
};
using DoubleArray = std::unique_ptr<double[], FreeDeleter>;
using ByteArray = std::unique_ptr<std::uint8_t[], FreeDeleter>;

/// A zeroed block of `bytes` bytes (never null) in a mapping of its own, 2 MiB aligned from 2 MiB up.
void* allocate_zeroed(std::size_t bytes);

/// Blocks of 2 MiB and more get mappings of their own (allocate_zeroed); smaller ones (the coarse
/// levels' arrays, the masks) are carved one after the other from 32 MiB slabs of huge pages, which
/// live as long as the arena. Each page is zeroed by the kernel at its first touch, which falls in
/// the solver's parallel loops: a serial memset of every coarse array (40 MiB at n = 128) had been
/// a third of the multigrid's set-up, and 4 KiB pages a fault per page.
class BlockArena {
 public:
  BlockArena() = default;
  ~BlockArena();
  BlockArena(const BlockArena&) = delete;
  BlockArena& operator=(const BlockArena&) = delete;

  void* allocate(std::size_t bytes);

 private:
  std::vector<std::pair<void*, std::size_t>> slabs_;  // mapping, length
  char* next_ = nullptr;                              // the current slab's first free byte
  std::size_t left_ = 0;                              // bytes free in the current slab
};

}  // namespace bhnsid::grid
