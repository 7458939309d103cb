"""An in-process QGIS application for the project's PyQGIS tests (one definition for every test folder)."""
import contextlib
import gc
import os


@contextlib.contextmanager
def pyqgis_app(profile_dir):
    """A headless QgsApplication on a throwaway profile; map layers must be deleted before it exits."""
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    os.environ["QGIS_CUSTOM_CONFIG_PATH"] = str(profile_dir)
    os.environ.setdefault("XDG_RUNTIME_DIR", str(profile_dir))
    from qgis.core import QgsApplication
    QgsApplication.setPrefixPath("/usr", True)
    app = QgsApplication([], False)
    app.initQgis()
    try:
        yield app
    finally:
        # Why: layers still referenced from Python would be freed after exitQgis and crash the process.
        gc.collect()
        app.exitQgis()
