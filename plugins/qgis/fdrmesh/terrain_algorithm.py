# Processing algorithm "Mesh terrain volume (FDR)": the terrain volume of `fdrmesh mesh DOMAIN --dem`.
"""Runs ``fdrmesh mesh DOMAIN --dem DEM --base Z --horizon H ... -o model.vtu`` (docs/terrain3d.md)
with the coastal algorithm's executable lookup, progress, cancel and error handling, and loads the
top surface GeoPackage (triangles styled by R/f, the outline of the side walls, nodes with the
DEM's elevation) when one is asked for.  The tetrahedra (VTU, Gmsh msh) are files for the modeller's
tools: QGIS has no layer type for them."""

from qgis.core import (
    QgsProcessing,
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterDefinition,
    QgsProcessingParameterFeatureSource,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterMultipleLayers,
    QgsProcessingParameterNumber,
    QgsProcessingParameterRasterLayer,
    QgsProcessingParameterString,
)

from .fdrmesh_algorithm import _OGR_FORMATS, FdrmeshMeshCoastalAlgorithm, gpkg_metadata

# (parameter, CLI option, label, advanced): the numbers the CLI takes; left empty, the CLI's default.
_NUMBERS = [
    ("HMIN", "--hmin", "Minimum element size hmin (m)", False),
    ("HMAX", "--hmax", "Maximum element size hmax (m)", False),
    ("VERTICAL_TOL", "--vertical-tol", "Vertical tolerance of the top TIN against the DEM (m)", False),
    ("DEPTH_GRADE", "--depth-grade", "Spacing growth per metre of depth below the DEM (default 0.25)", True),
    ("MIN_THICKNESS", "--min-thickness", "Layers thinner than this collapse (m; default: 0.15 x HMIN, at least the vertical tolerance; 0 keeps every layer)", True),
    ("WELL_SPACING", "--well-spacing", "Element size along the wells (m; default hmin)", False),
    ("GRADATION", "--gradation", "Gradation of the spacing (Lipschitz constant)", True),
    ("BOUND", "--bound", "Refinement bound B on R/f(c) (default: the 3D default)", True),
]
# (parameter, description, file filter, optional): -o outputs, the format from the extension.
_OUTPUTS = [
    ("OUTPUT_VTU", "Output volume mesh (VTU: tetrahedra with material, quality)", "VTK unstructured grid (*.vtu)", False),
    ("OUTPUT_MSH", "Output Gmsh MSH 4.1 (physical groups top, base, side, horizons, layers)", "Gmsh mesh (*.msh)", True),
    ("OUTPUT", "Output top surface GeoPackage (TIN with elevations, outline, wells, layer names)", "GeoPackage (*.gpkg)",
     True),
]


