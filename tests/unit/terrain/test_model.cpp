// The elevation model: tiles that join as one, nodata holes, overlapping rasters, projected
// rasters, errors naming the file, and the block cache's budget.
#include <catch2/catch.hpp>
#include <fstream>
#include <random>

#include "terrain/gdal_handle.hpp"
#include "terrain_fixture.hpp"

using namespace terrain_test;
using gimbal::geo::RayStatus;

namespace {

double bumpy(double lat, double lon) {
    const double x = east_m(lon), y = north_m(lat);
    return 400 + 300 * std::sin(x / 1700) * std::cos(y / 2300) + 0.01 * x;
}

}  // namespace

TEST_CASE("model: a raster cut into tiles answers as the whole one", "[terrain]") {
    TempDir tmp;
    const double s = 1.0 / 3600;
    const auto whole = tmp.file("whole.tif");
    REQUIRE(terrain::write_geotiff(whole, demo_grid(), bumpy).empty());
    // Four tiles with no node in common (edges between neighbouring nodes) ...
    std::vector<std::string> parts;
    const double lat_cut = 45.7, lon_cut = -121.5;
    for (const auto& [la0, la1, lo0, lo1] : {std::array{45.5, lat_cut - s, -121.7, lon_cut},
                                             std::array{45.5, lat_cut - s, lon_cut + s, -121.3},
                                             std::array{lat_cut, 45.9, -121.7, lon_cut},
                                             std::array{lat_cut, 45.9, lon_cut + s, -121.3}}) {
        parts.push_back(tmp.file("part" + std::to_string(parts.size()) + ".tif"));
        REQUIRE(terrain::write_geotiff(parts.back(), {la0, la1, lo0, lo1, s}, bumpy).empty());
    }
    // ... and SRTM-style tiles sharing their edge nodes, given by a glob.
    for (int k = 0; k < 2; ++k)
        REQUIRE(terrain::write_geotiff(tmp.file("srtm" + std::to_string(k) + ".tif"),
                                       {45.5, 45.9, k ? lon_cut : -121.7, k ? -121.3 : lon_cut, s},
                                       bumpy)
                    .empty());
    auto one = open_model({whole});
    auto four = open_model(parts);
    auto two = open_model({tmp.file("srtm*.tif")});
    CHECK(two->files().size() == 2);

    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(0, 1);
    for (int i = 0; i < 300; ++i) {
        // Near the cuts half of the time.
        const double lat = i % 2 ? lat_cut + (unit(rng) - 0.5) * 3 * s : 45.55 + 0.3 * unit(rng);
        const double lon = i % 2 ? lon_cut + (unit(rng) - 0.5) * 3 * s : -121.65 + 0.3 * unit(rng);
        const auto h = one->height(lat, lon);
        REQUIRE(h);
        CHECK(four->height(lat, lon).value() == Approx(*h).margin(1e-6));
        CHECK(two->height(lat, lon).value() == Approx(*h).margin(1e-6));
    }
    // Rays crossing the cuts meet the ground where they meet the whole raster.
    for (int i = 0; i < 40; ++i) {
        const geo::Lla from{lat_cut + (unit(rng) - 0.5) * 0.1, lon_cut + (unit(rng) - 0.5) * 0.1,
                            1500 + 1000 * unit(rng)};
        const geo::Vec3 dir = towards(from, unit(rng) * 360, 3000 + 12000 * unit(rng), 300);
        const auto a = one->intersect(from, dir, {});
        const auto b = four->intersect(from, dir, {});
        const auto c = two->intersect(from, dir, {});
        REQUIRE(a.status == b.status);
        REQUIRE(a.status == c.status);
        if (a.status != RayStatus::hit) continue;
        CHECK(std::abs(a.range_m - b.range_m) < 1e-3);
        CHECK(std::abs(a.range_m - c.range_m) < 1e-3);
    }
}

TEST_CASE("model: nodata is unknown, never zero", "[terrain]") {
    TempDir tmp;
    const auto path = tmp.file("holes.tif");
    // A hole 0.01 degrees wide around 45.7 N -121.5.
    REQUIRE(terrain::write_geotiff(path, demo_grid(), [](double lat, double lon) {
                return std::abs(lat - 45.7) < 0.005 && std::abs(lon + 121.5) < 0.005 ? NAN : 250.0;
            }).empty());
    auto model = open_model({path});
    CHECK_FALSE(model->height(45.7, -121.5));
    CHECK_FALSE(model->elevation(45.7, -121.5));
    CHECK(model->height(45.71, -121.5).value() == Approx(250));
    // Outside the raster, too.
    CHECK_FALSE(model->height(46.2, -121.5));
    CHECK_FALSE(model->height(45.7, -120.0));
    // Straight down into the hole: unknown; beside it: the ground.
    const geo::Lla over{45.7, -121.5, 1000};
    CHECK(model->intersect(over, geo::ned_to_ecef({0, 0, 1}, over), {}).status ==
          RayStatus::unknown);
    const geo::Lla beside{45.71, -121.5, 1000};
    CHECK(model->intersect(beside, geo::ned_to_ecef({0, 0, 1}, beside), {}).range_m ==
          Approx(750).margin(1e-3));
    // A slant ray whose ground point lies in the hole: unknown where it reaches the hole.
    const geo::Lla north{45.72, -121.5, 1250};
    const auto into = model->intersect(north, geo::ned_to_ecef({-2222, 0, 1000}, north), {});
    CHECK(into.status == RayStatus::unknown);
    CHECK(into.point.lat_deg == Approx(45.705).margin(2e-4));
    // A ray passing high over the hole to ground beyond it meets the ground.
    const auto over_hole = model->intersect(north, geo::ned_to_ecef({-4000, 0, 1000}, north), {});
    CHECK(over_hole.status == RayStatus::unknown);  // the hole is crossed: no ground known there
}

