#!/usr/bin/env python3
"""What a DEM may be (contract section 14 v4) and that reading one never stalls the io thread,
end to end with the real gimbald. Hostile DEMs - a VRT naming a server or an archive, a raw
band reading /etc/passwd (also saved as .tif), a pixel function, a source outside the terrain
folder, a sparse 1e6 x 1e6 GeoTIFF, a 2e9 x 2e9 VRT, a FIFO, 0.1 mm cells - are refused by
`--check-config` and at start with exit 1, naming the file. A real slow DEM (the simulator's
terrain as one DEFLATE tile GDAL must decode whole, mosaicked 12 deep) keeps the loader thread
busy for seconds per block while `ping` from another address still gets its answer at once.
The rasters are made with GDAL's own tools (gdal-bin).
"""

import json
import os
import shutil
import subprocess
import sys
import threading
import time
import unittest

import gimbaltest as gt
import skipping

GDAL_TOOLS = ("gdal_create", "gdal_translate", "gdalinfo")


def gdal(*args):
    result = subprocess.run(list(args), capture_output=True, text=True, timeout=120)
    if result.returncode != 0:
        raise RuntimeError("%s failed: %s" % (args[0], result.stderr))
    return result.stdout


def write(path, text):
    with open(path, "w") as f:
        f.write(text)
    return path


def vrt(size, transform, band_attributes, body):
    return ('<VRTDataset rasterXSize="%d" rasterYSize="%d">\n  <SRS>EPSG:4326</SRS>\n'
            '  <GeoTransform>%s</GeoTransform>\n'
            '  <VRTRasterBand dataType="Float32" band="1" %s>\n%s  </VRTRasterBand>\n'
            '</VRTDataset>\n' % (size[0], size[1], ", ".join(repr(v) for v in transform),
                                 band_attributes, body))


def source(name, relative=True):
    return ('    <SimpleSource><SourceFilename relativeToVRT="%d">%s</SourceFilename>'
            '<SourceBand>1</SourceBand></SimpleSource>\n' % (1 if relative else 0, name))


def raster_info(path):
    info = json.loads(gdal("gdalinfo", "-json", path))
    return info["size"], info["geoTransform"]


