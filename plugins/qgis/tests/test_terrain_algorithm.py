# The terrain volume algorithm (fdrmesh:meshterrain) with the real QGIS 3.22, on the synthetic rasters.
import json
import os
import subprocess

from conftest import FDRMESH, REPO, qgis_process

TERRAIN = os.path.join(REPO, "testdata", "terrain")


def terrain_params(out_dir, **outputs):
    p = {"INPUT": os.path.join(TERRAIN, "synthetic_domain.geojson"), "DEM": os.path.join(TERRAIN, "synthetic_dem.tif"),
         "BASE": "-200", "HORIZONS": os.path.join(TERRAIN, "synthetic_h1.tif"), "HMIN": "150", "HMAX": "400"}
    p.update({k: os.path.join(str(out_dir), v) for k, v in outputs.items()})
    return p


def test_qgis_process_run_is_the_cli_run(profile, tmp_path):
    """qgis_process writes the CLI's volume (same VTU bytes) and the top GeoPackage; counts returned."""
    params = terrain_params(tmp_path, OUTPUT_VTU="m.vtu", OUTPUT_MSH="m.msh", OUTPUT="top.gpkg", REPORT="r.json")
    r = qgis_process(profile, "--json", "run", "fdrmesh:meshterrain", "--",
                     *("%s=%s" % kv for kv in params.items()), timeout=300)
    assert r.returncode == 0, r.stdout + r.stderr
    res = json.loads(r.stdout)["results"]
    report = json.loads((tmp_path / "r.json").read_text())
    assert res["TETRAHEDRA"] == report["counts"]["tetrahedra"] > 0
    assert [l["name"] for l in report["layers"]] == ["top-synthetic_h1", "synthetic_h1-base"]
    assert (tmp_path / "m.msh").exists() and (tmp_path / "top.gpkg").exists()
    c = subprocess.run([FDRMESH, "mesh", params["INPUT"], "--dem", params["DEM"], "--base", "-200",
                        "--horizon", params["HORIZONS"], "--hmin", "150.0", "--hmax", "400.0", "-q",
                        "-o", str(tmp_path / "cli.vtu")], capture_output=True, text=True, timeout=300)
    assert c.returncode == 0, c.stderr
    assert (tmp_path / "m.vtu").read_bytes() == (tmp_path / "cli.vtu").read_bytes()


def test_in_process_run_loads_top_layers(qgs, tmp_path):
    from qgis.core import QgsGraduatedSymbolRenderer, QgsProcessingContext, QgsProcessingFeedback, QgsProject
    from fdrmesh.terrain_algorithm import FdrmeshTerrainVolumeAlgorithm
    alg = FdrmeshTerrainVolumeAlgorithm().create()
    context = QgsProcessingContext()
    context.setProject(QgsProject.instance())
    feedback = QgsProcessingFeedback()
    results, ok = alg.run(terrain_params(tmp_path, OUTPUT_VTU="m.vtu", OUTPUT="top.gpkg"), context, feedback)
    assert ok, feedback.textLog()
    assert "layer 2 synthetic_h1-base" in feedback.textLog()
    layers = {context.temporaryLayerStore().mapLayer(lid).name(): context.temporaryLayerStore().mapLayer(lid)
              for lid in context.layersToLoadOnCompletion()}
    assert set(layers) == {"top triangles", "top boundaries", "top nodes"}
    assert isinstance(layers["top triangles"].renderer(), QgsGraduatedSymbolRenderer)
    assert "z" in layers["top nodes"].fields().names()
    assert results["VERTICES"] > 0 and results["TETRAHEDRA"] > 0
    del layers
    context.temporaryLayerStore().removeAllMapLayers()


def test_cli_error_becomes_processing_error(profile, tmp_path):
    """A horizon above the DEM everywhere: the CLI's exit 5 message, nothing written."""
    params = terrain_params(tmp_path, OUTPUT_VTU="m.vtu", OUTPUT="top.gpkg")
    params["HORIZONS"] = os.path.join(TERRAIN, "synthetic_high.tif")
    r = qgis_process(profile, "run", "fdrmesh:meshterrain", "--", *("%s=%s" % kv for kv in params.items()),
                     timeout=300)
    assert r.returncode != 0
    assert "synthetic_high" in r.stdout + r.stderr
    assert not os.listdir(tmp_path)


def test_help_lists_the_parameters(profile):
    h = qgis_process(profile, "help", "fdrmesh:meshterrain")
    assert h.returncode == 0, h.stdout + h.stderr
    for name in ("INPUT", "DEM", "BASE", "BASE_RASTER", "HORIZONS", "HMIN", "HMAX", "VERTICAL_TOL", "DEPTH_GRADE",
                 "MIN_THICKNESS", "WELLS", "WELL_SPACING", "BOUND", "CHECK", "OUTPUT_VTU", "OUTPUT_MSH", "OUTPUT", "REPORT"):
        assert name in h.stdout, name


def test_in_process_wells_without_a_domain(qgs, tmp_path):
    """No INPUT: the DEM's valid-data box; WELLS: the wells layer of the top GeoPackage loaded beside the others."""
    from qgis.core import QgsProcessingContext, QgsProcessingFeedback, QgsProject
    from fdrmesh.terrain_algorithm import FdrmeshTerrainVolumeAlgorithm
    alg = FdrmeshTerrainVolumeAlgorithm().create()
    context = QgsProcessingContext()
    context.setProject(QgsProject.instance())
    feedback = QgsProcessingFeedback()
    params = terrain_params(tmp_path, OUTPUT_VTU="m.vtu", OUTPUT="top.gpkg")
    del params["INPUT"]
    params.update({"WELLS": os.path.join(TERRAIN, "synthetic_wells.geojson"), "WELL_SPACING": "60", "HMIN": "300",
                   "HMAX": "600"})
    results, ok = alg.run(params, context, feedback)
    assert ok, feedback.textLog()
    names = {context.temporaryLayerStore().mapLayer(lid).name() for lid in context.layersToLoadOnCompletion()}
    assert names == {"top triangles", "top boundaries", "top nodes", "top wells"}
    assert results["TETRAHEDRA"] > 0
    context.temporaryLayerStore().removeAllMapLayers()
