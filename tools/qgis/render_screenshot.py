#!/usr/bin/python3
# Renders the plugin's styled Chesapeake result (triangles by quality, boundaries by kind) to a PNG, headless.
# Usage: FDRMESH=/path/to/fdrmesh /usr/bin/python3 tools/qgis/render_screenshot.py OUT.png [WIDTH_PX]
# (plugins/qgis/docs/chesapeake_qgis.png was made with WIDTH_PX 800)
import os
import sys
import tempfile

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ.setdefault("GDAL_PAM_ENABLED", "NO")
root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(root, "plugins", "qgis"))


def render_png(layers_top_first, out_png, width):
    """Draws the layers (the last one sets the extent and CRS) to out_png, width px wide, on the
    plugin's paper background; a 48-colour palette keeps the picture small. Returns (width, height)."""
    from qgis.core import QgsMapRendererParallelJob, QgsMapSettings, QgsRectangle
    from qgis.PyQt.QtCore import QSize
    from qgis.PyQt.QtGui import QColor
    base = layers_top_first[-1]
    ext = QgsRectangle(base.extent())
    ext.scale(1.03)
    ms = QgsMapSettings()
    ms.setLayers(layers_top_first)
    ms.setDestinationCrs(base.crs())
    ms.setBackgroundColor(QColor("#f4efe4"))
    ms.setOutputSize(QSize(width, int(width * ext.height() / ext.width())))
    ms.setExtent(ext)
    job = QgsMapRendererParallelJob(ms)
    job.start()
    job.waitForFinished()
    img = job.renderedImage()
    img.save(out_png, "PNG")
    try:
        from PIL import Image
        Image.open(out_png).convert("RGB").quantize(colors=48).save(out_png, optimize=True)
    except ImportError:
        pass
    return img.width(), img.height()


def main():
    from qgis.core import QgsApplication, QgsProcessingContext, QgsProcessingFeedback, QgsProject
    out_png = os.path.abspath(sys.argv[1])
    width = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
    with tempfile.TemporaryDirectory() as prof, tempfile.TemporaryDirectory() as work:
        os.environ["QGIS_CUSTOM_CONFIG_PATH"] = prof
        app = QgsApplication([], False)
        app.initQgis()
        from fdrmesh.fdrmesh_algorithm import FdrmeshMeshCoastalAlgorithm
        d = os.path.join(root, "testdata", "chesapeake")
        alg = FdrmeshMeshCoastalAlgorithm().create()
        context, feedback = QgsProcessingContext(), QgsProcessingFeedback()
        context.setProject(QgsProject.instance())
        params = {"INPUT": os.path.join(d, "chesapeake_mouth_water.geojson"),
                  "OPEN_BOUNDARY": os.path.join(d, "chesapeake_mouth_open_boundary.geojson"),
                  "RASTER": os.path.join(d, "chesapeake_mouth_etopo5.tif"),
                  "OUTPUT": os.path.join(work, "chesapeake.gpkg")}
        results, ok = alg.run(params, context, feedback)
        if not ok:
            sys.exit("run failed:\n" + feedback.textLog())
        store = context.temporaryLayerStore()
        layers = {store.mapLayer(i).name().split()[-1]: store.mapLayer(i) for i in context.layersToLoadOnCompletion()}
        shown = [layers["boundaries"], layers["triangles"]]  # top first
        width_px, height_px = render_png(shown, out_png, width)
        print("%s: %d x %d, %d triangles" % (out_png, width_px, height_px, results["TRIANGLES"]))
        del shown, layers
        store.removeAllMapLayers()
        del store, context
        app.exitQgis()


if __name__ == "__main__":
    main()
