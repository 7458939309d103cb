# The MDAL driver that opens ADCIRC fort.14 and SCHISM hgrid.gr3/.ll as mesh layers
# (libmdal_fdrmesh.so, plugins/mdal): where it is installed and whether this QGIS has loaded it.
# MDAL scans MDAL_DRIVER_PATH once, when QGIS registers its data providers, before any plugin
# loads: a plugin cannot add the driver to a running QGIS, so it names the one-time setting instead.
import glob
import os

from qgis.core import QgsProviderRegistry

DRIVER_FILE = "libmdal_fdrmesh.so"
DRIVER_NAME = "FDRMESH_ADCIRC"


def driver_dir(exe=None):
    """The folder holding the driver: mdal/ beside this plugin (a zip built with it), else
    <prefix>/lib*/fdrmesh/mdal of the fdrmesh executable `exe` (build tree or install); or None."""
    candidates = [os.path.join(os.path.dirname(os.path.abspath(__file__)), "mdal")]
    if exe:
        prefix = os.path.dirname(os.path.dirname(os.path.realpath(exe)))
        candidates.append(os.path.join(prefix, "lib", "fdrmesh", "mdal"))
        candidates += sorted(glob.glob(os.path.join(prefix, "lib*", "*", "fdrmesh", "mdal")))
        candidates += sorted(glob.glob(os.path.join(prefix, "lib?*", "fdrmesh", "mdal")))
    for d in candidates:
        if os.path.isfile(os.path.join(d, DRIVER_FILE)):
            return d
    return None


def driver_loaded():
    """True when QGIS's MDAL provider lists the driver."""
    md = QgsProviderRegistry.instance().providerMetadata("mdal")
    return md is not None and any(d.name() == DRIVER_NAME for d in md.meshDriversMetadata())


def setup_hint(exe=None):
    """None when the driver is loaded; else what to do, naming the folder when it is found."""
    if driver_loaded():
        return None
    d = driver_dir(exe)
    if d is None:
        return ("fort.14 and hgrid.gr3/.ll open as mesh layers with the fdrmesh MDAL driver (%s), "
                "which was not found beside the plugin or the fdrmesh executable" % DRIVER_FILE)
    return ("to open fort.14 and hgrid.gr3/.ll as mesh layers, set the environment variable "
            "MDAL_DRIVER_PATH=%s once (Settings > Options > System > Environment: Use custom variables, "
            "Apply 'Overwrite') and restart QGIS; MDAL reads it only when QGIS starts" % d)
