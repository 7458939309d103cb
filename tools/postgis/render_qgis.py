#!/usr/bin/python3
"""Renders a mesh loaded by QGIS from PostGIS to a PNG, headless (the picture of docs/postgis.md).

  QT_QPA_PLATFORM=offscreen FDRMESH=build/bin/fdrmesh /usr/bin/python3 tools/postgis/render_qgis.py OUT.png [WIDTH_PX]

Starts a throw-away server (tools/postgis/cluster.sh), loads the bundled example's water polygons
and open boundary into the table coast.water / coast.open_boundary with ogr2ogr, meshes them
from the database into the database (tables chesapeake_*), then opens chesapeake_triangles and
chesapeake_boundaries through QGIS's PostgreSQL provider and draws them with the plugin's styles
(triangles by quality, boundaries by kind). docs/img/postgis_qgis.png was made with WIDTH_PX 800.
"""
import os
import re
import subprocess
import sys
import tempfile

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ.setdefault("GDAL_PAM_ENABLED", "NO")
root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(root, "plugins", "qgis"))
sys.path.insert(0, os.path.join(root, "tools", "qgis"))


def sh(*cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("%s failed:\n%s%s" % (" ".join(cmd), r.stdout, r.stderr))
    return r.stdout


def render(conn, out_png, width):
    from qgis.core import QgsApplication, QgsDataSourceUri, QgsVectorLayer
    from fdrmesh.fdrmesh_algorithm import style_layer
    from render_screenshot import render_png
    host = re.search(r"host=(\S+)", conn).group(1)
    with tempfile.TemporaryDirectory() as prof:
        os.environ["QGIS_CUSTOM_CONFIG_PATH"] = prof
        app = QgsApplication([], False)
        app.initQgis()
        layers = {}
        for name, geom in (("triangles", "Polygon"), ("boundaries", "LineString")):
            uri = QgsDataSourceUri()
            uri.setConnection(host, "5432", "fdrtest", "postgres", "")
            uri.setDataSource("public", "chesapeake_" + name, "geom", "", "fid")
            lyr = QgsVectorLayer(uri.uri(False), name, "postgres")
            if not lyr.isValid():
                sys.exit("QGIS cannot open %s from the database" % name)
            style_layer(lyr, name, 1.0)
            layers[name] = lyr
        width_px, height_px = render_png([layers["boundaries"], layers["triangles"]], out_png, width)
        print("%s: %d x %d, %d triangles from PostGIS" % (out_png, width_px, height_px,
                                                         layers["triangles"].featureCount()))
        del layers


def main():
    out_png = os.path.abspath(sys.argv[1])
    width = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
    fdrmesh = os.environ.get("FDRMESH", os.path.join(root, "build", "bin", "fdrmesh"))
    cluster = os.path.join(root, "tools", "postgis", "cluster.sh")
    with tempfile.TemporaryDirectory() as state:
        sh("bash", cluster, "start", state)
        try:
            conn = open(os.path.join(state, "conninfo")).read().strip()
            if conn.startswith("SKIP:"):
                sys.exit(conn)
            d = os.path.join(root, "testdata", "chesapeake")
            sh("ogr2ogr", "-f", "PostgreSQL", conn, os.path.join(d, "chesapeake_mouth.gpkg"), "-overwrite",
               "-lco", "SCHEMA=coast", "-lco", "GEOMETRY_NAME=geom")
            sh(fdrmesh, "mesh", conn, "--layer", "coast.water", "--open-boundary", conn, "--open-boundary-layer",
               "coast.open_boundary", "--raster", os.path.join(d, "chesapeake_mouth_etopo5.tif"), "-q",
               "--pg-prefix", "chesapeake_", "-o", conn)
            render(conn, out_png, width)
        finally:
            subprocess.run(["bash", cluster, "stop", state], capture_output=True)


if __name__ == "__main__":
    main()