TEST_CASE("model: overlapping rasters, finest first, then file order", "[terrain]") {
    TempDir tmp;
    const auto coarse = tmp.file("coarse.tif");
    const auto fine = tmp.file("fine.tif");
    const auto fine_b = tmp.file("fine_b.tif");
    REQUIRE(terrain::write_geotiff(coarse, demo_grid(3.0 / 3600), [](double, double) {
                return 100.0;
            }).empty());
    REQUIRE(terrain::write_geotiff(fine, {45.65, 45.75, -121.55, -121.45, 1.0 / 3600},
                                   [](double, double) { return 200.0; })
                .empty());
    REQUIRE(terrain::write_geotiff(fine_b, {45.65, 45.75, -121.55, -121.45, 1.0 / 3600},
                                   [](double, double) { return 300.0; })
                .empty());
    for (const auto& files : {std::vector<std::string>{coarse, fine, fine_b},
                              std::vector<std::string>{fine, coarse, fine_b}}) {
        auto model = open_model(files);
        CHECK(model->height(45.7, -121.5).value() == Approx(200));
        CHECK(model->elevation(45.7, -121.5)->source == fine);
        CHECK(model->height(45.6, -121.6).value() == Approx(100));
        CHECK(model->elevation(45.6, -121.6)->source == coarse);
        // A ray low over the coarse area towards the fine one: meets the step where the fine
        // raster starts answering (its edge is a cliff from 100 to 200 m).
        const geo::Lla from{45.7, -121.6, 180};
        const geo::Vec3 east = geo::ned_to_ecef({0, 1, 0.001}, from);
        const auto hit = model->intersect(from, east, {});
        REQUIRE(hit.status == RayStatus::hit);
        CHECK(hit.point.alt_m > 150);
        CHECK(hit.point.lon_deg == Approx(-121.55).margin(1e-4));
        const auto exact = exact_intersection(*model, from, east, 20000, 1000, 0.01);
        CHECK(std::abs(exact.range_m - hit.range_m) < 0.5);
    }
    auto swapped = open_model({coarse, fine_b, fine});
    CHECK(swapped->height(45.7, -121.5).value() == Approx(300));
}

TEST_CASE("model: a projected raster is reprojected", "[terrain]") {
    TempDir tmp;
    const auto path = tmp.file("utm.tif");
    // UTM zone 10 N (EPSG:32610), 30 m pixels around 45.7 N 121.5 W, written with GDAL directly.
    terrain::gdal_init();
    terrain::SpatialRef utm(OSRNewSpatialReference(nullptr));
    REQUIRE(OSRImportFromEPSG(utm.get(), 32610) == OGRERR_NONE);
    OSRSetAxisMappingStrategy(utm.get(), OAMS_TRADITIONAL_GIS_ORDER);
    terrain::SpatialRef wgs = terrain::wgs84_lonlat();
    terrain::Transform to_lonlat(OCTNewCoordinateTransformation(utm.get(), wgs.get()));
    const int n = 700;
    const double x0 = 600000, y0 = 5072000, px = 30;
    {
        terrain::Dataset ds(
            GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), n, n, 1, GDT_Float32, nullptr));
        REQUIRE(ds);
        double gt[6] = {x0, px, 0, y0, 0, -px};
        GDALSetGeoTransform(ds.get(), gt);
        GDALSetSpatialRef(ds.get(), utm.get());
        std::vector<float> row(n);
        for (int r = 0; r < n; ++r) {
            for (int c = 0; c < n; ++c) {
                double x = x0 + (c + 0.5) * px, y = y0 - (r + 0.5) * px;
                OCTTransform(to_lonlat.get(), 1, &x, &y, nullptr);
                row[static_cast<std::size_t>(c)] = static_cast<float>(bumpy(y, x));
            }
            REQUIRE(GDALRasterIO(GDALGetRasterBand(ds.get(), 1), GF_Write, 0, r, n, 1, row.data(),
                                 n, 1, GDT_Float32, 0, 0) == CE_None);
        }
    }
    auto model = open_model({path});
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> unit(0, 1);
    int checked = 0;
    for (int i = 0; i < 200; ++i) {
        double x = x0 + 1000 + unit(rng) * (n * px - 2000),
               y = y0 - 1000 - unit(rng) * (n * px - 2000);
        OCTTransform(to_lonlat.get(), 1, &x, &y, nullptr);
        const auto h = model->height(y, x);
        REQUIRE(h);
        // Two bilinear interpolations of a smooth surface at 30 m: well under a metre.
        CHECK(*h == Approx(bumpy(y, x)).margin(0.5));
        ++checked;
    }
    CHECK(checked == 200);
    double cx = x0 + n * px / 2, cy = y0 - n * px / 2;
    OCTTransform(to_lonlat.get(), 1, &cx, &cy, nullptr);
    const geo::Lla from{cy, cx, 2000};
    const auto hit = model->intersect(from, geo::ned_to_ecef({0.3, 0.2, 1}, from), {});
    REQUIRE(hit.status == RayStatus::hit);
    CHECK(hit.point.alt_m == Approx(bumpy(hit.point.lat_deg, hit.point.lon_deg)).margin(0.5));
}

