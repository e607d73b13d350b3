#include "terrain/block_cache.hpp"

#include <algorithm>
#include <cmath>

namespace gimbal::terrain {

void Block::summarise() {
    max = -INFINITY;
    all_known = true;
    for (int sr = 0; sr < subs; ++sr)
        for (int sc = 0; sc < subs; ++sc) {
            float m = -INFINITY;
            bool known = true;
            // A sub-block's cells reach the nodes on its far edges too.
            for (int r = sr * sub; r <= (sr + 1) * sub; ++r)
                for (int c = sc * sub; c <= (sc + 1) * sub; ++c) {
                    const float h = at(r, c);
                    if (std::isnan(h))
                        known = false;
                    else
                        m = std::max(m, h);
                }
            sub_max[sr][sc] = m;
            sub_known[sr][sc] = known;
            max = std::max(max, m);
            all_known = all_known && known;
        }
}

std::size_t BlockCache::KeyHash::operator()(const BlockKey& k) const {
    const auto r = static_cast<std::uint64_t>(k.row), c = static_cast<std::uint64_t>(k.col);
    return static_cast<std::size_t>((r * 0x9E3779B97F4A7C15ULL) ^ (c * 0xC2B2AE3D27D4EB4FULL) ^
                                    (std::uint64_t{k.lattice} << 48));
}

BlockCache::BlockCache(std::size_t budget_bytes, Loader loader)
    : capacity_(std::max<std::size_t>(4, budget_bytes / Block::bytes())),
      loader_(std::move(loader)) {}

const Block* BlockCache::get(const BlockKey& key) {
    if (const auto it = index_.find(key); it != index_.end()) {
        if (it->second != lru_.begin()) lru_.splice(lru_.begin(), lru_, it->second);
        return &it->second->block;
    }
    Block fetched;
    if (!loader_(key, fetched)) {
        ++misses_;
        return nullptr;
    }
    if (lru_.size() >= capacity_) {
        index_.erase(lru_.back().key);
        lru_.pop_back();
        ++evictions_;
    }
    lru_.push_front(Entry{key, std::move(fetched)});
    ++loads_;
    index_.emplace(key, lru_.begin());
    return &lru_.front().block;
}

CacheStats BlockCache::stats() const {
    return {loads_, misses_, evictions_, lru_.size(), capacity_};
}

}  // namespace gimbal::terrain
