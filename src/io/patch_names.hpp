// Names of boundary patches and regions, as the solver formats (SU2 markers, OpenFOAM patches,
// CGNS boundary conditions, Exodus side sets) and Gmsh's $PhysicalNames need them.
//
// A name is 1 to 32 characters from [A-Za-z0-9_], starting with a letter: valid as an SU2
// MARKER_TAG, an OpenFOAM word, a CGNS node name and an Exodus name (32 characters at most) as
// it is, so no writer has to change it. Default names: patch<label> and region<label>
// ("patch_m3" for label -3).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/status.hpp"

namespace anitet {

// Label -> name; labels not listed get the default name.
using PatchNames = std::map<int32_t, std::string>;

// "1=wall,2=farfield" (spaces around items allowed). Error::InvalidArgument, naming the item,
// for a malformed item, a label given twice, a name given twice or an invalid name.
Result<PatchNames> parse_patch_names(const std::string& spec);

// Error::InvalidArgument unless `name` follows the rule above.
Status check_patch_name(const std::string& name);

// Patch names made from free text, such as the names after `solid` in an STL file, which CAD
// exporters fill with part names ("Part1 - Body:1", "1002_tray_bottom"): `texts` maps every
// label of the mesh to its text ("" for none). Each run of characters other than [A-Za-z0-9_]
// becomes one '_' (dropped at either end), a name not starting with a letter gets the prefix
// "patch_", and it is cut to 32 characters; a name already taken (by a smaller label, or as the
// default name of an unnamed label) gets the suffix _2, _3, .... A text with nothing usable
// (only blanks or punctuation) leaves its label unnamed (its default name).
PatchNames patch_names_from_text(const std::map<int32_t, std::string>& texts);

// The name of a label: the given one, else patch<label> (prefix "region" for regions).
std::string patch_name(const PatchNames& names, int32_t label);
std::string region_name(int32_t label);

// The boundary condition a patch stands for, as the solver formats type it (OpenFOAM's boundary
// file, CGNS boundary conditions, Exodus side-set properties):
//   Wall      OpenFOAM wall           CGNS BCWall
//   Inlet     OpenFOAM patch          CGNS BCInflow
//   Outlet    OpenFOAM patch          CGNS BCOutflow
//   Farfield  OpenFOAM patch          CGNS BCFarfield
//   Symmetry  OpenFOAM symmetryPlane  CGNS BCSymmetryPlane  (OpenFOAM symmetry when not planar)
//   Patch     OpenFOAM patch          CGNS BCGeneral        (any other open boundary)
enum class PatchKind { Wall, Inlet, Outlet, Farfield, Symmetry, Patch };
// Label -> kind, overriding the kind the name implies (--patch-types).
using PatchTypes = std::map<int32_t, PatchKind>;

// The kind a name implies, case-insensitive: one containing "inlet" or "inflow" is an inlet,
// "outlet" or "outflow" an outlet, "farfield" a farfield, "symmetry" a symmetry plane; any other
// name a wall.
PatchKind patch_kind(const std::string& name);
// The kind given for `label` in `types`, else the one `name` implies.
PatchKind patch_kind(const PatchTypes& types, int32_t label, const std::string& name);
// "wall", "inlet", "outlet", "farfield", "symmetry", "patch".
const char* patch_kind_name(PatchKind kind);
// "1=wall,2=inlet" (the names above, case-insensitive). Error::InvalidArgument, naming the item,
// for a malformed item, an unknown type or a label given twice.
Result<PatchTypes> parse_patch_types(const std::string& spec);

// The names of the labels actually used by a mesh's boundary triangles, checked: every given
// name valid, every named label used by at least one triangle, no two labels with one name
// (a default name counts too: naming label 2 "patch1" while label 1 keeps its default fails).
// Ordered by increasing label. Each gets its kind (patch_kind(types, label, name)); a label in
// `types` that no triangle has is Error::InvalidArgument too.
struct NamedPatch {
  int32_t label = 0;
  std::string name;
  PatchKind kind = PatchKind::Wall;
};
Result<std::vector<NamedPatch>> named_patches(const std::vector<int32_t>& labels, const PatchNames& names,
                                              const PatchTypes& types = {});

// Entity ids for labels, as Gmsh tags and Exodus ids need positive numbers: the labels
// themselves when all are positive, else 1, 2, ... in increasing label order.
std::map<int32_t, int32_t> positive_ids(const std::vector<int32_t>& sorted_unique_labels);

}  // namespace anitet
