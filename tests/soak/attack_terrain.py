"""Hostile terrain files (issue 25 items 3, 4, 5, 12): `--check-config` must refuse each by
name, quickly; when it does not, the runtime attack runs - gimbald with that DEM, the laser
firing, `elevation` requests (observe role) ten times a second.

Files: a VRT whose source is /vsicurl/ on a local HTTP server that never answers; a VRT raw
band over /etc/passwd (and the same VRT saved as .tif); a sparse 1e6 x 1e6 GeoTIFF
(gdal_create); a 2e9 x 2e9 VRT over the simulator's DEM; a FIFO named .tif. The simulator's
DEM (gimbal-sim --write-dem) covers 45.5..45.9 N, 121.8..121.2 W, where the simulated
aircraft flies: every file here is georeferenced there, so telemetry reaches it too.
"""

import os
import shutil
import socket
import subprocess
import threading

from attack_process import run_measured
from attack_rig import AttackSkipped, Client, free_port

WEST, EAST, SOUTH, NORTH = -121.8, -121.2, 45.5, 45.9
WGS84 = ('GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],'
         'PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]]')
CHECK_LIMIT_S = 2.0
CHECK_RSS_LIMIT_MB = 128.0


class StallingHttp:
    """Accepts HTTP connections, reads the request, never answers (held open)."""

    def __init__(self):
        self.listener = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        self.listener.bind(("127.0.0.1", 0))
        self.listener.listen(64)
        self.port = self.listener.getsockname()[1]
        self.held = []
        self.requests = 0
        self.running = True
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self):
        self.listener.settimeout(0.1)
        while self.running:
            try:
                conn, _ = self.listener.accept()
            except socket.timeout:
                continue
            except OSError:
                return
            conn.settimeout(0.5)
            try:
                if conn.recv(65536):
                    self.requests += 1
            except OSError:
                pass
            self.held.append(conn)

    def close(self):
        self.running = False
        self.listener.close()
        for c in self.held:
            c.close()
        self.thread.join(timeout=2)


def vrt(width, height, band):
    gt = "%.12g, %.12g, 0, %.12g, 0, %.12g" % (WEST, (EAST - WEST) / width, NORTH,
                                               -(NORTH - SOUTH) / height)
    return ('<VRTDataset rasterXSize="%d" rasterYSize="%d">\n  <SRS>%s</SRS>\n'
            '  <GeoTransform>%s</GeoTransform>\n%s</VRTDataset>\n' % (width, height, WGS84, gt,
                                                                     band))


def simple_band(source, width=2160, height=1440):
    return ('  <VRTRasterBand dataType="Float32" band="1">\n    <SimpleSource>\n'
            '      <SourceFilename relativeToVRT="0">%s</SourceFilename>\n'
            '      <SourceBand>1</SourceBand>\n'
            '      <SrcRect xOff="0" yOff="0" xSize="2160" ySize="1440"/>\n'
            '      <DstRect xOff="0" yOff="0" xSize="%d" ySize="%d"/>\n'
            '    </SimpleSource>\n  </VRTRasterBand>\n' % (source, width, height))


PASSWD_W, PASSWD_H = 64, 32


def passwd_band():
    return ('  <VRTRasterBand dataType="Byte" band="1" subClass="VRTRawRasterBand">\n'
            '    <SourceFilename relativetoVRT="0">/etc/passwd</SourceFilename>\n'
            '    <ImageOffset>0</ImageOffset>\n    <PixelOffset>1</PixelOffset>\n'
            '    <LineOffset>%d</LineOffset>\n  </VRTRasterBand>\n' % PASSWD_W)


def write(path, text):
    with open(path, "w") as f:
        f.write(text)
    return path


def check_config(suite, f, dem):
    """--check-config on a configuration whose terrain is `dem`: True when refused in time,
    naming the file."""
    d = suite.attack_dir(f.name)
    config = write(os.path.join(d, "check.json"), (
        '{"gimbals": [{"name": "orion", "protocol": "orion", "link": {"type": "tcp", '
        '"host": "127.0.0.1", "port": %d}}], "command": {"port": %d}, '
        '"terrain": {"files": ["%s"], "geoid": "none"}}' % (free_port(socket.SOCK_STREAM),
                                                            free_port(), dem)))
    timeout = 3.0 if suite.brief else 10.0
    code, seconds, rss_kb, text = run_measured([suite.gimbald, "--check-config", "-c", config],
                                            timeout)
    f.runtime = False
    f.rss_peak_kb = rss_kb
    f.note("--check-config: %s in %.2f s, peak RSS %.0f MB: %s" % (
        "killed (hung)" if code is None else "exit %d" % code, seconds, rss_kb / 1024.0,
        " ".join(text.split())[:160]))
    f.check(code is not None, "--check-config hung (killed after %.0f s)" % timeout)
    f.check(code != 0, "--check-config accepted it")
    if code == 1:
        f.check(os.path.basename(dem) in text, "--check-config did not name the file")
    f.check(seconds <= CHECK_LIMIT_S or code is None, "--check-config took %.1f s (limit %.0f)"
            % (seconds, CHECK_LIMIT_S))
    f.check(rss_kb / 1024.0 < CHECK_RSS_LIMIT_MB, "--check-config peaked at %.0f MB" %
            (rss_kb / 1024.0))
    return code == 1


