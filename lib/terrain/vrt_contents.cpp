#include "terrain/vrt_contents.hpp"

#include <cpl_minixml.h>
#include <strings.h>

#include <array>
#include <cstdlib>

#include "terrain/gdal_handle.hpp"

namespace gimbal::terrain {

namespace {

bool same(const char* a, std::string_view b) {
    return a && std::string_view(a).size() == b.size() && strncasecmp(a, b.data(), b.size()) == 0;
}

bool starts_vsi(std::string_view text) {
    const auto first = text.find_first_not_of(" \t\r\n");
    return first != std::string_view::npos && text.size() - first >= 4 &&
           strncasecmp(text.data() + first, "/vsi", 4) == 0;
}

// An element's attribute value (or nullptr), its name compared ignoring case.
const char* attribute(const CPLXMLNode* element, std::string_view name) {
    for (const CPLXMLNode* c = element->psChild; c; c = c->psNext)
        if (c->eType == CXT_Attribute && same(c->pszValue, name))
            return c->psChild && c->psChild->eType == CXT_Text ? c->psChild->pszValue : "";
    return nullptr;
}

const CPLXMLNode* child(const CPLXMLNode* element, std::string_view name) {
    for (const CPLXMLNode* c = element->psChild; c; c = c->psNext)
        if (c->eType == CXT_Element && same(c->pszValue, name)) return c;
    return nullptr;
}

std::string text_of(const CPLXMLNode* element) {
    std::string out;
    for (const CPLXMLNode* c = element->psChild; c; c = c->psNext)
        if (c->eType == CXT_Text) out += c->pszValue;
    return out;
}

// Elements that make GDAL compute, read raw bytes or reach beyond plain sources.
constexpr std::array<std::pair<std::string_view, std::string_view>, 12> refused_elements{{
    {"PixelFunctionType", "pixel functions"},
    {"PixelFunctionLanguage", "pixel functions"},
    {"PixelFunctionCode", "pixel functions"},
    {"PixelFunctionArguments", "pixel functions"},
    {"KernelFilteredSource", "kernel-filtered sources"},
    {"OpenOptions", "open options for sources"},
    {"GDALWarpOptions", "warped VRTs (gdalwarp it into a GeoTIFF instead)"},
    {"PansharpeningOptions", "pansharpened VRTs"},
    {"ProcessingSteps", "processed VRTs"},
    {"ImageOffset", "raw-file bands"},
    {"PixelOffset", "raw-file bands"},
    {"LineOffset", "raw-file bands"},
}};

class Reader {
  public:
    VrtContents out;

    void element(const CPLXMLNode* e, int depth) {
        if (!out.refusal.empty()) return;
        if (depth > 64) return refuse("XML nested deeper than 64 levels");
        for (const auto& [name, what] : refused_elements)
            if (same(e->pszValue, name))
                return refuse(std::string(what) + " (<" + e->pszValue + ">) are not read");
        if (const char* sub = attribute(e, "subClass")) subclass(e, sub);
        if (const CPLXMLNode* file = child(e, "SourceFilename")) source(e, file);
        for (const CPLXMLNode* c = e->psChild; c && out.refusal.empty(); c = c->psNext) {
            if ((c->eType == CXT_Text || c->eType == CXT_Attribute) && starts_vsi(value(c)))
                return refuse("names a GDAL virtual file system (" + value(c) +
                              "): terrain files are local");
            if (c->eType == CXT_Element) element(c, depth + 1);
        }
    }

  private:
    void refuse(std::string why) {
        if (out.refusal.empty()) out.refusal = std::move(why);
    }

    static std::string value(const CPLXMLNode* n) {
        if (n->eType == CXT_Text) return n->pszValue ? n->pszValue : "";
        return n->psChild && n->psChild->pszValue ? n->psChild->pszValue : "";
    }

    void subclass(const CPLXMLNode* e, const char* sub) {
        if (same(e->pszValue, "VRTRasterBand") && same(sub, "VRTSourcedRasterBand")) return;
        if (same(sub, "VRTRawRasterBand"))
            return refuse("raw-file bands (VRTRawRasterBand) are not read");
        if (same(sub, "VRTDerivedRasterBand"))
            return refuse("pixel functions (VRTDerivedRasterBand) are not read");
        refuse(std::string("<") + e->pszValue + " subClass=\"" + sub + "\"> is not read");
    }

    void source(const CPLXMLNode* e, const CPLXMLNode* file) {
        // GDAL's own sources are these; anything else naming a file is refused.
        if (!same(e->pszValue, "SimpleSource") && !same(e->pszValue, "ComplexSource") &&
            !same(e->pszValue, "AveragedSource") && !same(e->pszValue, "Overview"))
            return refuse(std::string("<") + e->pszValue + "> sources are not read");
        VrtSource s;
        s.name = text_of(file);
        const char* rel = attribute(file, "relativeToVRT");
        s.relative_to_vrt = rel && std::atoi(rel) != 0;
        const CPLXMLNode* src = child(e, "SrcRect");
        const CPLXMLNode* dst = child(e, "DstRect");
        if (src && dst) {
            s.scale_x = ratio(attribute(src, "xSize"), attribute(dst, "xSize"));
            s.scale_y = ratio(attribute(src, "ySize"), attribute(dst, "ySize"));
        }
        out.sources.push_back(std::move(s));
    }

    static double ratio(const char* num, const char* den) {
        const double n = num ? std::atof(num) : 0, d = den ? std::atof(den) : 0;
        return n > 0 && d > 0 ? n / d : 1;
    }
};

}  // namespace

VrtContents read_vrt(std::string_view xml) {
    QuietErrors quiet;
    CPLXMLTreeCloser tree(CPLParseXMLString(std::string(xml).c_str()));
    Reader reader;
    if (!tree) {
        reader.out.refusal = "not a readable VRT (XML): " + QuietErrors::message();
        return std::move(reader.out);
    }
    bool has_dataset = false;
    for (const CPLXMLNode* n = tree.get(); n; n = n->psNext) {
        if (n->eType != CXT_Element) continue;
        has_dataset = has_dataset || same(n->pszValue, "VRTDataset");
        reader.element(n, 0);
    }
    if (!has_dataset && reader.out.refusal.empty())
        reader.out.refusal = "not a VRT (no <VRTDataset>)";
    return std::move(reader.out);
}

}  // namespace gimbal::terrain
