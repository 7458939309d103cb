# Processing algorithm "Mesh coastal domain (FDR)": runs the fdrmesh CLI; also usable alone as a Processing script.
"""The parameters are not written here: they are built when the algorithm is created, from the
option table that ``fdrmesh --json-usage`` prints.  The file is self-contained (standard library and
qgis.* imports only) so that it can be dropped into QGIS's Processing scripts folder as it is.

The fdrmesh executable is looked up in this order: the Processing setting "fdrmesh executable"
(QgsSettings key ``Processing/Configuration/FDRMESH_EXECUTABLE``), the environment variable
``FDRMESH``, then ``PATH``.  Its ``--version`` must equal the plugin's version, or the algorithm
refuses to run and says why.
"""

import json
import os
import queue
import re
import shutil
import signal
import sqlite3
import subprocess
import tempfile
import threading

from qgis.core import (
    Qgis,
    QgsCategorizedSymbolRenderer,
    QgsCoordinateReferenceSystem,
    QgsDataSourceUri,
    QgsGradientColorRamp,
    QgsGraduatedSymbolRenderer,
    QgsMarkerSymbol,
    QgsMeshLayer,
    QgsMessageLog,
    QgsProcessing,
    QgsProcessingAlgorithm,
    QgsProcessingContext,
    QgsProcessingException,
    QgsProcessingFeatureSourceDefinition,
    QgsProcessingLayerPostProcessorInterface,
    QgsProcessingOutputNumber,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterCrs,
    QgsProcessingParameterDefinition,
    QgsProcessingParameterEnum,
    QgsProcessingParameterExtent,
    QgsProcessingParameterFeatureSource,
    QgsProcessingParameterFile,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterNumber,
    QgsProcessingParameterRasterLayer,
    QgsProcessingParameterString,
    QgsRendererCategory,
    QgsRendererRange,
    QgsSettings,
    QgsStyle,
    QgsSymbol,
    QgsVectorLayer,
)
from qgis.PyQt.QtGui import QColor

# The version this algorithm was written for; metadata.txt beside this file (plugin form) wins.
PLUGIN_VERSION = "0.1.0"
SETTING_KEY = "Processing/Configuration/FDRMESH_EXECUTABLE"
SETTING_NAME = "FDRMESH_EXECUTABLE"
LOG_TAG = "fdrmesh"

# Options the plugin drives itself: -o becomes one output parameter per format, --of would
# contradict them, --quiet would hide the lines we forward to the log.
_HANDLED_KEYS = {"output", "of", "quiet"}
# Options shown on the main page of the dialog; every other option goes under "Advanced".
_COMMON_KEYS = {"input", "open-boundary", "land", "extent", "raster", "spacing", "hmin", "hmax", "t_srs"}
# One output parameter per mesh format (the CLI picks the format from the extension). The list
# comes from `fdrmesh --json-usage` ("output_formats", see mesh_outputs); this one is the fallback
# for an older CLI that does not publish it.
_MESH_OUTPUTS = [
    ("OUTPUT", "Output GeoPackage (nodes, triangles, boundaries, repairs)", "GeoPackage (*.gpkg)", False),
    ("OUTPUT_2DM", "Output SMS 2DM mesh", "SMS 2DM (*.2dm)", True),
    ("OUTPUT_UGRID", "Output UGRID netCDF mesh", "UGRID netCDF (*.nc)", True),
    ("OUTPUT_FORT14", "Output ADCIRC fort.14 mesh", "ADCIRC fort.14 (*.14 *.grd)", True),
]


def mesh_outputs(usage):
    """(parameter name, description, file filter, optional) per output format the CLI publishes:
    OUTPUT for the GeoPackage (required: the plugin loads its layers), OUTPUT_<NAME> for the others."""
    fmts = (usage or {}).get("output_formats")
    if not fmts:
        return list(_MESH_OUTPUTS)
    out = []
    for f in fmts:
        if is_database_format(f):
            continue  # a database target is a connection string, not a file to choose
        name = "OUTPUT" if f["name"] == "GPKG" else "OUTPUT_" + f["name"]
        pats = " ".join(e if not e.startswith((".", "_")) else "*" + e for e in f.get("extensions", []))
        desc = "Output %s" % f.get("label", f["name"])
        if f.get("carries"):
            desc += " [%s]" % f["carries"]
        out.append((name, desc, "%s (%s)" % (f.get("label", f["name"]), pats), name != "OUTPUT"))
    out.sort(key=lambda o: o[0] != "OUTPUT")  # the GeoPackage first
    return out
