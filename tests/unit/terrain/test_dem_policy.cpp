// What terrain refuses to read (contract section 14 v4, lib/terrain/dem_policy.hpp): network
// and archive handlers, raw-file bands, pixel functions, VRT sources outside the configured
// folders, absurd raster sizes, files that are not regular files - each refused when the
// model is opened (so by `--check-config`), with a problem naming the file. The hostile files
// are real: VRTs written here, GeoTIFFs made through GDAL, a real FIFO.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>

#include "terrain/gdal_handle.hpp"
#include "terrain_fixture.hpp"

using namespace terrain_test;

namespace {

// The model's open error (the test fails when the files are accepted).
std::string refusal(std::vector<std::string> files) {
    terrain::TerrainOptions o;
    o.files = std::move(files);
    o.geoid = terrain::GeoidModel::none;
    auto opened = terrain::ElevationModel::open(o);
    REQUIRE_FALSE(opened);
    return opened.error().message;
}

// A small geographic GeoTIFF (37 x 37 nodes) whose height is 100 m + the column.
std::string good_tile(const TempDir& tmp, const std::string& name) {
    const auto path = tmp.file(name);
    REQUIRE(terrain::write_geotiff(path, {45.6, 45.7, -121.6, -121.5, 1.0 / 360},
                                   [](double, double lon) { return 100 + (lon + 121.6) * 360; })
                .empty());
    return path;
}

void write(const std::string& path, const std::string& text) {
    std::ofstream(path) << text;
}

// A VRT the size and place of the good tile, with one band: its attributes and contents.
std::string vrt(const std::string& band_attributes, const std::string& band_body,
                const std::string& size = R"(rasterXSize="37" rasterYSize="37")",
                const std::string& transform =
                    "-121.60138888889, 0.00277777778, 0, "
                    "45.70138888889, 0, -0.00277777778") {
    return "<VRTDataset " + size + ">\n  <SRS>EPSG:4326</SRS>\n  <GeoTransform>" + transform +
           "</GeoTransform>\n  <VRTRasterBand dataType=\"Float32\" band=\"1\" " + band_attributes +
           ">\n" + band_body + "  </VRTRasterBand>\n</VRTDataset>\n";
}

std::string source(const std::string& name, bool relative = true,
                   const std::string& kind = "SimpleSource") {
    return "    <" + kind + "><SourceFilename relativeToVRT=\"" + (relative ? "1" : "0") + "\">" +
           name + "</SourceFilename><SourceBand>1</SourceBand></" + kind + ">\n";
}

// A GeoTIFF through GDAL: size, pixel size (degrees, or metres in UTM 10N), creation options.
void make_geotiff(const std::string& path, int w, int h, double pixel, bool projected,
                  std::vector<const char*> options = {}) {
    terrain::gdal_init();
    options.push_back(nullptr);
    terrain::Dataset ds(GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), w, h, 1, GDT_Byte,
                                   const_cast<char**>(options.data())));
    REQUIRE(ds);
    double gt[6] = {projected ? 600000.0 : -121.6, pixel, 0,
                    projected ? 5060000.0 : 45.7,  0,     -pixel};
    GDALSetGeoTransform(ds.get(), gt);
    terrain::SpatialRef srs(OSRNewSpatialReference(nullptr));
    OSRImportFromEPSG(srs.get(), projected ? 32610 : 4326);
    GDALSetSpatialRef(ds.get(), srs.get());
}

}  // namespace

