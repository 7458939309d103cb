# Processing provider "fdrmesh": the "fdrmesh executable" setting, availability check, the coastal
# mesh and terrain volume algorithms.
from qgis.core import Qgis, QgsMessageLog, QgsProcessingProvider

from .fdrmesh_algorithm import LOG_TAG, SETTING_NAME, FdrmeshMeshCoastalAlgorithm, plugin_version, probe
from .terrain_algorithm import FdrmeshTerrainVolumeAlgorithm

try:  # the Processing plugin's settings page; absent only in a bare PyQGIS session
    from processing.core.ProcessingConfig import ProcessingConfig, Setting
except ImportError:  # pragma: no cover
    ProcessingConfig = Setting = None


class FdrmeshProvider(QgsProcessingProvider):
    def id(self):
        return "fdrmesh"

    def name(self):
        return "fdrmesh"

    def longName(self):
        return "fdrmesh %s (Functional Delaunay Refinement)" % plugin_version()

    def versionInfo(self):
        return plugin_version()

    def load(self):
        if ProcessingConfig is not None:
            ProcessingConfig.settingIcons[self.name()] = self.icon()
            ProcessingConfig.addSetting(Setting(self.name(), SETTING_NAME, "fdrmesh executable", "",
                                                valuetype=Setting.FILE))
            ProcessingConfig.readSettings()
            try:
                ProcessingConfig.settingsWatcher.settingsChanged.connect(self._settings_changed)
            except AttributeError:
                pass
        self.refreshAlgorithms()
        return True

    def unload(self):
        if ProcessingConfig is not None:
            try:
                ProcessingConfig.settingsWatcher.settingsChanged.disconnect(self._settings_changed)
            except (AttributeError, TypeError):
                pass
            ProcessingConfig.removeSetting(SETTING_NAME)

    def _settings_changed(self):
        self.refreshAlgorithms()

    def warningMessage(self):  # noqa: N802 (QGIS API)
        st = probe()
        return "" if st["ok"] else "fdrmesh is unavailable: " + st["reason"]

    def loadAlgorithms(self):  # noqa: N802 (QGIS API)
        st = probe()
        if st["ok"]:
            QgsMessageLog.logMessage("fdrmesh provider: using %s (fdrmesh %s)" % (st["exe"], st["version"]),
                                     LOG_TAG, Qgis.Info)
        else:
            QgsMessageLog.logMessage("fdrmesh provider unavailable: " + st["reason"], LOG_TAG, Qgis.Critical)
        self.addAlgorithm(FdrmeshMeshCoastalAlgorithm())
        self.addAlgorithm(FdrmeshTerrainVolumeAlgorithm())