class FdrmeshTerrainVolumeAlgorithm(FdrmeshMeshCoastalAlgorithm):
    """Mesh terrain volume (FDR): a domain polygon x a DEM down to a base, cut by horizon rasters."""

    def name(self):
        return "meshterrain"

    def displayName(self):
        return "Mesh terrain volume (FDR)"

    def shortHelpString(self):
        lines = self._help_head()
        lines.append("<p>Tetrahedralizes the volume under a DEM with Functional Delaunay Refinement "
                     "(<code>fdrmesh mesh DOMAIN --dem DEM --base Z --horizon H ...</code>): the domain "
                     "polygon's TIN of the DEM is the top (without a domain polygon, the box of the DEM's valid data), the base an elevation or a raster, each horizon "
                     "raster (from the top down) cuts a layer; layer i from the top is material i; wells are "
                     "vertical segments refined to the well spacing. "
                     "Writes VTU and Gmsh MSH, and loads the top surface GeoPackage.</p>")
        return "\n".join(lines)

    def initAlgorithm(self, config=None):
        if not self.status()["ok"]:
            return
        self.addParameter(QgsProcessingParameterFeatureSource(
            "INPUT", "Domain polygon (empty: the box of the DEM's valid data)", [QgsProcessing.TypeVectorPolygon],
            optional=True))
        self.addParameter(QgsProcessingParameterRasterLayer("DEM", "DEM (the top surface)"))
        self.addParameter(QgsProcessingParameterString("BASE", "Base elevation (m)", defaultValue="-500",
                                                       optional=True))
        self.addParameter(QgsProcessingParameterRasterLayer(
            "BASE_RASTER", "Base raster (instead of the base elevation)", optional=True))
        self.addParameter(QgsProcessingParameterMultipleLayers(
            "HORIZONS", "Horizon rasters, from the top down", QgsProcessing.TypeRaster, optional=True))
        self.addParameter(QgsProcessingParameterFeatureSource(
            "WELLS", "Wells (points with top/bottom or depth_from/depth_to fields, or 3D lines)",
            [QgsProcessing.TypeVectorPoint, QgsProcessing.TypeVectorLine], optional=True))
        for name, _flag, label, advanced in _NUMBERS:
            p = QgsProcessingParameterNumber(name, label, QgsProcessingParameterNumber.Double, optional=True)
            if advanced:
                p.setFlags(p.flags() | QgsProcessingParameterDefinition.FlagAdvanced)
            self.addParameter(p)
        p = QgsProcessingParameterFeatureSource("BREAKLINES", "Breaklines (mesh edges of the top)",
                                                [QgsProcessing.TypeVectorLine], optional=True)
        p.setFlags(p.flags() | QgsProcessingParameterDefinition.FlagAdvanced)
        self.addParameter(p)
        self.addParameter(QgsProcessingParameterBoolean("CHECK", "Check the mesh (--check)", defaultValue=False))
        for name, desc, filt, optional in _OUTPUTS:
            self.addParameter(QgsProcessingParameterFileDestination(name, desc, filt, optional=optional,
                                                                    createByDefault=not optional))
        self.addParameter(QgsProcessingParameterFileDestination(
            "REPORT", "Report (JSON, with the layers' volumes)", "JSON files (*.json)", optional=True,
            createByDefault=False))
        self.addOutput(QgsProcessingOutputNumber("VERTICES", "Number of vertices"))
        self.addOutput(QgsProcessingOutputNumber("TETRAHEDRA", "Number of tetrahedra"))

    def _raster_path(self, parameters, name, context):
        lyr = self.parameterAsRasterLayer(parameters, name, context)
        if lyr is None:
            return None
        if lyr.providerType() != "gdal":
            raise QgsProcessingException("%s: raster layer '%s' is not a GDAL file (provider %s)"
                                         % (name, lyr.name(), lyr.providerType()))
        return lyr.source()

    def _vector_args(self, parameters, name, context, feedback, flag, layer_flag):
        path, layer = self.parameterAsCompatibleSourceLayerPathAndLayerName(
            parameters, name, context, _OGR_FORMATS, "gpkg", feedback)
        if not path:
            return [], []
        return ([flag, path] if flag else [path]), ([layer_flag, layer] if layer and layer_flag else [])

    def build_command(self, parameters, context, feedback):
        """The fdrmesh argument list and the output paths for these parameter values."""
        args = [self.status()["exe"], "mesh"]
        domain, layer = [], []
        if parameters.get("INPUT"):
            domain, layer = self._vector_args(parameters, "INPUT", context, feedback, None, "--layer")
        args += domain + layer + ["--dem", self._raster_path(parameters, "DEM", context)]
        base = self._raster_path(parameters, "BASE_RASTER", context) if parameters.get("BASE_RASTER") else None
        if base is None:
            base = self.parameterAsString(parameters, "BASE", context).strip()
        if not base:
            raise QgsProcessingException("give a base elevation (BASE) or a base raster (BASE_RASTER)")
        args += ["--base", base]
        for lyr in self.parameterAsLayerList(parameters, "HORIZONS", context) or []:
            if lyr.providerType() != "gdal":
                raise QgsProcessingException("HORIZONS: raster layer '%s' is not a GDAL file" % lyr.name())
            args += ["--horizon", lyr.source()]
        for name, flag, _label, _adv in _NUMBERS:
            if parameters.get(name) not in (None, ""):
                args += [flag, repr(self.parameterAsDouble(parameters, name, context))]
        if parameters.get("BREAKLINES"):
            lines, line_layer = self._vector_args(parameters, "BREAKLINES", context, feedback, "--breaklines",
                                                  "--breaklines-layer")
            args += lines + line_layer
        if parameters.get("WELLS"):
            wells, wells_layer = self._vector_args(parameters, "WELLS", context, feedback, "--wells", "--wells-layer")
            args += wells + wells_layer
        if self.parameterAsBoolean(parameters, "CHECK", context):
            args.append("--check")
        outputs = {}
        for name, _desc, _filt, _optional in _OUTPUTS + [("REPORT", "", "", True)]:
            if parameters.get(name) in (None, ""):
                continue
            path = self.parameterAsFileOutput(parameters, name, context)
            if path:
                outputs[name] = path
                args += ["--report", path] if name == "REPORT" else ["-o", path]
        if "OUTPUT_VTU" not in outputs:
            raise QgsProcessingException("an output volume mesh (OUTPUT_VTU) is required")
        return args, outputs

    def processAlgorithm(self, parameters, context, feedback):
        outputs, rep = self._command_and_report(parameters, context, feedback)
        for layer in rep.get("layers", []):
            feedback.pushInfo("layer %d %s: %d tetrahedra, %.6g m3 (expected %.6g m3)"
                              % (layer["material"], layer["name"], layer["tets"], layer["volume"],
                                 layer["expected_volume"]))
        results = dict(outputs)
        counts = rep.get("counts", {})
        results["VERTICES"] = counts.get("vertices")
        results["TETRAHEDRA"] = counts.get("tetrahedra")
        if "OUTPUT" in outputs:
            self._load_top(context, feedback, outputs["OUTPUT"], bool(parameters.get("WELLS")))
        return results

    def _load_top(self, context, feedback, gpkg, wells=False):
        """The top surface GeoPackage's layers on the map, styled as the coastal algorithm's."""
        try:
            bound = float(gpkg_metadata(gpkg).get("bound_B", "") or 1.0)
        except ValueError:
            bound = 1.0
        names = ("triangles", "boundaries", "nodes") + (("wells",) if wells else ())
        self._load_gpkg_layers(context, feedback, gpkg, names, bound)