TEST_CASE("dem policy: no network or archive handler, in the configuration or in a VRT",
          "[terrain][dem_policy]") {
    TempDir tmp;
    const std::string curl = "/vsicurl/http://127.0.0.1:9/dem.tif";
    CHECK_THAT(refusal({curl}), Catch::Contains(curl) && Catch::Contains("virtual file systems"));
    const std::string zip = "/vsizip/" + tmp.file("dem.zip") + "/N45W122.hgt";
    CHECK_THAT(refusal({zip}), Catch::Contains(zip) && Catch::Contains("virtual file systems"));
    // A VRT naming a stalled server: refused before GDAL opens anything.
    const auto remote = tmp.file("remote.vrt");
    write(remote, vrt("", source(curl, false)));
    CHECK_THAT(refusal({remote}), Catch::Contains(remote) && Catch::Contains(curl) &&
                                      Catch::Contains("virtual file system"));
    const auto zipped = tmp.file("zipped.vrt");
    write(zipped, vrt("", source("/vsizip/" + tmp.file("a.zip") + "/a.tif", false)));
    CHECK_THAT(refusal({zipped}),
               Catch::Contains(zipped) && Catch::Contains("virtual file system"));
    // An SRTM tile left zipped (GDAL would open it through /vsizip/).
    const auto hgt_zip = tmp.file("N45W122.hgt.zip");
    write(hgt_zip, "PK");
    CHECK_THAT(refusal({hgt_zip}), Catch::Contains(hgt_zip) && Catch::Contains("zip archive"));
}

TEST_CASE("dem policy: a raw-file band reads nothing, whatever the VRT's name",
          "[terrain][dem_policy]") {
    TempDir tmp;
    const std::string raw_band = R"(subClass="VRTRawRasterBand")";
    const std::string passwd =
        "    <SourceFilename relativeToVRT=\"0\">/etc/passwd</SourceFilename>\n"
        "    <ImageOffset>0</ImageOffset><PixelOffset>1</PixelOffset>"
        "<LineOffset>37</LineOffset>\n";
    for (const std::string name : {"passwd.vrt", "passwd.tif"}) {
        const auto path = tmp.file(name);
        write(path, vrt(raw_band, passwd));
        CHECK_THAT(refusal({path}), Catch::Contains(path) && Catch::Contains("raw-file bands"));
    }
    // Even over a file in the terrain folder.
    const auto tile = good_tile(tmp, "tile.tif");
    const auto local = tmp.file("local-raw.vrt");
    write(local,
          vrt(raw_band, "    <SourceFilename relativeToVRT=\"1\">tile.tif</SourceFilename>\n"));
    CHECK_THAT(refusal({local}), Catch::Contains(local) && Catch::Contains("raw-file bands"));
}

TEST_CASE("dem policy: a VRT saved as .tif is read as the VRT it is", "[terrain][dem_policy]") {
    TempDir tmp;
    const auto tile = good_tile(tmp, "tile.tif");
    const auto disguised = tmp.file("mosaic.tif");
    write(disguised, vrt("", source("tile.tif")));
    auto direct = open_model({tile});
    auto through = open_model({disguised});
    for (double lat : {45.61, 45.65, 45.69})
        for (double lon : {-121.59, -121.55, -121.51}) {
            REQUIRE(direct->height(lat, lon));
            REQUIRE(through->height(lat, lon));
            CHECK(*through->height(lat, lon) == Approx(*direct->height(lat, lon)).margin(1e-4));
        }
    CHECK(through->elevation(45.65, -121.55)->source == disguised);
}

TEST_CASE("dem policy: pixel functions and other computing VRTs are refused",
          "[terrain][dem_policy]") {
    TempDir tmp;
    good_tile(tmp, "tile.tif");
    const std::vector<std::pair<std::string, std::string>> cases{
        {vrt(R"(subClass="VRTDerivedRasterBand")",
             "    <PixelFunctionType>sum</PixelFunctionType>\n" + source("tile.tif")),
         "pixel functions"},
        {vrt("", "    <PixelFunctionType>sum</PixelFunctionType>\n" + source("tile.tif")),
         "pixel functions"},
        {vrt(R"(subClass="VRTDerivedRasterBand")",
             "    <PixelFunctionLanguage>Python</PixelFunctionLanguage>\n"
             "    <PixelFunctionCode>import os</PixelFunctionCode>\n" +
                 source("tile.tif")),
         "pixel functions"},
        {vrt("",
             "    <KernelFilteredSource><SourceFilename relativeToVRT=\"1\">tile.tif"
             "</SourceFilename><Kernel><Size>3</Size><Coefs>1 1 1 1 1 1 1 1 1</Coefs>"
             "</Kernel></KernelFilteredSource>\n"),
         "kernel"},
        {R"(<VRTDataset rasterXSize="37" rasterYSize="37" subClass="VRTWarpedDataset">
  <GDALWarpOptions><SourceDataset relativeToVRT="1">tile.tif</SourceDataset></GDALWarpOptions>
</VRTDataset>)",
         "not read"},
    };
    int n = 0;
    for (const auto& [text, why] : cases) {
        const auto path = tmp.file("computing" + std::to_string(n++) + ".vrt");
        write(path, text);
        CHECK_THAT(refusal({path}), Catch::Contains(path) && Catch::Contains(why));
    }
}