_OGR_FORMATS = ["gpkg", "shp", "geojson", "json", "fgb", "gml", "kml", "sqlite", "tab", "mif"]
_BOUNDARY_COLOURS = {"land": "#8c6d31", "island": "#31a354", "open": "#2171b5"}


def plugin_version():
    """The version in metadata.txt beside this file, else PLUGIN_VERSION (script form)."""
    meta = os.path.join(os.path.dirname(os.path.abspath(__file__)), "metadata.txt")
    try:
        with open(meta, encoding="utf-8") as f:
            for line in f:
                m = re.match(r"\s*version\s*=\s*(\S+)", line)
                if m:
                    return m.group(1)
    except OSError:
        pass
    return PLUGIN_VERSION


def find_executable():
    """(path or None, where it came from, reason when missing)."""
    configured = QgsSettings().value(SETTING_KEY, "", type=str) or ""
    if configured.strip():
        p = configured.strip()
        if os.path.isfile(p) and os.access(p, os.X_OK):
            return p, "Processing setting 'fdrmesh executable'", ""
        return None, "", "the Processing setting 'fdrmesh executable' points to '%s', which is not an executable file" % p
    env = os.environ.get("FDRMESH", "").strip()
    if env:
        if os.path.isfile(env) and os.access(env, os.X_OK):
            return env, "environment variable FDRMESH", ""
        return None, "", "the environment variable FDRMESH points to '%s', which is not an executable file" % env
    found = shutil.which("fdrmesh")
    if found:
        return found, "PATH", ""
    return None, "", ("fdrmesh was not found: set the Processing setting 'fdrmesh executable' "
                      "(Settings > Options > Processing > Providers > fdrmesh), the environment variable FDRMESH, "
                      "or put fdrmesh on PATH")


_probe_cache = {}


def probe():
    """Checks the executable once per (path, mtime): returns dict(ok, exe, reason, usage, version)."""
    exe, where, reason = find_executable()
    want = plugin_version()
    if not exe:
        return {"ok": False, "exe": None, "reason": reason, "usage": None, "version": None}
    try:
        key = (exe, os.stat(exe).st_mtime_ns, want)
    except OSError as e:
        return {"ok": False, "exe": exe, "reason": "%s: %s" % (exe, e), "usage": None, "version": None}
    if key in _probe_cache:
        return _probe_cache[key]
    res = {"ok": False, "exe": exe, "reason": "", "usage": None, "version": None}
    try:
        out = subprocess.run([exe, "--version"], capture_output=True, text=True, timeout=20)
        m = re.match(r"\s*fdrmesh\s+(\S+)", out.stdout)
        if out.returncode != 0 or not m:
            res["reason"] = "'%s --version' (found via %s) did not print 'fdrmesh <version>' (exit %d: %s)" % (
                exe, where, out.returncode, (out.stdout + out.stderr).strip()[:200])
        elif m.group(1) != want:
            res["version"] = m.group(1)
            res["reason"] = ("version mismatch: %s (found via %s) is fdrmesh %s, this plugin needs fdrmesh %s"
                             % (exe, where, m.group(1), want))
        else:
            res["version"] = m.group(1)
            usage = subprocess.run([exe, "--json-usage"], capture_output=True, text=True, timeout=20)
            if usage.returncode != 0:
                res["reason"] = "'%s --json-usage' failed (exit %d): %s" % (exe, usage.returncode, usage.stderr.strip()[:200])
            else:
                res["usage"] = json.loads(usage.stdout)
                res["ok"] = True
    except (OSError, subprocess.SubprocessError, ValueError) as e:
        res["reason"] = "cannot run %s (found via %s): %s" % (exe, where, e)
    if not res["ok"]:
        QgsMessageLog.logMessage("fdrmesh provider unavailable: " + res["reason"], LOG_TAG, Qgis.Warning)
    _probe_cache[key] = res
    return res


def param_name(key):
    """CLI option key -> Processing parameter name ('open-boundary' -> 'OPEN_BOUNDARY')."""
    return re.sub(r"[^A-Za-z0-9]+", "_", key).strip("_").upper()


