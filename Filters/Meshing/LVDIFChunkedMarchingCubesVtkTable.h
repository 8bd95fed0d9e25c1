/**
 * @file   LVDIFChunkedMarchingCubesVtkTable.h
 * @brief  VTK's marching cubes case table in lvdif's numbering
 *
 * Internal to vtkChunkedMarchingCubes. VTK's table
 * (vtkMarchingCubesTriangleCases::GetCases(), used by vtkMarchingCubes and
 * vtkFlyingEdges3D) is read at run time and converted:
 * - vertices: VTK's cell vertex v sits at (x, y, z) = (0,0,0), (1,0,0), (1,1,0),
 *   (0,1,0), (0,0,1), (1,0,1), (1,1,1), (0,1,1) for v = 0..7 (vtkMarchingCubes'
 *   order, that of vtkHexahedron); lvdif's corner is x + 2y + 4z;
 * - edges: VTK's edge k joins vertices (0,1) (1,2) (3,2) (0,3) (4,5) (5,6)
 *   (7,6) (4,7) (0,4) (1,5) (3,7) (2,6); lvdif's edge ids are 4*axis + 2*bu + bv
 *   (MarchingCubesTables.h);
 * - case index: bit v of VTK's case is bit corner(v) of ours (both: value >= iso);
 * - orientation: VTK's triangles are reversed (VTK lists them clockwise seen
 *   from the above side; lvdif wants counter-clockwise).
 * The result is then checked by lvdif::marchingCubesTablesWith (same loops),
 * and Filters/Meshing/Testing checks it against vtkMarchingCubes on all 256
 * single-cell images.
 */
#ifndef LVDIFChunkedMarchingCubesVtkTable_h
#define LVDIFChunkedMarchingCubesVtkTable_h

#include "lvdifFiltersMeshingModule.h"

#include "lvdif/MarchingCubesTables.h"

#include <memory>

namespace LVDIFChunkedMarchingCubesVtkTable
{
/// VTK's table converted to lvdif's numbering (computed once; thread-safe).
LVDIFFILTERSMESHING_EXPORT std::shared_ptr<const lvdif::MarchingCubesTriangleTable> Get();
}

#endif
