// A least-recently-used cache of elevation blocks: 129 x 129 node heights (128 x 128 cells,
// so every cell lies in one block), with the highest height of each 16 x 16-cell sub-block
// for skipping rays over them. Bounded by a byte budget; fetches through a callback, which
// may have no block to give yet (read elsewhere, gimbald's loader thread): nothing is kept
// then and the next get() asks again. Not thread-safe (gimbald's io thread is its only user).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <list>
#include <unordered_map>
#include <vector>

namespace gimbal::terrain {

struct BlockKey {
    std::uint32_t lattice = 0;
    std::int64_t row = 0;  // block row and column in the lattice (128 nodes each)
    std::int64_t col = 0;
    bool operator==(const BlockKey&) const = default;
};

struct Block {
    static constexpr int cells = 128;
    static constexpr int nodes = cells + 1;
    static constexpr int sub = 16;  // cells per sub-block side
    static constexpr int subs = cells / sub;
    std::vector<float> height;  // nodes x nodes, row-major; NaN where unknown
    float max = 0;              // over the whole block
    bool all_known = false;
    float sub_max[subs][subs]{};
    bool sub_known[subs][subs]{};

    float at(int r, int c) const { return height[static_cast<std::size_t>(r * nodes + c)]; }
    // Fills max, all_known and the sub-block tables from `height`.
    void summarise();
    static constexpr std::size_t bytes() { return sizeof(float) * nodes * nodes + sizeof(Block); }
};

struct CacheStats {
    std::uint64_t loads = 0;      // blocks read from files (or taken from the loader)
    std::uint64_t misses = 0;     // lookups of a block the loader could not give yet
    std::uint64_t evictions = 0;  // blocks dropped to stay within the budget
    std::size_t resident = 0;     // blocks held now
    std::size_t capacity = 0;     // blocks the budget allows
};

class BlockCache {
  public:
    // Fills a complete block (heights and summary); false when it cannot now.
    using Loader = std::function<bool(const BlockKey&, Block&)>;
    // At least 4 blocks whatever the budget.
    BlockCache(std::size_t budget_bytes, Loader loader);
    // The block, fetched when absent; nullptr when the loader has none yet. The pointer stays
    // valid until the next get().
    const Block* get(const BlockKey& key);
    CacheStats stats() const;
    // Changes whenever a block is loaded (and so possibly another evicted): a caller holding
    // a Block pointer may keep it while this stays the same.
    std::uint64_t generation() const { return loads_; }

  private:
    struct KeyHash {
        std::size_t operator()(const BlockKey& k) const;
    };
    struct Entry {
        BlockKey key;
        Block block;
    };
    std::size_t capacity_;
    Loader loader_;
    std::list<Entry> lru_;  // front: most recently used
    std::unordered_map<BlockKey, std::list<Entry>::iterator, KeyHash> index_;
    std::uint64_t loads_ = 0, evictions_ = 0, misses_ = 0;
};

}  // namespace gimbal::terrain
