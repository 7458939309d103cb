# The QGIS plugin object: adds the fdrmesh Processing provider (also under qgis_process, where there is no GUI).
from qgis.core import Qgis, QgsApplication, QgsMessageLog

from .fdrmesh_algorithm import LOG_TAG, find_executable
from .mdal_driver import setup_hint
from .provider import FdrmeshProvider


class FdrmeshPlugin:
    def __init__(self, iface):
        self.iface = iface
        self.provider = None

    def initProcessing(self):  # noqa: N802 (QGIS API)
        if self.provider is None:
            self.provider = FdrmeshProvider()
            QgsApplication.processingRegistry().addProvider(self.provider)
            hint = setup_hint(find_executable()[0])
            if hint:
                QgsMessageLog.logMessage(hint, LOG_TAG, Qgis.Info)

    def initGui(self):  # noqa: N802 (QGIS API)
        self.initProcessing()

    def unload(self):
        if self.provider is not None:
            QgsApplication.processingRegistry().removeProvider(self.provider)
            self.provider = None