TEST_CASE("model: errors name the file", "[terrain]") {
    TempDir tmp;
    auto error = [](std::vector<std::string> files) {
        terrain::TerrainOptions o;
        o.files = std::move(files);
        o.geoid = terrain::GeoidModel::none;
        auto opened = terrain::ElevationModel::open(o);
        REQUIRE_FALSE(opened);
        return opened.error().message;
    };
    const auto good = tmp.file("good.tif");
    REQUIRE(
        terrain::write_geotiff(good, {45.6, 45.7, -121.6, -121.5, 1.0 / 360}, [](double, double) {
            return 1.0;
        }).empty());
    const auto missing = tmp.file("missing.tif");
    CHECK_THAT(error({good, missing}), Catch::Contains(missing) && Catch::Contains("no such file"));
    const auto pattern = tmp.file("none*.hgt");
    CHECK_THAT(error({pattern}), Catch::Contains(pattern) && Catch::Contains("no file matches"));
    const auto junk = tmp.file("junk.tif");
    std::ofstream(junk) << "this is not a raster\n";
    CHECK_THAT(error({good, junk}),
               Catch::Contains(junk) && Catch::Contains("not a GeoTIFF, SRTM .hgt, DTED or VRT"));
    // A raster without any CRS.
    const auto bare = tmp.file("bare.tif");
    {
        terrain::Dataset ds(GDALCreate(GDALGetDriverByName("GTiff"), bare.c_str(), 10, 10, 1,
                                       GDT_Float32, nullptr));
        double gt[6] = {-121.6, 0.01, 0, 45.7, 0, -0.01};
        GDALSetGeoTransform(ds.get(), gt);
    }
    CHECK_THAT(error({bare}),
               Catch::Contains(bare) && Catch::Contains("no coordinate reference system"));
    CHECK_THAT(error({}), Catch::Contains("names no file"));
    // A missing geoid grid is named too.
    terrain::TerrainOptions o;
    o.files = {good};
    o.geoid_grid = tmp.file("egm96_15.gtx");
    const auto opened = terrain::ElevationModel::open(o);
    REQUIRE_FALSE(opened);
    CHECK_THAT(opened.error().message, Catch::Contains(o.geoid_grid));
}

TEST_CASE("model: the block cache stays within cache_mb", "[terrain]") {
    TempDir tmp;
    const auto path = tmp.file("big.tif");
    REQUIRE(terrain::write_geotiff(path, demo_grid(), bumpy).empty());
    // 1441 x 1441 nodes = 144 blocks of 129 x 129; 1 MB holds 15.
    auto model = open_model({path}, terrain::GeoidModel::none, 1);
    const auto capacity = model->cache_stats().capacity;
    CHECK(capacity * terrain::Block::bytes() <= (1u << 20));
    CHECK(capacity >= 4);
    const double s = 1.0 / 3600;
    // Visit every block once, row by row.
    for (double lat = 45.5 + s / 2; lat < 45.9; lat += 128 * s)
        for (double lon = -121.7 + s / 2; lon < -121.3; lon += 128 * s)
            REQUIRE(model->height(lat, lon));
    auto stats = model->cache_stats();
    CHECK(stats.loads == 144);
    CHECK(stats.resident == capacity);
    CHECK(stats.evictions == 144 - capacity);
    // The last block is still there; the first was evicted and is read again.
    const auto before = stats.loads;
    REQUIRE(model->height(45.9 - s, -121.3 - s));
    CHECK(model->cache_stats().loads == before);
    REQUIRE(model->height(45.5 + s, -121.7 + s));
    CHECK(model->cache_stats().loads == before + 1);
    // Reading the same place again costs nothing.
    REQUIRE(model->height(45.5 + s, -121.7 + 2 * s));
    CHECK(model->cache_stats().loads == before + 1);
}