class DemFiles(gt.GimbaldTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        missing = [t for t in GDAL_TOOLS if not shutil.which(t)]
        if missing:
            raise unittest.SkipTest("GDAL's tools (gdal-bin) are not installed: %s" % missing)
        cls.dem_dir = os.path.join(cls.class_workdir, "dem")
        os.makedirs(cls.dem_dir)
        cls.sim_dem = os.path.join(cls.dem_dir, "sim-dem.tif")
        result = gt.run([gt.GIMBAL_SIM, "--write-dem", cls.sim_dem])
        if result.returncode != 0:
            raise RuntimeError("gimbal-sim --write-dem failed: %s" % result.stderr)
        cls.size, cls.transform = raster_info(cls.sim_dem)

    def dem(self, name):
        return os.path.join(self.dem_dir, name)

    def config(self, files):
        path = gt.unique_path(self.workdir, "terrain-", ".json")
        write(path, json.dumps({"gimbals": [], "terrain": {"files": files, "geoid": "none"}}))
        return path

    def gimbald(self, files, *args):
        # A DEM that hangs the daemon fails here by the timeout.
        return subprocess.run([gt.GIMBALD, "-c", self.config(files), *args],
                              capture_output=True, text=True, timeout=20)

    def hostile(self):
        """(name, the configured path, what the refusal says)."""
        outside = os.path.join(self.workdir, "elsewhere")
        os.makedirs(outside, exist_ok=True)
        shutil.copy(self.sim_dem, outside)
        size, gt_ = self.size, self.transform
        cases = []

        def add(name, path, why):
            cases.append((name, path, why))

        add("a /vsicurl/ path", "/vsicurl/http://127.0.0.1:9/dem.tif", "virtual file systems")
        add("a /vsizip/ path", "/vsizip/" + self.dem("dem.zip") + "/N45W122.hgt",
            "virtual file systems")
        add("a VRT naming a server",
            write(self.dem("remote.vrt"),
                  vrt(size, gt_, "", source("/vsicurl/http://127.0.0.1:9/dem.tif", False))),
            "virtual file system")
        add("a VRT naming an archive",
            write(self.dem("zipped.vrt"),
                  vrt(size, gt_, "", source("/vsizip/" + self.dem("a.zip") + "/a.tif", False))),
            "virtual file system")
        passwd = ('    <SourceFilename relativeToVRT="0">/etc/passwd</SourceFilename>\n'
                  '    <ImageOffset>0</ImageOffset><PixelOffset>1</PixelOffset>'
                  '<LineOffset>40</LineOffset>\n')
        add("a raw band reading /etc/passwd",
            write(self.dem("passwd.vrt"),
                  vrt((40, 40), gt_, 'subClass="VRTRawRasterBand"', passwd)),
            "raw-file bands")
        add("the same saved as .tif",
            write(self.dem("passwd.tif"),
                  vrt((40, 40), gt_, 'subClass="VRTRawRasterBand"', passwd)),
            "raw-file bands")
        add("a pixel function",
            write(self.dem("sum.vrt"),
                  vrt(size, gt_, 'subClass="VRTDerivedRasterBand"',
                      "    <PixelFunctionType>sum</PixelFunctionType>\n" +
                      source("sim-dem.tif"))),
            "pixel functions")
        add("a source outside the terrain folder",
            write(self.dem("outside.vrt"),
                  vrt(size, gt_, "", source(os.path.join(outside, "sim-dem.tif"), False))),
            "outside the terrain folders")
        sparse = self.dem("sparse.tif")
        gdal("gdal_create", "-q", "-outsize", "1000000", "1000000", "-ot", "Byte", "-co",
             "SPARSE_OK=TRUE", "-co", "TILED=YES", "-co", "BLOCKXSIZE=4096", "-co",
             "BLOCKYSIZE=4096", "-a_srs", "EPSG:4326", "-a_ullr", "-121.8", "45.9", "-121.7",
             "45.8", sparse)
        add("a sparse 1e6 x 1e6 GeoTIFF", sparse, "more than 2^31")
        add("a 2e9 x 2e9 VRT",
            write(self.dem("huge.vrt"),
                  vrt((2000000000, 2000000000), (-180, 1.8e-7, 0, 90, 0, -9e-8), "",
                      source("sim-dem.tif"))),
            "more than 2^31")
        fifo = self.dem("N45W122.hgt")
        os.mkfifo(fifo)
        add("a FIFO", fifo, "not a regular file")
        fine = self.dem("fine.tif")
        gdal("gdal_create", "-q", "-outsize", "100", "100", "-ot", "Byte", "-a_srs",
             "EPSG:4326", "-a_ullr", "-121.7", "45.7", "-121.6999999", "45.6999999", fine)
        add("0.1 mm cells", fine, "smaller than 1 mm")
        return cases

    def test_check_config_and_start_refuse_each_hostile_dem_by_name(self):
        for name, path, why in self.hostile():
            for args in (["--check-config"], []):
                with self.subTest(dem=name, args=args):
                    result = self.gimbald([path], *args)
                    self.assertEqual(result.returncode, 1, result)
                    self.assertIn("terrain.files: " + path, result.stderr)
                    self.assertIn(why, result.stderr)
        # A glob over the folder names the first file it refuses.
        result = self.gimbald([self.dem("*.vrt")], "--check-config")
        self.assertEqual(result.returncode, 1, result)
        self.assertIn("terrain.files: " + self.dem_dir, result.stderr)

    def test_a_vrt_over_local_files_in_the_folder_is_read(self):
        mosaic = write(self.dem("mosaic.tif"), vrt(self.size, self.transform, "",
                                                   source("sim-dem.tif")))
        result = self.gimbald([mosaic], "--check-config")
        self.assertEqual(result.returncode, 0, result)
        self.assertIn("terrain: 1 file", result.stdout)
        daemon = self.start_daemon({"terrain": {"files": [mosaic], "geoid": "none"}},
                                   args=["--sim"])
        c = self.client(daemon)
        reply = gt.wait_for(lambda: (lambda r: r if r and r.get("ok") else None)(
            c.request("elevation", lat=45.7, lon=-121.5)), 10.0, interval=0.1)
        self.assertTrue(reply, "elevation never answered through the VRT")
        self.assertEqual(reply["source"], mosaic)
        direct = self.start_daemon({"terrain": {"files": [self.sim_dem], "geoid": "none"}},
                                   args=["--sim"])
        d = self.client(direct)
        expected = gt.wait_for(lambda: (lambda r: r if r and r.get("ok") else None)(
            d.request("elevation", lat=45.7, lon=-121.5)), 10.0, interval=0.1)
        self.assertAlmostEqual(reply["alt"], expected["alt"], delta=0.001)


class SlowTerrain(gt.GimbaldTestCase):
    def setUp(self):
        super().setUp()
        missing = [t for t in GDAL_TOOLS if not shutil.which(t)]
        if missing:
            skipping.need(self, "GDAL's tools (gdal-bin) are not installed: %s" % missing)

    def slow_dem(self):
        """The simulator's terrain as one DEFLATE tile (12.7 MB decoded for any window), in
        two copies mosaicked alternately 12 deep: GDAL's cache keeps one decoded tile at most,
        so every block costs twelve whole decodes."""
        folder = os.path.join(self.workdir, "slow")
        os.makedirs(folder)
        sim_dem = os.path.join(folder, "sim-dem.tif")
        result = gt.run([gt.GIMBAL_SIM, "--write-dem", sim_dem])
        self.assertEqual(result.returncode, 0, result.stderr)
        tile = os.path.join(folder, "one-tile.tif")
        gdal("gdal_translate", "-q", "-co", "TILED=YES", "-co", "BLOCKXSIZE=2176", "-co",
             "BLOCKYSIZE=1456", "-co", "COMPRESS=DEFLATE", sim_dem, tile)
        os.remove(sim_dem)
        shutil.copy(tile, os.path.join(folder, "other-tile.tif"))
        size, transform = raster_info(tile)
        return write(os.path.join(folder, "slow.vrt"),
                     vrt(size, transform, "",
                         (source("one-tile.tif") + source("other-tile.tif")) * 6))

    def test_the_io_thread_answers_pings_while_terrain_loads(self):
        slow = self.slow_dem()
        # The simulated Orion flies over the same terrain: its footprint asks for blocks too.
        daemon = self.start_daemon({"terrain": {"files": [slow], "geoid": "none"}},
                                   args=["--sim"])
        c = self.client(daemon)
        pinger = self.client(daemon)
        rtts, stop = [], threading.Event()

        def ping():
            while not stop.is_set():
                sent = time.monotonic()
                reply = pinger.request("ping", timeout=5.0)
                rtts.append(time.monotonic() - sent if reply else 5.0)
                time.sleep(0.02)
        thread = threading.Thread(target=ping)
        thread.start()
        started = time.monotonic()
        loading_seen, answered = 0, []
        try:
            for lat, lon in ((45.62, -121.70), (45.80, -121.30), (45.55, -121.25),
                             (45.85, -121.75)):
                deadline = time.monotonic() + 120
                while time.monotonic() < deadline:
                    reply = c.request("elevation", lat=lat, lon=lon, timeout=5.0)
                    self.assertIsNotNone(reply, "no reply to elevation")
                    if reply["ok"]:
                        answered.append(time.monotonic() - started)
                        self.assertEqual(reply["source"], slow)
                        break
                    self.assertEqual(reply["error"]["code"], "unavailable", reply)
                    self.assertIn("still being read", reply["error"]["message"])
                    loading_seen += 1
                    time.sleep(0.1)
        finally:
            stop.set()
            thread.join()
        self.assertEqual(len(answered), 4, "elevation never answered while the terrain loaded")
        rtts.sort()
        p99 = rtts[int(0.99 * (len(rtts) - 1))]
        sys.stderr.write("slow DEM: %d elevation replies 'still being read', answers after %s s; "
                         "%d pings: p50 %.1f ms, p99 %.1f ms, max %.1f ms\n" %
                         (loading_seen, ", ".join("%.1f" % t for t in answered), len(rtts),
                          rtts[len(rtts) // 2] * 1000, p99 * 1000, rtts[-1] * 1000))
        # The premise: reads took longer than the io thread's wait (so one made on the io
        # thread would have shown in the pings).
        self.assertGreater(loading_seen, 0)
        self.assertLess(p99, 0.1, "ping p99 %.0f ms while terrain loaded" % (p99 * 1000))
        self.assertLess(rtts[-1], 0.5, "a ping waited %.0f ms" % (rtts[-1] * 1000))
        self.assertTrue(daemon.events("terrain_slow"))
        # SIGTERM ends it promptly although reads are still queued, and although GDAL cannot
        # interrupt the one under way (a read of this DEM takes seconds): it is left running.
        asked = time.monotonic()
        self.assertEqual(daemon.stop(), 0)
        stopping_s = time.monotonic() - asked
        sys.stderr.write("SIGTERM to exit: %.2f s\n" % stopping_s)
        self.assertLess(stopping_s, 2.0, "gimbald waited for a terrain read to end")


if __name__ == "__main__":
    gt.main()
