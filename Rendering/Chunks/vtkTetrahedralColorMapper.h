/**
 * @class   vtkTetrahedralColorMapper
 * @brief   OpenGL poly data mapper colouring marching cubes surfaces by
 *          tetrahedral interpolation of the 8 cell corner colours
 *
 * Paper Sect. 3.4.1 (after Kasson et al.'s tetrahedral interpolation): the
 * colour of a fragment is interpolated from the 8 corner colours of the
 * marching cubes cell that produced its triangle. The unit cube is split
 * into 6 tetrahedra sharing the main diagonal (0,0,0)-(1,1,1); the fragment's
 * local cell coordinate u = (x,y,z) lies in the tetrahedron selected by the
 * order of x, y, z, and its barycentric weights in that tetrahedron weigh the
 * tetrahedron's 4 corner colours. Unlike the original shader, u is clamped
 * to [0,1]^3 so rounding cannot give negative weights.
 *
 * Input: the output of vtkCornerColorAttributes (un-shared triangles with
 * the `lvdif_cell_local` and `lvdif_corner0..7` point arrays). The mapper
 * binds them with MapDataArrayToVertexAttribute and injects GLSL through the
 * actor's vtkShaderProperty (AddVertexShaderReplacement /
 * AddFragmentShaderReplacement). Lighting stays VTK's.
 *
 * Fallback: ColorMode PerVertex, or an input without those arrays, renders
 * the point array `rgba` as direct per-vertex colours (the shader
 * replacements are removed from the actor).
 *
 * Matcap (SetMatcap): the fragment's colour is the texture that the actor's
 * property holds under the name MatcapTextureName() (see
 * vtkChunkActorManager::SetMatcapTexture), looked up at u,v = n.xy * 0.5 + 0.5
 * with n the view-space normal, times the surface colour (the diffuse colour
 * the colour code above computed); the scene's lights play no part. Without
 * that texture on the property the mapper renders lit as usual.
 */
#ifndef vtkTetrahedralColorMapper_h
#define vtkTetrahedralColorMapper_h

#include "lvdifRenderingChunksModule.h" // for export macro
#include "vtkOpenGLPolyDataMapper.h"

class vtkShaderProperty;

class LVDIFRENDERINGCHUNKS_EXPORT vtkTetrahedralColorMapper : public vtkOpenGLPolyDataMapper
{
public:
  static vtkTetrahedralColorMapper* New();
  vtkTypeMacro(vtkTetrahedralColorMapper, vtkOpenGLPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ColorModes
  {
    Tetrahedral = 0,
    PerVertex = 1
  };
  ///@{
  /// Tetrahedral (default) or PerVertex colours.
  vtkSetClampMacro(InterpolationMode, int, Tetrahedral, PerVertex);
  vtkGetMacro(InterpolationMode, int);
  void SetInterpolationModeToTetrahedral() { this->SetInterpolationMode(Tetrahedral); }
  void SetInterpolationModeToPerVertex() { this->SetInterpolationMode(PerVertex); }
  ///@}

  /// True if the last render used the tetrahedral shader (false: fallback).
  vtkGetMacro(UsedTetrahedral, bool);

  ///@{
  /// Matcap shading (see above); off by default.
  vtkSetMacro(Matcap, bool);
  vtkGetMacro(Matcap, bool);
  ///@}
  /// The property texture name (and GLSL sampler) of the matcap image.
  static const char* MatcapTextureName() { return "lvdifMatcap"; }

  void RenderPiece(vtkRenderer* ren, vtkActor* act) override;

  /// Installs (or with on=false removes) the tetrahedral GLSL on a shader
  /// property. Public so that other mappers of the same data can share it.
  static void InstallShaderReplacements(vtkShaderProperty* property, bool on);
  /// Installs (or removes) the matcap GLSL on a shader property.
  static void InstallMatcapReplacement(vtkShaderProperty* property, bool on);

protected:
  vtkTetrahedralColorMapper();
  ~vtkTetrahedralColorMapper() override = default;

  int InterpolationMode = Tetrahedral;
  bool UsedTetrahedral = false;
  bool Matcap = false;

private:
  vtkTetrahedralColorMapper(const vtkTetrahedralColorMapper&) = delete;
  void operator=(const vtkTetrahedralColorMapper&) = delete;
};

#endif
