# QGIS plugin entry point: classFactory returns the plugin that registers the fdrmesh Processing provider.


def classFactory(iface):  # noqa: N802 (name required by QGIS)
    from .plugin import FdrmeshPlugin
    return FdrmeshPlugin(iface)
