# Shared fixtures for the QGIS plugin tests: real Debian QGIS 3.22, headless, throwaway profiles.
import json
import os
import shutil
import subprocess
import sys
import time

import pytest

QGIS_PROCESS = "/usr/bin/qgis_process.bin"  # Debian's /usr/bin/qgis_process wrapper is broken
HERE = os.path.dirname(os.path.abspath(__file__))
PLUGINS_DIR = os.path.dirname(HERE)  # plugins/qgis: holds the fdrmesh/ plugin folder
REPO = os.path.dirname(os.path.dirname(PLUGINS_DIR))
CHESAPEAKE = os.path.join(REPO, "testdata", "chesapeake")
GULF_OF_MAINE = os.path.join(REPO, "testdata", "gulf_of_maine")
SKIP_CODE = 77  # CTest SKIP_RETURN_CODE

FDRMESH = os.environ.get("FDRMESH") or shutil.which("fdrmesh")
SKIP_REASON = None
if not os.path.exists(QGIS_PROCESS):
    SKIP_REASON = "QGIS is not installed (%s missing): QGIS plugin tests skipped" % QGIS_PROCESS
elif not FDRMESH or not os.access(FDRMESH, os.X_OK):
    SKIP_REASON = "set FDRMESH to the fdrmesh executable (CTest does): QGIS plugin tests skipped"
else:
    FDRMESH = os.path.abspath(FDRMESH)


def pytest_sessionstart(session):
    # Why: exiting here (not at import) gives pytest's own exit code, which CTest maps to "skipped".
    if SKIP_REASON:
        pytest.exit(SKIP_REASON, returncode=SKIP_CODE)


# The in-process PyQGIS tests need these before QgsApplication starts.
os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ.setdefault("GDAL_PAM_ENABLED", "NO")
sys.path.insert(0, PLUGINS_DIR)
sys.path.insert(0, os.path.join(REPO, "tools", "qgis"))
sys.path.insert(0, "/usr/share/qgis/python/plugins")  # the Processing plugin (settings page)
from pyqgis_app import pyqgis_app  # noqa: E402


def qgis_env(profile, **extra):
    """Environment for a qgis_process.bin run with a throwaway profile."""
    env = dict(os.environ)
    env.update(QT_QPA_PLATFORM="offscreen", GDAL_PAM_ENABLED="NO", QGIS_CUSTOM_CONFIG_PATH=str(profile),
               QGIS_PLUGINPATH=PLUGINS_DIR, FDRMESH=FDRMESH, XDG_RUNTIME_DIR=str(profile))
    env.update({k: v for k, v in extra.items() if v is not None})
    for k, v in extra.items():
        if v is None:
            env.pop(k, None)
    return env


def qgis_process(profile, *args, timeout=120, **extra):
    return subprocess.run([QGIS_PROCESS, *args], env=qgis_env(profile, **extra), capture_output=True,
                          text=True, timeout=timeout)


@pytest.fixture(scope="session")
def profile(tmp_path_factory):
    """A QGIS profile with the fdrmesh plugin enabled."""
    p = tmp_path_factory.mktemp("qgis_profile")
    os.chmod(p, 0o700)
    r = qgis_process(p, "plugins", "enable", "fdrmesh")
    assert r.returncode == 0, r.stdout + r.stderr
    return p


def chesapeake_args(out_dir, **outputs):
    args = ["INPUT=%s" % os.path.join(CHESAPEAKE, "chesapeake_mouth_water.geojson"),
            "OPEN_BOUNDARY=%s" % os.path.join(CHESAPEAKE, "chesapeake_mouth_open_boundary.geojson"),
            "RASTER=%s" % os.path.join(CHESAPEAKE, "chesapeake_mouth_etopo5.tif")]
    return args + ["%s=%s" % (k, os.path.join(str(out_dir), v)) for k, v in outputs.items()]


@pytest.fixture(scope="session")
def chesapeake_run(profile, tmp_path_factory):
    """One qgis_process run of fdrmesh:meshcoastal on Chesapeake, plus the CLI's own time for comparison."""
    out = tmp_path_factory.mktemp("chesapeake")
    t0 = time.monotonic()
    r = qgis_process(profile, "--json", "run", "fdrmesh:meshcoastal", "--",
                     *chesapeake_args(out, OUTPUT="mesh.gpkg", OUTPUT_2DM="mesh.2dm", OUTPUT_UGRID="mesh.nc",
                                      OUTPUT_FORT14="mesh.14", REPORT="report.json"))
    plugin_s = time.monotonic() - t0
    assert r.returncode == 0, r.stdout + r.stderr
    cli_out = tmp_path_factory.mktemp("chesapeake_cli")
    t0 = time.monotonic()
    c = subprocess.run([FDRMESH, "mesh", os.path.join(CHESAPEAKE, "chesapeake_mouth_water.geojson"),
                        "--open-boundary", os.path.join(CHESAPEAKE, "chesapeake_mouth_open_boundary.geojson"),
                        "--raster", os.path.join(CHESAPEAKE, "chesapeake_mouth_etopo5.tif"), "-q",
                        "-o", str(cli_out / "m.gpkg"), "-o", str(cli_out / "m.2dm"), "-o", str(cli_out / "m.nc"),
                        "-o", str(cli_out / "m.14"), "--report", str(cli_out / "r.json")],
                       capture_output=True, text=True)
    cli_s = time.monotonic() - t0
    assert c.returncode == 0, c.stderr
    with open(out / "report.json") as f:
        report = json.load(f)
    return {"dir": out, "result": json.loads(r.stdout), "report": report, "plugin_s": plugin_s, "cli_s": cli_s}


@pytest.fixture(scope="session")
def qgs(tmp_path_factory):
    """An in-process QgsApplication (own profile); map layers must be deleted before it exits."""
    with pyqgis_app(tmp_path_factory.mktemp("pyqgis_profile")) as app:
        yield app
