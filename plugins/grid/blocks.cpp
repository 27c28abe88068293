#include "blocks.hpp"

#include <algorithm>
#include <new>

#include <sys/mman.h>

namespace bhnsid::grid {

namespace {

// A block of its own starts with a header one cache line before the pointer handed out, saying
// how to unmap it (outside the huge-page stretch: a 4 KiB page of the mapping's head).
struct BlockHeader {
  void* base;
  std::size_t length;
};
constexpr std::size_t header_space = 64;
constexpr std::size_t huge_page = std::size_t{2} << 20;
constexpr std::size_t slab_size = std::size_t{32} << 20;

/// A fresh anonymous mapping with a huge-page aligned stretch of `length` bytes that has at least
/// `prefix` mapped bytes before it. Returns the stretch and {base, mapped length} for munmap.
std::pair<char*, std::pair<void*, std::size_t>> map_huge(std::size_t length, std::size_t prefix) {
  const std::size_t mapped = (prefix + length + 2 * huge_page - 1) / huge_page * huge_page;
  void* base = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (base == MAP_FAILED) throw std::bad_alloc();
  const auto first = reinterpret_cast<std::uintptr_t>(base) + prefix;
  auto* aligned = reinterpret_cast<char*>((first + huge_page - 1) / huge_page * huge_page);
  // 2 MiB alignment plus MADV_HUGEPAGE gets huge pages under the usual defrag=madvise setting.
  madvise(aligned, length, MADV_HUGEPAGE);
  return {aligned, {base, mapped}};
}

}  // namespace

void* allocate_zeroed(std::size_t bytes) {
  // A fresh anonymous mapping is zero already, so no memset pass over hundreds of MiB: the kernel
  // zeroes each page at its first touch (4 KiB pages cost a fault per page: a sixth of an N = 255
  // Poisson run, and TLB misses in the sweeps).
  const auto [p, mapping] = map_huge(bytes, header_space);
  *reinterpret_cast<BlockHeader*>(p - header_space) = BlockHeader{mapping.first, mapping.second};
  return p;
}

void release_block(void* p) {
  if (!p) return;
  const BlockHeader header = *reinterpret_cast<const BlockHeader*>(static_cast<char*>(p) - header_space);
  munmap(header.base, header.length);
}

BlockArena::~BlockArena() {
  for (const auto& [base, length] : slabs_) munmap(base, length);
}

void* BlockArena::allocate_bytes(std::size_t bytes, bool& owned) {
  owned = bytes >= huge_page;
  if (owned) return allocate_zeroed(bytes);
  const std::size_t need = std::max<std::size_t>(64, (bytes + 63) / 64 * 64);
  if (need > left_) {
    const auto [start, mapping] = map_huge(slab_size, 0);
    slabs_.push_back(mapping);
    next_ = start;
    left_ = slab_size;
  }
  char* p = next_;
  next_ += need;
  left_ -= need;
  return p;
}

}  // namespace bhnsid::grid