def _label(opt):
    """A short dialog label from the option's help text."""
    text = opt.get("help", "") or opt["key"]
    for sep in (": ", "; ", " ("):
        if len(text) > 70 and sep in text:
            text = text.split(sep, 1)[0]
    return text


def _number_default(opt):
    try:
        return float(opt.get("default", ""))
    except ValueError:
        return None


def is_database_format(fmt):
    """True for an output format written into a database (its "extension" is a prefix such as PG:)."""
    return any(e.endswith(":") for e in fmt.get("extensions", []))


def redact_passwords(text):
    """`text` without the password=... parts of database connection strings (for the log)."""
    text = re.sub(r"(?i)(^|[\s?&:'\"])password\s*=\s*('(?:[^'\\]|\\.)*'|[^\s&'\"]*)[ &]?", r"\1", text)
    return re.sub(r"(?i)(postgres(?:ql)?://[^:/@\s]*):[^@/\s]*@", r"\1@", text)


def _libpq_value(v):
    """A libpq connection-string value, quoted when it has blanks or quotes."""
    v = str(v)
    if v and not re.search(r"[\s'\\]", v):
        return v
    return "'" + v.replace("\\", "\\\\").replace("'", "\\'") + "'"


def postgis_source(layer):
    """(GDAL "PG:" connection string, "schema.table", subset SQL) of a PostGIS layer, so fdrmesh
    reads the table itself; None when QGIS must export the features instead (another provider,
    credentials kept in QGIS's authentication database, or a layer made from an SQL query)."""
    if layer is None or layer.providerType() != "postgres":
        return None
    uri = QgsDataSourceUri(layer.source())
    if uri.authConfigId() or not uri.table() or uri.table().startswith("("):
        return None
    parts = []
    for key, value in (("service", uri.service()), ("host", uri.host()), ("port", uri.port()),
                       ("dbname", uri.database()), ("user", uri.username()), ("password", uri.password())):
        if value:
            parts.append("%s=%s" % (key, _libpq_value(value)))
    if uri.sslMode() not in (QgsDataSourceUri.SslPrefer,):
        parts.append("sslmode=%s" % QgsDataSourceUri.encodeSslMode(uri.sslMode()))
    table = "%s.%s" % (uri.schema(), uri.table()) if uri.schema() else uri.table()
    return "PG:" + " ".join(parts), table, uri.sql()


def layer_option_key(usage_opts, opt):
    """The option that names the layer to read from a vector_in option's file, if the CLI has one."""
    keys = {o["key"] for o in usage_opts}
    candidate = "layer" if opt.get("positional") else opt["key"] + "-layer"
    return candidate if candidate in keys else None


class ProgressParser:
    """Turns the CLI's stderr (GDAL ticks '0...10...20... - done.' and 'ERROR n: ...' lines) into events."""

    _tick = re.compile(r"(\d+)\.")

    def __init__(self):
        self.line = ""
        self.percent = None
        self.errors = []
        self.messages = []

    def feed(self, text):
        for ch in text:
            if ch in "\r\n":
                self._end_line()
                continue
            self.line += ch
            # Why: ticks arrive a few characters at a time, so progress is read from the partial line.
            if ch == "." and "ERROR" not in self.line:
                ticks = self._tick.findall(self.line)
                if ticks:
                    self.percent = min(100, int(ticks[-1]))
            if self.line.endswith(" - done."):
                self.percent = 100

    def _end_line(self):
        line, self.line = self.line, ""
        m = re.search(r"ERROR\s+\d+:.*", line)
        if m:
            self.errors.append(m.group(0).strip())
            return
        # Why: a message can follow ticks on the same line ("0..ERROR 7: ..."); drop the tick prefix.
        rest = re.match(r"^((?:\d+\.+)*(?:\d+\s*-\s*done\.)?)(.*)$", line).group(2).strip()
        if rest:
            self.messages.append(rest)

    def close(self):
        if self.line:
            self._end_line()


class _StylePostProcessor(QgsProcessingLayerPostProcessorInterface):
    """Styles a result layer once it is in the project (runs in the main thread)."""

    def __init__(self, kind, bound):
        super().__init__()
        self.kind = kind
        self.bound = bound

    def postProcessLayer(self, layer, context, feedback):
        if isinstance(layer, QgsVectorLayer):
            style_layer(layer, self.kind, self.bound)