def runtime(suite, f, dem, probe=None):
    """gimbald running on the DEM: the laser fires while an observe client asks `elevation`
    ten times a second over the DEM's area."""
    f.runtime = True
    with suite.rig(f, terrain=[dem]) as rig:
        asker = Client(rig.command_port, source="127.0.0.3")
        answers = []

        def elevations(stop):
            n = 0
            while not stop.wait(0.1):
                lat = SOUTH + 0.05 + (n % 30) * 0.01
                lon = WEST + 0.05 + (n % 50) * 0.01
                asker.send({"cmd": "elevation", "lat": lat, "lon": lon, "id": "e%d" % n})
                n += 1
            rig.count("elevation requests", n)

        rig.measure([elevations])
        answered = sum(1 for r in asker.replies.values())
        f.note("elevation replies: %d" % answered)
        if probe and rig.daemon.poll() is None:
            probe(rig, asker, answers)
        asker.close()


def dem_file(suite):
    def make():
        path = os.path.join(suite.workdir, "sim-dem.tif")
        subprocess.run([suite.gimbal_sim, "--write-dem", path], check=True,
                       capture_output=True, timeout=60)
        return path
    return suite.cached("sim-dem", make)


def attack(suite, f, dem, probe=None):
    if not check_config(suite, f, dem):
        runtime(suite, f, dem, probe)


def vsicurl_stall(suite, f):
    """Item 3: a VRT over /vsicurl/ on a server that never answers."""
    server = StallingHttp()
    try:
        d = suite.attack_dir(f.name)
        dem = write(os.path.join(d, "remote.vrt"), vrt(2160, 1440, simple_band(
            "/vsicurl/http://127.0.0.1:%d/dem.tif" % server.port)))
        attack(suite, f, dem)
        f.note("stalled HTTP requests: %d" % server.requests)
    finally:
        server.close()


def passwd_leak_probe(rig, asker, answers):
    """Elevation at the centres of the raster's first row: does /etc/passwd come back?"""
    f = rig.figures
    text = ""
    for i in range(PASSWD_W):
        lon = WEST + (i + 0.5) * (EAST - WEST) / PASSWD_W
        lat = NORTH - 0.5 * (NORTH - SOUTH) / PASSWD_H
        r = asker.request({"cmd": "elevation", "lat": lat, "lon": lon}, timeout=1.0)
        if r and r.get("ok") and isinstance(r.get("alt"), (int, float)):
            v = int(round(r["alt"]))
            text += chr(v) if 32 <= v < 127 else "."
    with open("/etc/passwd", "rb") as p:
        head = p.read(PASSWD_W).decode(errors="replace")
    leaked = len(text) >= 8 and text[:8] == head[:8]
    f.note("elevation along the first row: %r" % text[:24])
    f.check(not leaked, "/etc/passwd read through elevation: %r" % text[:24])


def raw_passwd(suite, f):
    """Item 5: a VRT raw band over /etc/passwd."""
    d = suite.attack_dir(f.name)
    dem = write(os.path.join(d, "passwd.vrt"), vrt(PASSWD_W, PASSWD_H, passwd_band()))
    attack(suite, f, dem, passwd_leak_probe)


def vrt_as_tif(suite, f):
    """Item 5: the same VRT saved as .tif."""
    d = suite.attack_dir(f.name)
    dem = write(os.path.join(d, "innocent.tif"), vrt(PASSWD_W, PASSWD_H, passwd_band()))
    attack(suite, f, dem, passwd_leak_probe)


def sparse_huge_tif(suite, f):
    """Item 4: a sparse 1e6 x 1e6 GeoTIFF (10^12 cells of 4.4 cm), made by gdal_create."""
    tool = shutil.which("gdal_create")
    if not tool:
        raise AttackSkipped("gdal_create (gdal-bin) is not installed")

    def make():
        path = os.path.join(suite.workdir, "sparse-1e6.tif")
        subprocess.run([tool, "-q", "-of", "GTiff", "-outsize", "1000000", "1000000", "-bands",
                        "1", "-ot", "Float32", "-co", "SPARSE_OK=YES", "-co", "TILED=YES",
                        "-co", "BLOCKXSIZE=1024", "-co", "BLOCKYSIZE=1024", "-co", "BIGTIFF=YES",
                        "-a_srs", "EPSG:4326", "-a_ullr", str(WEST), str(NORTH), str(EAST),
                        str(SOUTH), path], check=True, capture_output=True, timeout=120)
        return path
    attack(suite, f, suite.cached("sparse-tif", make))


def huge_vrt(suite, f):
    """Item 4: a 2e9 x 2e9 VRT over the simulator's DEM."""
    d = suite.attack_dir(f.name)
    dem = write(os.path.join(d, "huge.vrt"), vrt(2_000_000_000, 2_000_000_000, simple_band(
        dem_file(suite), 2_000_000_000, 2_000_000_000)))
    attack(suite, f, dem)


def fifo_dem(suite, f):
    """Item 12: a FIFO named like a GeoTIFF."""
    d = suite.attack_dir(f.name)
    path = os.path.join(d, "pipe.tif")
    if not os.path.exists(path):
        os.mkfifo(path)
    attack(suite, f, path)
