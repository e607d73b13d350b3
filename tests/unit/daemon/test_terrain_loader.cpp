// The terrain loader (daemon/terrain_loader.hpp, contract section 14 v4): with it the elevation
// model on the calling thread - the io thread in gimbald - never reads a file. A real slow
// source made here (one 2176 x 1456 DEFLATE tile that GDAL must decode whole for any window,
// in two copies mosaicked alternately 12 deep by a VRT; GDAL's cache keeps one decoded tile
// at most, so each block costs twelve decodes) shows a lookup answered without its block,
// the block read on the loader's thread meanwhile, and the same height as a synchronous read
// once it is there.
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

#include <boost/asio/io_context.hpp>

#include "terrain/elevation_model.hpp"
#include "terrain/gdal_handle.hpp"
#include "terrain/geotiff_writer.hpp"
#include "terrain_loader.hpp"

namespace terrain = gimbal::terrain;
using gimbald::TerrainLoader;

namespace {

struct TempDir {
    std::filesystem::path path;
    TempDir() {
        char tmpl[] = "/tmp/unit_terrain_loader.XXXXXX";
        path = mkdtemp(tmpl);
    }
    ~TempDir() { std::filesystem::remove_all(path); }
    std::string file(const std::string& name) const { return (path / name).string(); }
};

double hills(double lat, double lon) {
    return 400 + 150 * std::sin(lat * 300) * std::cos(lon * 200);
}

constexpr int width = 2176, height = 1456;
constexpr double pixel = 1.0 / 3600, west = -121.8, north = 45.9;

// One tile over the whole raster: any window decodes all 12.7 MB of it.
std::string slow_tile(const TempDir& tmp) {
    terrain::gdal_init();
    const auto path = tmp.file("one-tile.tif");
    const char* options[] = {"TILED=YES", "BLOCKXSIZE=2176", "BLOCKYSIZE=1456", "COMPRESS=DEFLATE",
                             nullptr};
    terrain::Dataset ds(GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), width, height, 1,
                                   GDT_Float32, const_cast<char**>(options)));
    REQUIRE(ds);
    double gt[6] = {west, pixel, 0, north, 0, -pixel};
    GDALSetGeoTransform(ds.get(), gt);
    terrain::SpatialRef srs(OSRNewSpatialReference(nullptr));
    OSRImportFromEPSG(srs.get(), 4326);
    GDALSetSpatialRef(ds.get(), srs.get());
    std::vector<float> values;
    values.reserve(static_cast<std::size_t>(width) * height);
    for (int r = 0; r < height; ++r)
        for (int c = 0; c < width; ++c)
            values.push_back(
                static_cast<float>(hills(north - (r + 0.5) * pixel, west + (c + 0.5) * pixel)));
    REQUIRE(GDALRasterIO(GDALGetRasterBand(ds.get(), 1), GF_Write, 0, 0, width, height,
                         values.data(), width, height, GDT_Float32, 0, 0) == CE_None);
    return path;
}

std::string slow_mosaic(const TempDir& tmp) {
    std::filesystem::copy_file(slow_tile(tmp), tmp.file("other-tile.tif"));
    const auto path = tmp.file("slow.vrt");
    std::ofstream vrt(path);
    vrt << "<VRTDataset rasterXSize=\"" << width << "\" rasterYSize=\"" << height
        << "\">\n  <SRS>EPSG:4326</SRS>\n  <GeoTransform>" << west << ", " << pixel << ", 0, "
        << north << ", 0, " << -pixel
        << "</GeoTransform>\n  <VRTRasterBand dataType=\"Float32\" band=\"1\">\n";
    for (int i = 0; i < 12; ++i)
        vrt << "    <SimpleSource><SourceFilename relativeToVRT=\"1\">"
            << (i % 2 ? "other-tile.tif" : "one-tile.tif")
            << "</SourceFilename><SourceBand>1</SourceBand></SimpleSource>\n";
    vrt << "  </VRTRasterBand>\n</VRTDataset>\n";
    return path;
}

std::unique_ptr<terrain::ElevationModel> open(const std::string& file) {
    terrain::TerrainOptions o;
    o.files = {file};
    o.geoid = terrain::GeoidModel::none;
    auto opened = terrain::ElevationModel::open(o);
    REQUIRE(opened);
    return std::move(opened).value();
}

// Asks until the model answers (the loader has read the block) or `seconds` pass.
std::optional<double> height_when_read(terrain::ElevationModel& model, double lat, double lon,
                                       double seconds) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < until) {
        if (auto h = model.height(lat, lon)) return h;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return std::nullopt;
}

}  // namespace

TEST_CASE("TerrainLoader: a slow block is unknown to the io thread until the loader has read it",
          "[terrain_loader]") {
    TempDir tmp;
    const auto mosaic = slow_mosaic(tmp);
    const double lat = 45.75, lon = -121.5;
    const double expected = *open(mosaic)->height(lat, lon);  // read here, synchronously

    boost::asio::io_context io;
    auto model = open(mosaic);
    TerrainLoader loader(io, *model);
    // Twelve decodes of 12.7 MB take far longer than the io thread's 40 ms wait: the first
    // lookup goes without its block, so the read cannot have happened on this thread.
    CHECK_FALSE(model->height(lat, lon));
    CHECK(model->cache_stats().misses >= 1);
    CHECK(loader.counters().not_ready >= 1);
    // While that read runs, lookups do not wait at all.
    CHECK_FALSE(model->height(lat, lon));
    const auto h = height_when_read(*model, lat, lon, 120);
    REQUIRE(h);
    CHECK(*h == Approx(expected).margin(1e-4));
    CHECK(loader.counters().reads >= 1);
    CHECK(model->cache_stats().loads >= 1);
}

TEST_CASE("TerrainLoader: a fast file's blocks are there, with the blocks around them read ahead",
          "[terrain_loader]") {
    TempDir tmp;
    const auto path = tmp.file("fast.tif");
    REQUIRE(terrain::write_geotiff(path, {45.6, 45.8, -121.6, -121.4, 1.0 / 3600}, hills).empty());
    boost::asio::io_context io;
    auto model = open(path);
    const auto direct = open(path);
    TerrainLoader loader(io, *model);
    const double lat = 45.7, lon = -121.5;
    const auto h = height_when_read(*model, lat, lon, 30);
    REQUIRE(h);
    CHECK(*h == Approx(*direct->height(lat, lon)).margin(1e-4));
    // The eight blocks around it (128 cells each way) are read without being asked for.
    const double block = 128.0 / 3600;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (loader.counters().reads < 9 && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    REQUIRE(loader.counters().reads >= 9);
    const auto misses = model->cache_stats().misses;
    for (int dr = -1; dr <= 1; ++dr)
        for (int dc = -1; dc <= 1; ++dc) {
            const double la = lat + dr * block, lo = lon + dc * block;
            const auto around = model->height(la, lo);
            REQUIRE(around);
            CHECK(*around == Approx(*direct->height(la, lo)).margin(1e-4));
        }
    CHECK(model->cache_stats().misses == misses);
}
