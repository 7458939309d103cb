# End-to-end tests of the fdrmesh QGIS plugin with the real QGIS 3.22 (qgis_process.bin and PyQGIS).
import json
import os
import re
import shutil
import stat
import threading
import time

import pytest

from conftest import (CHESAPEAKE, FDRMESH, GULF_OF_MAINE, PLUGINS_DIR, chesapeake_args, qgis_process)


def _feature_count(gpkg, layer):
    from osgeo import ogr
    ds = ogr.Open(str(gpkg))
    assert ds is not None, gpkg
    lyr = ds.GetLayerByName(layer)
    assert lyr is not None, "%s has no layer %s" % (gpkg, layer)
    return lyr.GetFeatureCount()


# ---------------------------------------------------------------- (a) qgis_process run
def test_qgis_process_run_chesapeake(chesapeake_run):
    out, res, rep = chesapeake_run["dir"], chesapeake_run["result"]["results"], chesapeake_run["report"]
    assert res["VERTICES"] == rep["vertices"] > 1000
    assert res["TRIANGLES"] == rep["triangles"] > 1000
    for name in ("mesh.gpkg", "mesh.2dm", "mesh.nc", "mesh.14", "report.json"):
        assert (out / name).stat().st_size > 0, name
    assert not [n for n in os.listdir(out) if ".tmp-" in n]
    assert _feature_count(out / "mesh.gpkg", "nodes") == rep["vertices"]
    assert _feature_count(out / "mesh.gpkg", "triangles") == rep["triangles"]
    assert _feature_count(out / "mesh.gpkg", "boundaries") > 0
    # The log carries the CLI's info lines and the command line.
    info = "\n".join(chesapeake_run["result"]["log"]["info"])
    assert "working CRS" in info and "wrote %s" % (out / "mesh.gpkg") in info
    overhead = chesapeake_run["plugin_s"] - chesapeake_run["cli_s"]
    print("\nchesapeake: qgis_process %.2f s, CLI alone %.2f s, overhead %.2f s"
          % (chesapeake_run["plugin_s"], chesapeake_run["cli_s"], overhead))
    assert overhead <= 10.0


def test_gpkg_layers_valid_in_qgis(qgs, chesapeake_run):
    from qgis.core import QgsVectorLayer
    gpkg, rep = chesapeake_run["dir"] / "mesh.gpkg", chesapeake_run["report"]
    counts = {}
    for name in ("nodes", "triangles", "boundaries", "repairs"):
        lyr = QgsVectorLayer("%s|layername=%s" % (gpkg, name), name, "ogr")
        assert lyr.isValid(), name
        counts[name] = lyr.featureCount()
        assert lyr.crs().authid() == "EPSG:32618"
        del lyr
    assert counts["nodes"] == rep["vertices"] and counts["triangles"] == rep["triangles"]


# ---------------------------------------------------------------- (b) mesh layers
def test_mesh_layers_2dm_and_ugrid(qgs, chesapeake_run):
    from qgis.core import QgsCoordinateReferenceSystem, QgsMeshLayer
    from fdrmesh.fdrmesh_algorithm import gpkg_metadata
    out, rep = chesapeake_run["dir"], chesapeake_run["report"]
    wkt = gpkg_metadata(str(out / "mesh.gpkg"))["crs_wkt"]
    for name in ("mesh.2dm", "mesh.nc"):
        m = QgsMeshLayer(str(out / name), name, "mdal")
        assert m.isValid(), name
        if name.endswith(".2dm"):
            m.setCrs(QgsCoordinateReferenceSystem.fromWkt(wkt))  # a .2dm carries no CRS
        assert m.crs().authid() == "EPSG:32618", (name, m.crs().authid())
        assert m.dataProvider().vertexCount() == rep["vertices"], name
        assert m.dataProvider().faceCount() == rep["triangles"], name
        del m