_post_processors = []  # kept alive until QGIS has called them


def _ramp():
    ramp = QgsStyle.defaultStyle().colorRamp("RdYlGn")
    if ramp is None:
        ramp = QgsGradientColorRamp(QColor("#1a9641"), QColor("#d7191c"))
    else:
        ramp.invert()  # green for good (small R/f), red for bad
    return ramp


def style_layer(layer, kind, bound=1.0):
    """Renderer for one fdrmesh GeoPackage layer: triangles graduated by R/f(c), boundaries by kind."""
    if kind == "triangles":
        field = "R_over_f"
        # Why: fixed breaks relative to the bound B make 'bad' (R/f > B) a class of its own.
        breaks = [0.0, 0.25 * bound, 0.5 * bound, 0.75 * bound, 0.9 * bound, bound]
        ramp = _ramp()
        ranges = []
        n = len(breaks)
        for i in range(n):
            lo = breaks[i]
            hi = breaks[i + 1] if i + 1 < n else max(2.0 * bound, 1e9)
            sym = QgsSymbol.defaultSymbol(layer.geometryType())
            sym.setColor(ramp.color(i / (n - 1)))
            sym.symbolLayer(0).setStrokeColor(QColor(60, 60, 60, 120))
            sym.symbolLayer(0).setStrokeWidth(0.05)
            label = ("%.3g - %.3g" % (lo, hi)) if i + 1 < n else ("> %.3g (bad)" % lo)
            ranges.append(QgsRendererRange(lo, hi, sym, label))
        renderer = QgsGraduatedSymbolRenderer(field, ranges)
        renderer.setSourceColorRamp(ramp)
        layer.setRenderer(renderer)
    elif kind == "boundaries":
        idx = layer.fields().indexOf("kind")
        values = sorted(str(v) for v in layer.uniqueValues(idx)) if idx >= 0 else []
        cats = []
        for v in values:
            sym = QgsSymbol.defaultSymbol(layer.geometryType())
            sym.setColor(QColor(_BOUNDARY_COLOURS.get(v, "#756bb1")))
            sym.setWidth(0.6 if v == "open" else 0.4)
            cats.append(QgsRendererCategory(v, sym, v))
        layer.setRenderer(QgsCategorizedSymbolRenderer("kind", cats))
    elif kind in ("nodes", "repairs"):
        colour, size = ("#444444", 0.6) if kind == "nodes" else ("#e31a1c", 2.5)
        sym = QgsMarkerSymbol.createSimple({"name": "circle", "color": colour, "size": str(size),
                                             "outline_style": "no"})
        layer.renderer().setSymbol(sym)
    layer.triggerRepaint()


def gpkg_metadata(path):
    """The key/value rows of the fdrmesh GeoPackage's 'metadata' table."""
    try:
        con = sqlite3.connect("file:%s?mode=ro" % path, uri=True)
        try:
            return {k: v for k, v in con.execute("SELECT key, value FROM metadata")}
        finally:
            con.close()
    except sqlite3.Error:
        return {}


def remove_outputs(paths):
    """Deletes the outputs of an aborted run and the CLI's temporary siblings (<target>.tmp-XXXXXX*)."""
    for p in paths:
        if not p:
            continue
        d = os.path.dirname(os.path.abspath(p)) or "."
        base = os.path.basename(p)
        try:
            names = os.listdir(d)
        except OSError:
            continue
        for n in names:
            if n == base or n.startswith(base + ".tmp-"):
                try:
                    os.remove(os.path.join(d, n))
                except OSError:
                    pass


