// Writers of 3D meshes (tet::TetMesh): VTU, Gmsh MSH 4.1 (ASCII) and TetGen .node/.ele/.face.
// Every writer is all-or-nothing (base/out_file.hpp): on any error nothing is left at the target.
#pragma once
#include <string>
#include <vector>
#include "tet/tet_mesh.hpp"

namespace fdr::tetio {

// How the VTU's arrays are stored: raw bytes in an <AppendedData> block (compact; ParaView, VTK,
// meshio), or base64 inside each <DataArray> (plain XML, readable without a VTK library).
enum class VtuEncoding { kAppendedRaw, kBase64 };

// VTU (XML UnstructuredGrid, little endian, UInt64 headers): points, tetrahedra (cell type 10),
// cell data "material" (Int32) and every cell_fields entry (Float64).
void write_vtu(const std::string& path, const tet::TetMesh& mesh, VtuEncoding encoding = VtuEncoding::kAppendedRaw);

// Gmsh MSH 4.1 ASCII: one volume entity and physical group per material (tetrahedra), one surface
// entity and physical group per face marker (triangles), one curve entity and group per edge
// marker (lines). Group names come from material_names / marker_names when given there, else
// "material_<m>" / "marker_<m>". Physical tags are the materials and markers themselves when all
// are >= 1 (Gmsh's tags are positive), else shifted by 1 - (smallest) so that they are.
void write_msh(const std::string& path, const tet::TetMesh& mesh);

// TetGen: BASE.node, BASE.ele (material as the one attribute), BASE.face (with markers), and
// BASE.edge when the mesh has subsegments; 1-based like TetGen's own output. `path` is BASE or
// BASE.node / BASE.ele. Tetrahedra keep their positive-volume order: TetGen 1.5 writes its own
// .ele files that way (every tetrahedron of its meshes of testdata/3d has
// dot(b - a, cross(c - a, d - a)) > 0; tools/verify/test_tets.py checks it).
void write_tetgen(const std::string& path, const tet::TetMesh& mesh);

// The writer for the extension: .vtu, .msh, or .node/.ele (TetGen). Unknown extension:
// Error(kUsage).
void write_tets(const std::string& path, const tet::TetMesh& mesh);
bool is_tets_output_path(const std::string& path);

// Several outputs of one mesh (each by extension as write_tets) committed as one: when any of them
// fails, none is left, not even those whose files were complete.
void write_tets_all(const std::vector<std::string>& paths, const tet::TetMesh& mesh,
                    VtuEncoding encoding = VtuEncoding::kAppendedRaw);

// Throws Error(kInternal) when the mesh's arrays disagree (a per-tetrahedron array of the wrong
// length, a vertex id out of range): a bug upstream, caught before anything is written.
void check_mesh_arrays(const tet::TetMesh& mesh);

}  // namespace fdr::tetio