def test_in_process_run_loads_styled_layers(qgs, tmp_path):
    """The algorithm run through PyQGIS: layers to load, graduated triangles, categorised boundaries, mesh CRS."""
    from qgis.core import (QgsCategorizedSymbolRenderer, QgsGraduatedSymbolRenderer, QgsMeshLayer,
                           QgsProcessingContext, QgsProcessingFeedback, QgsProject)
    from fdrmesh.fdrmesh_algorithm import FdrmeshMeshCoastalAlgorithm
    alg = FdrmeshMeshCoastalAlgorithm().create()
    params = dict(a.split("=", 1) for a in chesapeake_args(tmp_path, OUTPUT="m.gpkg", OUTPUT_2DM="m.2dm"))
    context = QgsProcessingContext()
    context.setProject(QgsProject.instance())
    feedback = QgsProcessingFeedback()
    results, ok = alg.run(params, context, feedback)
    assert ok, feedback.textLog()
    layers = {context.temporaryLayerStore().mapLayer(lid).name(): context.temporaryLayerStore().mapLayer(lid)
              for lid in context.layersToLoadOnCompletion()}
    assert set(layers) == {"m triangles", "m boundaries", "m repairs", "m nodes", "m.2dm"}
    tri = layers["m triangles"]
    assert isinstance(tri.renderer(), QgsGraduatedSymbolRenderer)
    assert tri.renderer().classAttribute() == "R_over_f"
    assert tri.featureCount() == results["TRIANGLES"]
    bnd = layers["m boundaries"].renderer()
    assert isinstance(bnd, QgsCategorizedSymbolRenderer)
    assert {c.value() for c in bnd.categories()} == {"land", "island", "open"}
    # The post-processor (run by QGIS once the layer is in the project) styles it again.
    details = context.layerToLoadOnCompletionDetails(tri.id())
    assert details.outputName == "OUTPUT" and details.postProcessor() is not None
    from qgis.core import QgsSingleSymbolRenderer, QgsSymbol
    tri.setRenderer(QgsSingleSymbolRenderer(QgsSymbol.defaultSymbol(tri.geometryType())))
    details.postProcessor().postProcessLayer(tri, context, feedback)
    assert isinstance(tri.renderer(), QgsGraduatedSymbolRenderer) and len(tri.renderer().ranges()) == 6
    assert tri.renderer().ranges()[-1].lowerValue() == 1.0  # the bound B of this run
    mesh = layers["m.2dm"]
    assert isinstance(mesh, QgsMeshLayer) and mesh.crs().authid() == "EPSG:32618"
    assert mesh.dataProvider().faceCount() == results["TRIANGLES"]
    del tri, bnd, mesh, layers
    context.temporaryLayerStore().removeAllMapLayers()


def test_gpkg_layer_input_passes_layer_name(qgs, tmp_path):
    """A layer of a multi-layer GeoPackage reaches the CLI as path + --layer (or a converted copy)."""
    from qgis.core import QgsProcessingContext, QgsProcessingFeedback
    from fdrmesh.fdrmesh_algorithm import FdrmeshMeshCoastalAlgorithm
    gpkg = os.path.join(CHESAPEAKE, "chesapeake_mouth.gpkg")
    alg = FdrmeshMeshCoastalAlgorithm().create()
    params = {"INPUT": gpkg + "|layername=water", "OPEN_BOUNDARY": gpkg + "|layername=open_boundary",
              "HMIN": 500, "OUTPUT": str(tmp_path / "g.gpkg")}
    context = QgsProcessingContext()
    args, outputs = alg.build_command(params, context, QgsProcessingFeedback())
    assert args[:3] == [FDRMESH, "mesh", gpkg] and "--layer" in args and args[args.index("--layer") + 1] == "water"
    assert args[args.index("--hmin") + 1] == "500.0"
    assert outputs == {"OUTPUT": str(tmp_path / "g.gpkg")}
    results, ok = alg.run(params, context, QgsProcessingFeedback())
    assert ok and results["TRIANGLES"] == _feature_count(tmp_path / "g.gpkg", "triangles")
    context.temporaryLayerStore().removeAllMapLayers()


# ---------------------------------------------------------------- (c) error path
@pytest.mark.parametrize("bad, code", [("SPACING=sin(", 2), ("HMIN=-5", 6)])
def test_cli_error_becomes_processing_error(profile, tmp_path, bad, code):
    r = qgis_process(profile, "run", "fdrmesh:meshcoastal", "--",
                     *chesapeake_args(tmp_path, OUTPUT="e.gpkg", OUTPUT_2DM="e.2dm"), bad)
    assert r.returncode != 0
    assert re.search(r"ERROR %d: " % code, r.stdout + r.stderr), r.stdout + r.stderr
    assert os.listdir(tmp_path) == []


