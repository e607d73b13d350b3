// What a VRT file asks GDAL to do, read from its XML before GDAL opens it (dem_policy.hpp):
// the files it names and whether it uses anything terrain refuses. Element and attribute
// names are compared ignoring case, and every element of the document is looked at (GDAL
// finds sources in bands, mask bands and overviews), so nothing GDAL would follow is missed.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace gimbal::terrain {

struct VrtSource {
    std::string name;                 // the SourceFilename text, as written
    bool relative_to_vrt = false;     // its relativeToVRT attribute, read as GDAL reads it
    double scale_x = 1, scale_y = 1;  // source cells per VRT cell (SrcRect / DstRect sizes)
};

struct VrtContents {
    std::vector<VrtSource> sources;
    std::string refusal;  // what it uses that terrain refuses; empty when nothing
};

VrtContents read_vrt(std::string_view xml);

}  // namespace gimbal::terrain