TEST_CASE("dem policy: a VRT's sources lie inside the configured folders",
          "[terrain][dem_policy]") {
    TempDir tmp;
    std::filesystem::create_directories(tmp.path / "dem" / "tiles");
    std::filesystem::create_directories(tmp.path / "elsewhere");
    const auto outside = good_tile(tmp, "elsewhere/tile.tif");
    const auto inside = good_tile(tmp, "dem/tiles/tile.tif");
    const auto mosaic = tmp.file("dem/mosaic.vrt");
    const auto pattern = tmp.file("dem/*.vrt");

    write(mosaic, vrt("", source(outside, false)));
    CHECK_THAT(refusal({pattern}), Catch::Contains(mosaic) && Catch::Contains(outside) &&
                                       Catch::Contains("outside the terrain folders"));
    // Named in the configuration, that folder is a terrain folder too.
    CHECK(open_model({pattern, tmp.file("elsewhere/*.tif")}));
    // A symbolic link inside pointing outside is outside.
    std::filesystem::create_symlink(outside, tmp.path / "dem" / "link.tif");
    write(mosaic, vrt("", source("link.tif")));
    CHECK_THAT(refusal({pattern}), Catch::Contains("outside the terrain folders"));

    // Below the folder, named relative to the VRT: read.
    write(mosaic, vrt("", source("tiles/tile.tif")));
    auto model = open_model({pattern});
    CHECK(model->height(45.65, -121.55));
    // No "..", no path relative to the working directory, no connection strings.
    const std::vector<std::pair<std::string, std::string>> bad{
        {source("../elsewhere/tile.tif"), "\"..\""},
        {source("tiles/tile.tif", false), "working directory"},
        {source("GTIFF_DIR:1:" + inside, false), "not a local file path"},
        {source("&lt;VRTDataset rasterXSize=&quot;1&quot; rasterYSize=&quot;1&quot;&gt;"
                "&lt;/VRTDataset&gt;",
                false),
         "not a local file path"},
        {source("http://127.0.0.1:9/tile.tif", false), "not a local file path"},
    };
    for (const auto& [body, why] : bad) {
        write(mosaic, vrt("", body));
        CHECK_THAT(refusal({pattern}), Catch::Contains(mosaic) && Catch::Contains(why));
    }
    // A VRT naming itself, or another that names it back.
    write(mosaic, vrt("", source("mosaic.vrt")));
    CHECK_THAT(refusal({pattern}), Catch::Contains("loop"));
    write(tmp.file("dem/other.vrt"), vrt("", source("mosaic.vrt")));
    write(mosaic, vrt("", source("other.vrt")));
    CHECK_THAT(refusal({pattern}), Catch::Contains("loop"));
}