def test_missing_input_file(qgs, tmp_path):
    """An input that vanished after validation: the CLI's 'ERROR 3:' line is the exception's text."""
    from qgis.core import QgsProcessingContext, QgsProcessingFeedback
    from fdrmesh.fdrmesh_algorithm import FdrmeshMeshCoastalAlgorithm
    src = tmp_path / "water.geojson"
    shutil.copy(os.path.join(CHESAPEAKE, "chesapeake_mouth_water.geojson"), src)
    alg = FdrmeshMeshCoastalAlgorithm().create()
    context, feedback = QgsProcessingContext(), QgsProcessingFeedback()
    args, _ = alg.build_command({"INPUT": str(src), "OUTPUT": str(tmp_path / "x.gpkg")}, context, feedback)
    os.remove(src)
    from qgis.core import QgsProcessingException
    with pytest.raises(QgsProcessingException, match=r"ERROR 3: .*water\.geojson"):
        alg._run(args, [str(tmp_path / "x.gpkg")], feedback)
    assert os.listdir(tmp_path) == []


# ---------------------------------------------------------------- (d) cancel
def _pids_with(text):
    pids = []
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            with open("/proc/%s/cmdline" % d, "rb") as f:
                if text.encode() in f.read():
                    pids.append(int(d))
        except OSError:
            pass
    return pids


def test_cancel_kills_cli_and_removes_outputs(qgs, tmp_path):
    from qgis.core import QgsProcessingContext, QgsProcessingFeedback
    from fdrmesh.fdrmesh_algorithm import FdrmeshMeshCoastalAlgorithm
    alg = FdrmeshMeshCoastalAlgorithm().create()
    out = tmp_path / "gom_cancel.gpkg"
    params = {"INPUT": os.path.join(GULF_OF_MAINE, "gulf_of_maine.gpkg") + "|layername=water",
              "RASTER": os.path.join(GULF_OF_MAINE, "gulf_of_maine_etopo5.tif"), "HMIN": 20,
              "OUTPUT": str(out), "OUTPUT_2DM": str(tmp_path / "gom_cancel.2dm")}
    context, feedback = QgsProcessingContext(), QgsProcessingFeedback()
    seen = {}

    def cancel():
        seen["pids"] = _pids_with(str(out))
        seen["t"] = time.monotonic()
        feedback.cancel()

    timer = threading.Timer(2.5, cancel)
    timer.start()
    results, ok = alg.run(params, context, feedback)
    elapsed = time.monotonic() - seen["t"]
    timer.join()
    assert seen["pids"], "fdrmesh was not running when canceled (finished too early?)"
    assert not ok and "canceled" in feedback.textLog()
    print("\ncancel: run returned %.2f s after cancel()" % elapsed)
    assert elapsed < 2.0
    assert _pids_with(str(out)) == []
    for pid in seen["pids"]:
        assert not os.path.exists("/proc/%d" % pid)
    assert os.listdir(tmp_path) == []


def test_progress_parser():
    from fdrmesh.fdrmesh_algorithm import ProgressParser
    p = ProgressParser()
    seen = []
    for chunk in ["0.", "..1", "0...2", "0...30...40...50...60...70...80...90...100 - done.\n",
                  "warning: something\n", "0..ERROR 7: too many Steiner points\n"]:
        p.feed(chunk)
        seen.append(p.percent)
    p.close()
    assert seen[:4] == [0, 0, 10, 100]
    assert p.messages == ["warning: something"]
    assert p.errors == ["ERROR 7: too many Steiner points"]


# ---------------------------------------------------------------- (e) unavailable provider
def _fake_fdrmesh(path, version):
    path.write_text("#!/bin/sh\nif [ \"$1\" = --version ]; then echo 'fdrmesh %s'; exit 0; fi\n"
                    "exec %s \"$@\"\n" % (version, FDRMESH))
    path.chmod(path.stat().st_mode | stat.S_IXUSR)
    return str(path)


@pytest.mark.parametrize("case", ["missing", "wrong_version"])
def test_provider_unavailable(qgs, tmp_path, monkeypatch, case):
    from qgis.core import QgsApplication, QgsProcessingContext, QgsProcessingFeedback
    from fdrmesh.provider import FdrmeshProvider
    exe = str(tmp_path / "no_such_fdrmesh") if case == "missing" else _fake_fdrmesh(tmp_path / "fdrmesh", "9.9.9")
    monkeypatch.setenv("FDRMESH", exe)
    log = []
    QgsApplication.messageLog().messageReceived.connect(lambda msg, tag, level: log.append((tag, msg)))
    provider = FdrmeshProvider()
    assert QgsApplication.processingRegistry().addProvider(provider)
    try:
        alg = QgsApplication.processingRegistry().createAlgorithmById("fdrmesh:meshcoastal")
        ok, why = alg.canExecute()
        expected = "not an executable file" if case == "missing" else "version mismatch"
        assert not ok and expected in why and exe in why
        assert expected in alg.shortHelpString()
        assert expected in provider.warningMessage()
        assert any(tag == "fdrmesh" and expected in msg for tag, msg in log), log
        if case == "wrong_version":
            assert "fdrmesh 9.9.9" in why and "needs fdrmesh 0.1.0" in why
        results, ran = alg.run({"OUTPUT": str(tmp_path / "o.gpkg")}, QgsProcessingContext(), QgsProcessingFeedback())
        assert not ran
    finally:
        QgsApplication.processingRegistry().removeProvider(provider)


