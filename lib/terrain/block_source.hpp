// Where the elevation model gets a block it does not hold (elevation_model.hpp): read from the
// files right away (tools, tests, benchmarks), or - in gimbald - from a loader thread, which
// may not have it yet; the model then treats the block's cells as unknown for that lookup and
// asks again at the next (contract section 14 v4: a GDAL read never blocks the io thread).
#pragma once

#include "terrain/block_cache.hpp"

namespace gimbal::terrain {

class BlockSource {
  public:
    virtual ~BlockSource() = default;
    // Fills `out` completely (heights and summary) and returns true, or returns false when
    // the block is not available now.
    virtual bool fetch(const BlockKey& key, Block& out) = 0;
};

}  // namespace gimbal::terrain
