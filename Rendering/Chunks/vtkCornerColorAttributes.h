/**
 * @class   vtkCornerColorAttributes
 * @brief   un-shares triangle vertices and turns the per-triangle marching
 *          cubes cell colours into per-vertex attributes for the
 *          tetrahedral colour shader
 *
 * Input: triangles with cell data `corner_rgba` (unsigned char, 32
 * components: the RGBA of the 8 corners of the marching cubes cell the
 * triangle came from, corner c at offset (c&1, (c>>1)&1, (c>>2)&1)) and
 * `cell_ijk` (int, 3 components: the cell's lowest voxel index). Origin and
 * Spacing are the volume's (world position of voxel (0,0,0), voxel size).
 *
 * Output: every triangle gets its own 3 points (polygons with more points are
 * fanned). Point data keeps the input's point arrays (Normals, rgba, ...) and
 * adds
 * - `lvdif_cell_local` (float, 3): the vertex position in the cell's local
 *   coordinates, (P - origin - ijk*spacing) / spacing, nominally in [0,1]^3.
 *   It is affine in P, so the rasteriser's interpolation gives every
 *   fragment its exact local coordinate (no barycentric reconstruction as in
 *   the original Unity shader).
 * - `lvdif_corners_packed0` .. `lvdif_corners_packed2` (float, 4): the 32
 *   bytes of the corner colours, equal on the triangle's three vertices,
 *   packed 3 to a float (byte i at float i/3, times 256^(i%3): below 2^24,
 *   exact; PackCorners/UnpackCorners): 3 vertex attributes instead of 8,
 *   which is what software OpenGL's vertex stage pays for.
 *
 * For marching cubes' meshes (float points, int cell_ijk, triangles only) the
 * output points' ranges are cached in their array (vtkDataArray::GetRange
 * finds them), as the vertex buffer upload asks for them.
 *
 * Triangle order (SpatialOrder): off (default), the output triangles follow
 * the input's polygons; on, they follow the Morton (Z-order) code of their
 * cells' cell_ijk, input order among equal codes, a polygon's fan triangles
 * together. Consecutive triangles then lie close together, which is what
 * vtkTetrahedralColorMapper's draw ranges need to skip the triangles outside
 * a partial redraw's scissor box (a marching cubes scan order gives ranges
 * that are long rows through the chunk).
 *
 * Memory: the GPU needs per-vertex attributes, and a vertex shared by
 * several triangles would need several corner sets, hence un-sharing. An
 * indexed marching cubes mesh has about T/2 points for T triangles (28 bytes
 * each with float position+normal and rgba) plus 12 bytes of indices per
 * triangle, ~26 B/triangle; the output holds 3 points per triangle of
 * 12 (position) + 12 (normal) + 4 (rgba) + 12 (local) + 48 (packed corners)
 * bytes, 264 B/triangle (+ 12 B of connectivity), about 10x more.
 */
#ifndef vtkCornerColorAttributes_h
#define vtkCornerColorAttributes_h

#include "lvdifRenderingChunksModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

class LVDIFRENDERINGCHUNKS_EXPORT vtkCornerColorAttributes : public vtkPolyDataAlgorithm
{
public:
  static vtkCornerColorAttributes* New();
  vtkTypeMacro(vtkCornerColorAttributes, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// World position of voxel (0,0,0) and the voxel size of the volume the mesh came from.
  vtkSetVector3Macro(Origin, double);
  vtkGetVector3Macro(Origin, double);
  vtkSetVector3Macro(Spacing, double);
  vtkGetVector3Macro(Spacing, double);
  ///@}

  ///@{
  /// Output triangles in the Morton order of their cells (see above); off by default.
  vtkSetMacro(SpatialOrder, bool);
  vtkGetMacro(SpatialOrder, bool);
  vtkBooleanMacro(SpatialOrder, bool);
  ///@}

  /// The Morton (Z-order) code of a cell index: the bits of i, j, k (21 each) interleaved.
  static unsigned long long MortonCode(int i, int j, int k);

  /// Names of the output point arrays (shared with vtkTetrahedralColorMapper).
  static const char* LocalArrayName() { return "lvdif_cell_local"; }
  static const char* PackedCornerArrayName(int i);
  /// The packing of the 8 corners' RGBA (corner_rgba's 32 bytes) into 12 floats, and back.
  static void PackCorners(const unsigned char rgba[32], float packed[12]);
  static void UnpackCorners(const float packed[12], unsigned char rgba[32]);

  /// True if the poly data carries the input contract (corner_rgba + cell_ijk cell arrays).
  static bool HasCornerColors(vtkPolyData* pd);

protected:
  vtkCornerColorAttributes();
  ~vtkCornerColorAttributes() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double Origin[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
  bool SpatialOrder = false;

private:
  vtkCornerColorAttributes(const vtkCornerColorAttributes&) = delete;
  void operator=(const vtkCornerColorAttributes&) = delete;
};

#endif
