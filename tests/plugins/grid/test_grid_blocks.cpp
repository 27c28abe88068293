// The grid's memory blocks: every block zeroed, 64-byte aligned and disjoint from every other, the
// small ones carved from the arena's slabs across slab boundaries, the large ones with mappings of
// their own that their deleters unmap.
#include <catch2/catch.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "blocks.hpp"

using bhnsid::grid::BlockArena;

TEST_CASE("plugins.grid.arena_blocks_are_zeroed_aligned_and_disjoint", "[plugins][grid]") {
  // Sizes from a byte to 1 MiB, and every sixth just over 2 MiB (a mapping of its own): the small
  // ones, 64 MiB in all, fill the arena's 32 MiB slabs and open new ones; a block that ran past the
  // end of its slab would fault or overlap another.
  std::vector<std::size_t> sizes;
  for (int b = 0; b < 120; ++b) sizes.push_back(b % 6 == 5 ? (std::size_t{2} << 20) + 8 * b : 1 + 9'000 * b);
  BlockArena arena;
  std::vector<bhnsid::grid::ByteArray> blocks;
  for (std::size_t s : sizes) {
    bhnsid::grid::ByteArray block = arena.allocate<std::uint8_t>(s);
    std::uint8_t* p = block.get();
    REQUIRE(p != nullptr);
    CHECK(block.get_deleter().owned == (s >= (std::size_t{2} << 20)));
    CHECK(reinterpret_cast<std::uintptr_t>(p) % 64 == 0);
    std::size_t nonzero = 0;
    for (std::size_t i = 0; i < s; ++i) nonzero += p[i] != 0;
    CHECK(nonzero == 0);
    std::memset(p, static_cast<int>(blocks.size() % 251) + 1, s);  // overlap would overwrite an earlier block
    blocks.push_back(std::move(block));
  }
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    INFO("block " << b << " of " << sizes[b] << " bytes");
    const std::uint8_t mark = static_cast<std::uint8_t>(b % 251 + 1);
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < sizes[b]; ++i) wrong += blocks[b][i] != mark;
    CHECK(wrong == 0);
  }
  // The large blocks are their own mappings, unmapped by their deleters; the small ones go with the
  // arena's slabs.
}