def test_qgis_process_reports_missing_binary(profile, tmp_path):
    r = qgis_process(profile, "run", "fdrmesh:meshcoastal", "--",
                     *chesapeake_args(tmp_path, OUTPUT="o.gpkg"), FDRMESH=str(tmp_path / "nope"))
    assert r.returncode != 0
    assert "fdrmesh is unavailable" in r.stdout + r.stderr and "not an executable file" in r.stdout + r.stderr


# ---------------------------------------------------------------- (f) processing script form
def test_standalone_script_from_scripts_folder(tmp_path):
    prof = tmp_path / "profile"
    scripts = prof / "profiles" / "default" / "processing" / "scripts"
    scripts.mkdir(parents=True)
    shutil.copy(os.path.join(PLUGINS_DIR, "fdrmesh", "fdrmesh_algorithm.py"), scripts)
    out = tmp_path / "out"
    out.mkdir()
    r = qgis_process(prof, "--json", "run", "script:meshcoastal", "--",
                     *chesapeake_args(out, OUTPUT="s.gpkg", REPORT="s.json"), QGIS_PLUGINPATH=None)
    assert r.returncode == 0, r.stdout + r.stderr
    res = json.loads(r.stdout)["results"]
    with open(out / "s.json") as f:
        rep = json.load(f)
    assert res["TRIANGLES"] == rep["triangles"] == _feature_count(out / "s.gpkg", "triangles")


def test_script_version_matches_metadata():
    import configparser
    from fdrmesh import fdrmesh_algorithm
    meta = configparser.ConfigParser()
    meta.read(os.path.join(PLUGINS_DIR, "fdrmesh", "metadata.txt"))
    assert meta["general"]["version"] == fdrmesh_algorithm.PLUGIN_VERSION == fdrmesh_algorithm.plugin_version()
    assert meta["general"]["hasProcessingProvider"] == "yes" and meta["general"]["qgisMinimumVersion"] == "3.22"


def test_parameters_follow_json_usage(qgs):
    """Every mesh option of --json-usage has a parameter (or is one the plugin drives itself)."""
    import subprocess
    from fdrmesh.fdrmesh_algorithm import FdrmeshMeshCoastalAlgorithm, param_name
    usage = json.loads(subprocess.run([FDRMESH, "--json-usage"], capture_output=True, text=True).stdout)
    opts = next(c for c in usage["commands"] if c["name"] == "mesh")["options"]
    alg = FdrmeshMeshCoastalAlgorithm().create()
    names = {p.name(): p for p in alg.parameterDefinitions()}
    keys = {o["key"] for o in opts}
    for o in opts:
        paired = o["key"] == "layer" or (o["key"].endswith("-layer") and o["key"][:-6] in keys)
        if o["key"] == "output":
            continue  # one output parameter per format, checked below
        if o["key"] in ("of", "quiet") or paired:
            assert param_name(o["key"]) not in names
            continue
        p = names[param_name(o["key"])]
        want = {"vector_in": "source", "raster_in": "raster", "float": "number", "int": "number",
                "flag": "boolean", "crs": "crs", "choice": "enum", "bbox": "extent", "expr": "string",
                "string": "string", "file_out": "fileDestination"}[o["type"]]
        assert p.type() == want, (o["key"], p.type())
    for out in ("OUTPUT", "OUTPUT_2DM", "OUTPUT_UGRID", "OUTPUT_FORT14"):
        assert names[out].type() == "fileDestination"
    # One output per format the CLI publishes (Telemac, SCHISM, Delft3D FM included).
    for f in usage["output_formats"]:
        out = "OUTPUT" if f["name"] == "GPKG" else "OUTPUT_" + f["name"]
        if any(e.endswith(":") for e in f["extensions"]):  # PostGIS: a connection, not a file
            assert out not in names
            continue
        assert names[out].type() == "fileDestination", out
        assert bool(names[out].flags() & names[out].FlagOptional) == (out != "OUTPUT")
    assert "*_net.nc" in names["OUTPUT_DFLOWFM"].fileFilter() and "*.slf" in names["OUTPUT_SELAFIN"].fileFilter()
    # INPUT follows the CLI: optional, since --land with --extent can define the domain instead;
    # both are among the common (non-advanced) parameters.
    assert bool(names["INPUT"].flags() & names["INPUT"].FlagOptional) == (not usage_required(opts, "input"))
    assert not names["INPUT"].flags() & names["INPUT"].FlagAdvanced
    assert not names["LAND"].flags() & names["LAND"].FlagAdvanced
    assert names["CHECK"].flags() & names["CHECK"].FlagAdvanced
    assert not names["HMIN"].flags() & names["HMIN"].FlagAdvanced