class FdrmeshMeshCoastalAlgorithm(QgsProcessingAlgorithm):
    """Mesh coastal domain (FDR): parameters from `fdrmesh --json-usage`, runs the CLI, loads the results."""

    def __init__(self):
        super().__init__()
        self._status = None
        self._params = []  # (parameter name, option dict, extra) in CLI order

    # ------------------------------------------------------------------ identity
    def name(self):
        return "meshcoastal"

    def displayName(self):
        return "Mesh coastal domain (FDR)"

    def group(self):
        return ""

    def groupId(self):
        return ""

    def createInstance(self):
        return type(self)()

    def status(self):
        if self._status is None:
            self._status = probe()
        return self._status

    def canExecute(self):
        st = self.status()
        return (True, "") if st["ok"] else (False, "fdrmesh is unavailable: " + st["reason"])

    def _help_head(self):
        """The help's first lines: why fdrmesh cannot run, when it cannot."""
        st = self.status()
        return [] if st["ok"] else ["<p><b>fdrmesh is unavailable:</b> %s</p>" % st["reason"]]

    def shortHelpString(self):
        st = self.status()
        lines = self._help_head()
        lines.append("<p>Meshes a coastal water domain with Functional Delaunay Refinement by running "
                     "the <code>fdrmesh mesh</code> command-line tool, and loads the GeoPackage layers "
                     "(nodes, triangles styled by quality, boundaries by kind, repairs) and the 2DM or "
                     "UGRID mesh.</p>")
        if st["ok"]:
            lines.append("<p>Executable: <code>%s</code> (fdrmesh %s)</p>" % (st["exe"], st["version"]))
            group = None
            for _name, opt, _extra in self._params:
                if opt["group"] != group:
                    group = opt["group"]
                    lines.append("<h3>%s</h3>" % group)
                d = (" (default: %s)" % opt["default"]) if opt.get("default") else ""
                lines.append("<p><b>%s</b>: %s%s</p>" % (" / ".join(opt["names"]), opt["help"], d))
        return "\n".join(lines)

    # ------------------------------------------------------------------ parameters
    def initAlgorithm(self, config=None):
        st = self.status()
        if not st["ok"]:
            return
        mesh = next((c for c in st["usage"]["commands"] if c["name"] == "mesh"), None)
        if mesh is None:
            return
        opts = mesh["options"]
        paired_layer_keys = {layer_option_key(opts, o) for o in opts if o["type"] == "vector_in"} - {None}
        common, advanced = [], []
        for opt in opts:
            key = opt["key"]
            if key in _HANDLED_KEYS or key in paired_layer_keys:
                continue
            p = self._make_parameter(opt, opts)
            if p is None:
                continue
            p.setHelp(opt["help"] + ((" (default: %s)" % opt["default"]) if opt.get("default") else ""))
            if key in _COMMON_KEYS or opt.get("required"):
                common.append(p)
            else:
                p.setFlags(p.flags() | QgsProcessingParameterDefinition.FlagAdvanced)
                advanced.append(p)
            self._params.append((p.name(), opt, layer_option_key(opts, opt) if opt["type"] == "vector_in" else None))
        for p in common + advanced:
            self.addParameter(p)
        for name, desc, filt, optional in mesh_outputs(st["usage"]):
            p = QgsProcessingParameterFileDestination(name, desc, filt, optional=optional,
                                                      createByDefault=not optional)
            self.addParameter(p)
        self.addOutput(QgsProcessingOutputNumber("VERTICES", "Number of vertices"))
        self.addOutput(QgsProcessingOutputNumber("TRIANGLES", "Number of triangles"))

    def _make_parameter(self, opt, opts):
        name, t, label = param_name(opt["key"]), opt["type"], _label(opt)
        optional = not opt.get("required", False)
        if t == "vector_in":
            return QgsProcessingParameterFeatureSource(name, label, [QgsProcessing.TypeVectorAnyGeometry],
                                                       optional=optional)
        if t == "raster_in":
            return QgsProcessingParameterRasterLayer(name, label, optional=optional)
        if t == "mesh_in":
            return QgsProcessingParameterFile(name, label, optional=optional)
        if t in ("float", "int"):
            kind = QgsProcessingParameterNumber.Double if t == "float" else QgsProcessingParameterNumber.Integer
            dv = _number_default(opt)
            if dv is not None and t == "int":
                dv = int(dv)
            return QgsProcessingParameterNumber(name, label, kind, defaultValue=dv, optional=optional)
        if t == "flag":
            return QgsProcessingParameterBoolean(name, label, defaultValue=False, optional=True)
        if t == "crs":
            return QgsProcessingParameterCrs(name, label, optional=optional)
        if t == "choice":
            return QgsProcessingParameterEnum(name, label, options=list(opt.get("choices", [])),
                                              optional=optional)
        if t == "bbox":
            return QgsProcessingParameterExtent(name, label, optional=optional)
        if t in ("expr", "string"):
            return QgsProcessingParameterString(name, label, optional=optional)
        if t == "file_out":
            ext = os.path.splitext(opt.get("metavar", ""))[1].lstrip(".")
            filt = ("%s files (*.%s)" % (ext.upper(), ext)) if ext else "All files (*.*)"
            return QgsProcessingParameterFileDestination(name, label, filt, optional=True, createByDefault=False)
        return None  # an option type this plugin does not know is left to the CLI's default

    # ------------------------------------------------------------------ command line
    def build_command(self, parameters, context, feedback):
        """The fdrmesh argument list and the list of mesh output paths for these parameter values."""
        st = self.status()
        args = [st["exe"], "mesh"]
        positional = []
        outputs = {}
        for name, opt, layer_key in self._params:
            if name not in parameters or parameters[name] is None:
                continue
            t, flag = opt["type"], opt["names"][-1]
            value = None
            if t == "vector_in":
                pg = self._postgis_value(parameters, name, context, opt, layer_key)
                if pg:
                    value, extra = pg
                    args += extra
                elif layer_key:
                    path, layer = self.parameterAsCompatibleSourceLayerPathAndLayerName(
                        parameters, name, context, _OGR_FORMATS, "gpkg", feedback)
                else:
                    path, layer = self.parameterAsCompatibleSourceLayerPath(
                        parameters, name, context, _OGR_FORMATS, "gpkg", feedback), ""
                if not pg and not path:
                    continue
                if not pg:
                    value = path
                if not pg and layer_key and layer:
                    lk = next(o for o in self._usage_opts() if o["key"] == layer_key)
                    args += [lk["names"][-1], layer]
            elif t == "raster_in":
                lyr = self.parameterAsRasterLayer(parameters, name, context)
                if lyr is None:
                    continue
                if lyr.providerType() != "gdal":
                    raise QgsProcessingException("%s: raster layer '%s' is not a GDAL file (provider %s)"
                                                 % (name, lyr.name(), lyr.providerType()))
                value = lyr.source()
            elif t == "mesh_in":
                value = self.parameterAsFile(parameters, name, context) or None
            elif t in ("float", "int"):
                v = (self.parameterAsDouble if t == "float" else self.parameterAsInt)(parameters, name, context)
                dv = _number_default(opt)
                if parameters[name] == "" or (dv is not None and v == dv):
                    continue  # the CLI's own default
                value = repr(v) if t == "float" else str(v)
            elif t == "flag":
                if self.parameterAsBoolean(parameters, name, context):
                    args.append(flag)
                continue
            elif t == "crs":
                crs = self.parameterAsCrs(parameters, name, context)
                if not crs.isValid():
                    continue
                value = crs.authid() or crs.toWkt(QgsCoordinateReferenceSystem.WKT2_2019)
            elif t == "choice":
                if parameters[name] == "":
                    continue
                value = opt["choices"][self.parameterAsEnum(parameters, name, context)]
            elif t == "bbox":
                if not parameters[name]:
                    continue
                r = self.parameterAsExtent(parameters, name, context, QgsCoordinateReferenceSystem("EPSG:4326"))
                if r.isNull():
                    continue
                value = "%.10g,%.10g,%.10g,%.10g" % (r.xMinimum(), r.yMinimum(), r.xMaximum(), r.yMaximum())
            elif t in ("expr", "string"):
                value = self.parameterAsString(parameters, name, context).strip() or None
            elif t == "file_out":
                value = self.parameterAsFileOutput(parameters, name, context) or None
                if value:
                    outputs[name] = value
            if value is None:
                continue
            if opt.get("positional"):
                positional.append(value)
            else:
                args += [flag, value]
        for name, _desc, _filt, _optional in mesh_outputs(self.status()["usage"]):
            if parameters.get(name) in (None, ""):
                continue
            path = self.parameterAsFileOutput(parameters, name, context)
            if path:
                outputs[name] = path
                args += ["-o", path]
        if "OUTPUT" not in outputs:
            raise QgsProcessingException("an output GeoPackage (OUTPUT) is required")
        return args[:2] + positional + args[2:], outputs

    def _postgis_value(self, parameters, name, context, opt, layer_key):
        """(connection string, [layer and where options]) for a PostGIS layer fdrmesh can read
        itself, else None (the layer is then exported to a file as any other)."""
        if not layer_key:
            return None  # no option names the table (e.g. --land)
        value = parameters.get(name)
        if isinstance(value, QgsProcessingFeatureSourceDefinition) and value.selectedFeaturesOnly:
            return None  # only QGIS knows the selection
        pg = postgis_source(self.parameterAsVectorLayer(parameters, name, context))
        if pg is None:
            return None
        conn, table, subset = pg
        where_key = "where" if opt.get("positional") else None
        if subset and not where_key:
            return None  # a filtered layer where fdrmesh has no --where: export the filtered features
        opts = {o["key"]: o for o in self._usage_opts()}
        extra = [opts[layer_key]["names"][-1], table]
        if subset:
            extra += [opts[where_key]["names"][-1], subset]
        return conn, extra

    def _usage_opts(self):
        mesh = next(c for c in self.status()["usage"]["commands"] if c["name"] == "mesh")
        return mesh["options"]

    # ------------------------------------------------------------------ run
    def processAlgorithm(self, parameters, context, feedback):
        outputs, rep = self._command_and_report(parameters, context, feedback)
        results = dict(outputs)
        results["VERTICES"] = rep.get("vertices")
        results["TRIANGLES"] = rep.get("triangles")
        self._load_results(parameters, context, feedback, outputs, rep)
        return results

    def _command_and_report(self, parameters, context, feedback):
        """Builds and runs the command, its --report in a temporary file unless REPORT is asked
        for; returns the outputs and the report's JSON."""
        ok, why = self.canExecute()
        if not ok:
            raise QgsProcessingException(why)
        args, outputs = self.build_command(parameters, context, feedback)
        report = outputs.get("REPORT")
        tmp_report = None
        if not report:
            fd, tmp_report = tempfile.mkstemp(prefix="fdrmesh-report-", suffix=".json")
            os.close(fd)
            report = tmp_report
            args += ["--report", report]
        feedback.pushCommandInfo(redact_passwords(" ".join(_quote(a) for a in args)))
        try:
            paths = list(outputs.values())
            # A Selafin output comes with its .cli boundary file beside it.
            paths += [os.path.splitext(p)[0] + ".cli" for p in paths if p.lower().endswith(".slf")]
            self._run(args, paths, feedback)
            with open(report, encoding="utf-8") as f:
                rep = json.load(f)
        finally:
            if tmp_report:
                try:
                    os.remove(tmp_report)
                except OSError:
                    pass
        return outputs, rep

    def _run(self, args, output_paths, feedback):
        """Runs the CLI; ticks -> progress, stdout -> log, cancel -> kill; raises with the ERROR line."""
        try:
            proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL,
                                    start_new_session=True)
        except OSError as e:
            raise QgsProcessingException("cannot start %s: %s" % (args[0], e))
        events = queue.Queue()

        def pump(stream, tag):
            # Why: os.read returns what is there (ticks arrive without a newline), a line reader would wait.
            fd = stream.fileno()
            while True:
                try:
                    chunk = os.read(fd, 4096)
                except OSError:
                    chunk = b""
                if not chunk:
                    break
                events.put((tag, chunk.decode("utf-8", "replace")))
            events.put((tag, None))

        threads = [threading.Thread(target=pump, args=(proc.stdout, "out"), daemon=True),
                   threading.Thread(target=pump, args=(proc.stderr, "err"), daemon=True)]
        for t in threads:
            t.start()
        parser = ProgressParser()
        out_buf = ""
        open_streams = 2
        canceled = False
        while open_streams or proc.poll() is None:
            if feedback.isCanceled():
                canceled = True
                _kill(proc)
                break
            try:
                tag, text = events.get(timeout=0.05)
            except queue.Empty:
                continue
            if text is None:
                open_streams -= 1
                continue
            if tag == "err":
                before = parser.percent
                parser.feed(text)
                if parser.percent is not None and parser.percent != before:
                    feedback.setProgress(parser.percent)
                for m in parser.messages:
                    feedback.pushWarning(m)
                parser.messages.clear()
            else:
                out_buf += text
                while "\n" in out_buf:
                    line, out_buf = out_buf.split("\n", 1)
                    feedback.pushInfo(line)
        if canceled:
            for t in threads:
                t.join(timeout=0.5)
            _close_streams(proc)
            remove_outputs(output_paths)
            raise QgsProcessingException("canceled: fdrmesh (pid %d) was stopped and its partial outputs removed"
                                         % proc.pid)
        proc.wait()
        for t in threads:
            t.join(timeout=1)
        _close_streams(proc)
        while not events.empty():
            tag, text = events.get()
            if text and tag == "err":
                parser.feed(text)
            elif text:
                out_buf += text
        parser.close()
        for line in out_buf.splitlines():
            feedback.pushInfo(line)
        for m in parser.messages:
            feedback.pushWarning(m)
        if proc.returncode != 0:
            remove_outputs(output_paths)
            msg = parser.errors[-1] if parser.errors else "fdrmesh exited with code %d" % proc.returncode
            raise QgsProcessingException(msg)

    def _load_gpkg_layers(self, context, feedback, gpkg, layer_names, bound):
        """The GeoPackage's layers on the map when the algorithm completes, styled (triangles by R/f
        against `bound`, boundaries by kind)."""
        base = os.path.splitext(os.path.basename(gpkg))[0]
        for layer_name in layer_names:
            lyr = QgsVectorLayer("%s|layername=%s" % (gpkg, layer_name), "%s %s" % (base, layer_name), "ogr")
            if not lyr.isValid():
                feedback.pushWarning("%s: layer '%s' could not be opened" % (gpkg, layer_name))
                continue
            style_layer(lyr, layer_name, bound)
            context.temporaryLayerStore().addMapLayer(lyr)
            details = QgsProcessingContext.LayerDetails(lyr.name(), context.project(), "OUTPUT")
            pp = _StylePostProcessor(layer_name, bound)
            _post_processors.append(pp)
            details.setPostProcessor(pp)
            context.addLayerToLoadOnCompletion(lyr.id(), details)

    def _load_results(self, parameters, context, feedback, outputs, rep):
        gpkg = outputs["OUTPUT"]
        meta = gpkg_metadata(gpkg)
        try:
            bound = float(meta.get("bound_B", "") or rep.get("bound_B") or 1.0)
        except ValueError:
            bound = 1.0
        self._load_gpkg_layers(context, feedback, gpkg, ("triangles", "boundaries", "repairs", "nodes"), bound)
        # Why: a .2dm carries no CRS; the coordinates are in --output-crs if given, else the working CRS.
        crs = QgsCoordinateReferenceSystem()
        if parameters.get("OUTPUT_CRS"):
            crs = self.parameterAsCrs(parameters, "OUTPUT_CRS", context)
        if not crs.isValid() and meta.get("crs_wkt"):
            crs = QgsCoordinateReferenceSystem.fromWkt(meta["crs_wkt"])
        for name in ("OUTPUT_2DM", "OUTPUT_UGRID", "OUTPUT_DFLOWFM", "OUTPUT_SELAFIN"):
            path = outputs.get(name)
            if not path:
                continue
            mesh = QgsMeshLayer(path, os.path.basename(path), "mdal")
            if not mesh.isValid():
                feedback.pushWarning("%s could not be opened as a mesh layer" % path)
                continue
            if crs.isValid():
                mesh.setCrs(crs)
            context.temporaryLayerStore().addMapLayer(mesh)
            context.addLayerToLoadOnCompletion(
                mesh.id(), QgsProcessingContext.LayerDetails(mesh.name(), context.project(), name))
            break  # one mesh layer is enough on the map


def _kill(proc):
    """SIGTERM the CLI's process group, SIGKILL after 0.5 s; returns once it is reaped."""
    for sig, wait in ((signal.SIGTERM, 0.5), (signal.SIGKILL, 2.0)):
        try:
            os.killpg(proc.pid, sig)
        except (ProcessLookupError, PermissionError):
            pass
        try:
            proc.wait(timeout=wait)
            return
        except subprocess.TimeoutExpired:
            continue


def _close_streams(proc):
    for s in (proc.stdout, proc.stderr):
        try:
            s.close()
        except OSError:
            pass


def _quote(a):
    return a if re.match(r"^[\w@%+=:,./-]+$", a) else "'" + a.replace("'", "'\\''") + "'"