TEST_CASE("dem policy: absurd sizes are refused before anything is read", "[terrain][dem_policy]") {
    TempDir tmp;
    // A sparse 1e6 x 1e6 GeoTIFF: a few hundred KB on disk.
    const auto sparse = tmp.file("sparse.tif");
    make_geotiff(sparse, 1000000, 1000000, 1e-7, false,
                 {"SPARSE_OK=TRUE", "TILED=YES", "BLOCKXSIZE=4096", "BLOCKYSIZE=4096"});
    CHECK(std::filesystem::file_size(sparse) < (std::uintmax_t{4} << 20));
    CHECK_THAT(refusal({sparse}), Catch::Contains(sparse) && Catch::Contains("more than 2^31"));
    // A 2e9 x 2e9 VRT over a real tile.
    good_tile(tmp, "tile.tif");
    const auto huge = tmp.file("huge.vrt");
    write(huge, vrt("", source("tile.tif"), R"(rasterXSize="2000000000" rasterYSize="2000000000")",
                    "-180, 1.8e-7, 0, 90, 0, -9e-8"));
    CHECK_THAT(refusal({huge}), Catch::Contains(huge) && Catch::Contains("more than 2^31"));
    // ... and as a VRT's source.
    const auto wrapper = tmp.file("wrapper.vrt");
    write(wrapper, vrt("", source("huge.vrt")));
    CHECK_THAT(refusal({wrapper}), Catch::Contains(wrapper) && Catch::Contains("more than 2^31"));
    // Cells under 1 mm, geographic (1e-9 degrees: 0.1 mm) and projected (0.5 mm).
    const auto fine = tmp.file("fine.tif");
    make_geotiff(fine, 100, 100, 1e-9, false);
    CHECK_THAT(refusal({fine}), Catch::Contains(fine) && Catch::Contains("smaller than 1 mm"));
    const auto fine_utm = tmp.file("fine-utm.tif");
    make_geotiff(fine_utm, 100, 100, 0.0005, true);
    CHECK_THAT(refusal({fine_utm}),
               Catch::Contains(fine_utm) && Catch::Contains("smaller than 1 mm"));
    // One tile of 8192 x 8192 cells (64 MiB): every read would decode all of it.
    const auto strip = tmp.file("one-tile.tif");
    make_geotiff(strip, 8192, 8192, 1e-4, false,
                 {"TILED=YES", "BLOCKXSIZE=8192", "BLOCKYSIZE=8192", "SPARSE_OK=TRUE"});
    CHECK_THAT(refusal({strip}), Catch::Contains(strip) && Catch::Contains("TILED=YES"));
    // Down-sampling a large source window into a small one.
    const auto shrink = tmp.file("shrink.vrt");
    write(shrink, vrt("",
                      "    <SimpleSource><SourceFilename relativeToVRT=\"1\">tile.tif"
                      "</SourceFilename><SourceBand>1</SourceBand><SrcRect xOff=\"0\" yOff=\"0\" "
                      "xSize=\"37\" ySize=\"37\"/><DstRect xOff=\"0\" yOff=\"0\" xSize=\"1\" "
                      "ySize=\"1\"/></SimpleSource>\n"));
    CHECK_THAT(refusal({shrink}), Catch::Contains(shrink) && Catch::Contains("16:1"));
}

TEST_CASE("dem policy: only regular files, and a FIFO is never opened", "[terrain][dem_policy]") {
    TempDir tmp;
    const auto fifo = tmp.file("N45W122.hgt");
    REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
    CHECK_THAT(refusal({fifo}), Catch::Contains(fifo) && Catch::Contains("not a regular file"));
    CHECK_THAT(refusal({tmp.file("*.hgt")}),
               Catch::Contains(fifo) && Catch::Contains("not a regular file"));
    // As a VRT's source, and a folder named like a DEM.
    good_tile(tmp, "tile.tif");
    const auto via = tmp.file("via.vrt");
    write(via, vrt("", source("N45W122.hgt")));
    CHECK_THAT(refusal({via}), Catch::Contains(via) && Catch::Contains("not a regular file"));
    std::filesystem::create_directory(tmp.path / "folder.tif");
    CHECK_THAT(refusal({tmp.file("folder.tif")}), Catch::Contains("not a regular file"));
    // A FIFO beside a good tile, named as GDAL's side-car files, is never looked at.
    const auto tile = tmp.file("tile.tif");
    for (const char* side : {".aux.xml", ".ovr", ".msk"})
        REQUIRE(mkfifo((tile + side).c_str(), 0600) == 0);
    REQUIRE(mkfifo(tmp.file("tile.tfw").c_str(), 0600) == 0);
    auto model = open_model({tile});
    CHECK(model->height(45.65, -121.55));
}