def usage_required(opts, key):
    return next(o for o in opts if o["key"] == key).get("required", False)


# ---------------------------------------------------------------- plugin zip
def test_plugin_zip_installs(tmp_path):
    import subprocess
    import zipfile
    script = os.path.join(os.path.dirname(os.path.dirname(PLUGINS_DIR)), "tools", "qgis", "build_plugin_zip.sh")
    r = subprocess.run(["bash", script, str(tmp_path / "dist")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    zpath = r.stdout.strip()
    assert os.path.basename(zpath) == "fdrmesh-qgis-0.1.0.zip"
    with zipfile.ZipFile(zpath) as z:
        names = z.namelist()
        assert all(n.startswith("fdrmesh/") for n in names)
        assert {"fdrmesh/__init__.py", "fdrmesh/metadata.txt", "fdrmesh/fdrmesh_algorithm.py"} <= set(names)
        assert not [n for n in names if "__pycache__" in n]
        z.extractall(tmp_path / "plugins")
    prof = tmp_path / "profile"
    prof.mkdir()
    plugin_path = str(tmp_path / "plugins")
    assert qgis_process(prof, "plugins", "enable", "fdrmesh", QGIS_PLUGINPATH=plugin_path).returncode == 0
    h = qgis_process(prof, "help", "fdrmesh:meshcoastal", QGIS_PLUGINPATH=plugin_path)
    assert h.returncode == 0 and "OPEN_BOUNDARY" in h.stdout and "OUTPUT_UGRID" in h.stdout, h.stdout + h.stderr


def test_mesh_outputs_fallback_and_order():
    from fdrmesh.fdrmesh_algorithm import _MESH_OUTPUTS, mesh_outputs
    assert mesh_outputs({}) == _MESH_OUTPUTS  # an older CLI without "output_formats"
    usage = {"output_formats": [
        {"name": "2DM", "extensions": [".2dm"], "label": "SMS 2DM mesh", "carries": "z up"},
        {"name": "GPKG", "extensions": [".gpkg"], "label": "GeoPackage", "carries": ""},
        {"name": "DFLOWFM", "extensions": ["_net.nc"], "label": "Delft3D FM net", "carries": "CRS"},
        {"name": "FORT14", "extensions": [".14", "fort.14"], "label": "ADCIRC", "carries": ""}]}
    outs = mesh_outputs(usage)
    assert [o[0] for o in outs] == ["OUTPUT", "OUTPUT_2DM", "OUTPUT_DFLOWFM", "OUTPUT_FORT14"]
    assert outs[0][3] is False and all(o[3] for o in outs[1:])
    assert outs[2][2] == "Delft3D FM net (*_net.nc)" and outs[3][2] == "ADCIRC (*.14 fort.14)"


def test_model_outputs_through_the_plugin(profile, tmp_path):
    """Telemac and Delft3D FM outputs from the Processing algorithm; the .cli comes along."""
    r = qgis_process(profile, "--json", "run", "fdrmesh:meshcoastal", "--",
                     *chesapeake_args(tmp_path, OUTPUT="p.gpkg", OUTPUT_SELAFIN="p.slf", OUTPUT_DFLOWFM="p_net.nc",
                                      OUTPUT_GR3="p.gr3"))
    assert r.returncode == 0, r.stdout + r.stderr
    assert {"p.gpkg", "p.slf", "p.cli", "p_net.nc", "p.gr3"} <= set(os.listdir(tmp_path))
